#!/usr/bin/python3
"""Isaac's way of attaching behavior scripts, `omni:scripting:scripts` with `exposedVar:` values, on a YAML
prim and on a USD prim: an existing file runs through the Isaac layer (the user's file is the truth); a
missing file named like one of Isaac's six gets the built-in with one note per run; --isaac-scripts and
run.isaac_scripts force either way; inspect, --set and the JSON Schema see the script's variables.

usage: check_isaac_attach.py SDGBEHAVE SCENE_DIR SHARED_DIR"""
import json
import os
import subprocess
import sys
import tempfile

from checklib import check, finish

LAYER_NOTE = "the Isaac Sim script"        # log line: an Isaac script stands in for the built-in
BUILTIN_NOTE = "not found, the built-in"   # log line: the built-in stands in for a missing file


def sdg(binary, *args, code=0):
    p = subprocess.run([binary, *args], capture_output=True, text=True, timeout=120)
    check(p.returncode == code, f"sdgbehave {' '.join(args)} exited {p.returncode} (expected {code}): "
                                f"{p.stderr.strip()[-800:]}")
    return p


def locations(binary, scene, tmp, *flags):
    record = os.path.join(tmp, "record.jsonl")
    p = sdg(binary, "run", scene, "--out", os.path.join(tmp, "out"), "--no-render", "--frames", "40", "--record",
            record, *flags)
    xs = []
    with open(record) as f:
        for line in f:
            entry = json.loads(line)
            if "frame" in entry:
                xs += [c["value"] for c in entry["changes"]
                       if c["attribute"] == "xformOp:translate" and c["prim"] == "/World/Box"]
    return p, xs


def in_range(xs):
    lo, hi = (0.5, 1.5, 3.0), (1.5, 2.5, 3.2)  # translate [1, 2, 3] + the exposed range
    return len(xs) == 40 and all(lo[i] - 1e-9 <= v[i] <= hi[i] + 1e-9 for v in xs for i in range(3))


def main():
    binary, scenes, shared = sys.argv[1:4]
    if not os.path.isdir(os.path.join(shared, "isaacsim", "replicator", "behavior")):
        print(f"skipped: Isaac Sim's behavior scripts are not at {shared}")
        return 77
    attached, missing = os.path.join(scenes, "attached.yaml"), os.path.join(scenes, "attached_missing.yaml")
    with tempfile.TemporaryDirectory() as tmp:
        # An existing file runs through the layer, with the prim's exposedVar: values.
        p, xs = locations(binary, attached, tmp)
        check(LAYER_NOTE in p.stderr, f"attached.yaml: no line saying Isaac's script runs: {p.stderr[-400:]}")
        check(in_range(xs), f"attached.yaml: {len(xs)} locations, not all within the exposed range: {xs[:3]}")
        # The same on a USD prim.
        p, xs = locations(binary, os.path.join(scenes, "attached.usda"), tmp)
        check(LAYER_NOTE in p.stderr, f"attached.usda: no line saying Isaac's script runs: {p.stderr[-400:]}")
        check(in_range(xs), f"attached.usda: {len(xs)} locations, not all in range: {xs[:3]}")
        # Forced to the built-in: the file is not loaded.
        p, xs = locations(binary, attached, tmp, "--isaac-scripts", "builtin")
        check(LAYER_NOTE not in p.stderr, "--isaac-scripts builtin still ran Isaac's file")
        check(in_range(xs), "--isaac-scripts builtin: locations not in range")
        # A missing file named like one of the six: the built-in, one note for the whole run.
        p, xs = locations(binary, missing, tmp)
        check(p.stderr.count(BUILTIN_NOTE) == 1, f"expected one note for the missing files: {p.stderr[-600:]}")
        check(in_range(xs), "attached_missing.yaml: locations not in range")
        # ... unless the file is required.
        p = sdg(binary, "validate", missing, "--isaac-scripts", "script", code=2)
        check("attached_missing.yaml:11:" in p.stderr and "not found" in p.stderr,
              f"--isaac-scripts script: expected a located 'not found': {p.stderr[-400:]}")
        # The setting says the same as the flag.
        forced = os.path.join(scenes, ".forced_script.yaml")
        try:
            with open(missing) as f:
                text = f.read()
            with open(forced, "w") as f:
                f.write(text.replace("version: 1\n", "version: 1\nrun: {isaac_scripts: script}\n"))
            p = sdg(binary, "validate", forced, code=2)
            check("not found" in p.stderr, f"run.isaac_scripts: script: {p.stderr[-300:]}")
        finally:
            os.remove(forced)
        # inspect and --set see the script's variables.
        p = sdg(binary, "inspect", attached, "--set", "/World/Box.exposedVar:locationRandomizer:interval=3")
        check("locationRandomizer" in p.stdout and "interval" in p.stdout and "3" in p.stdout,
              f"inspect does not show the script's variables: {p.stdout[-600:]}")
        p = sdg(binary, "validate", attached, "--set", "/World/Box.exposedVar:locationRandomizer:intervall=3", code=2)
        check("did you mean" in p.stderr, f"--set of a misspelt variable: {p.stderr[-300:]}")
        # A misspelt exposedVar: key is located.
        bad = os.path.join(scenes, ".bad_key.yaml")
        try:
            with open(bad, "w") as f:
                f.write(text.replace("exposedVar:locationRandomizer:includeChildren",
                                     "exposedVar:locationRandomizer:includeChildre"))
            p = sdg(binary, "validate", bad, code=2)
            check(".bad_key.yaml:14:" in p.stderr and "did you mean" in p.stderr, f"bad key: {p.stderr[-300:]}")
        finally:
            os.remove(bad)
        # The JSON Schema accepts the keys.
        schema = json.loads(sdg(binary, "schema").stdout)
        cube = schema["definitions"]["primCube"]["properties"]
        check("omni:scripting:scripts" in cube and "exposedVar:locationRandomizer:range:minPosition" in cube,
              "the schema's Cube lacks omni:scripting:scripts / exposedVar: keys")
    return finish("omni:scripting:scripts: files run through the layer (YAML, USD), built-ins stand in for missing "
                  "ones (one note), --isaac-scripts and run.isaac_scripts force; inspect/--set/schema see them")


if __name__ == "__main__":
    sys.exit(main())
