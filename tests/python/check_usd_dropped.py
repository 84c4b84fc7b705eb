#!/usr/bin/python3
"""What a scene's USD files have that the stage does not carry over is said
once per kind of loss, with a count and the first place, by validate,
inspect and run (text and JSON logs, run_summary.json); validate --strict
fails on it. A run warns once when no prim is labelled and when a frame is
black.

usage: check_usd_dropped.py SDGBEHAVE SOURCE_DIR"""
import json
import os
import subprocess
import sys
import tempfile

from checklib import check, finish


def run(binary, *args, cwd=None):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=300, cwd=cwd)


def main():
    binary, source = os.path.abspath(sys.argv[1]), sys.argv[2]
    stage = os.path.join(source, "tests/data/usd/dropped/losses.usda")
    expected = [
        ("losses.usda:24:5: warning: dropped: 2 prims of type BasisCurves (first /World/Hair1)", "prim_type", "BasisCurves", 2),
        ("losses.usda:36:5: warning: dropped: 1 prim of type FooBar (/World/Unknown)", "prim_type", "FooBar", 1),
        ("losses.usda:65:5: warning: dropped: applied schema ShapingAPI on 1 prim (/World/Spot)", "applied_schema", "ShapingAPI", 1),
        ("warning: dropped: 1 material with ", "material_network", None, 1),
    ]
    for command in (["validate"], ["inspect"]):
        r = run(binary, *command, stage)
        check(r.returncode == 0, f"{command[0]}: exit {r.returncode}\n{r.stderr}")
        for text, _, _, _ in expected:
            check(r.stderr.count(text) == 1, f"{command[0]}: stderr should say once: {text}\n{r.stderr}")
    r = run(binary, "validate", stage)
    check("4 kinds of content dropped" in r.stdout, f"validate's line counts the losses: {r.stdout}")

    strict = run(binary, "validate", "--strict", stage)
    check(strict.returncode == 2, f"validate --strict: exit {strict.returncode}, expected 2")
    check("invalid under --strict" in strict.stdout, f"validate --strict says why: {strict.stdout}")
    clean = run(binary, "validate", "--strict", os.path.join(source, "tests/data/usd/cube_camera.usda"))
    check(clean.returncode == 0 and "dropped" not in clean.stderr,
          f"a stage read whole passes --strict: exit {clean.returncode}\n{clean.stderr}")

    js = run(binary, "--log-format", "json", "validate", stage)
    drops = [json.loads(line) for line in js.stderr.splitlines() if line.startswith("{")]
    drops = [d for d in drops if "dropped" in d]
    check(len(drops) == 4, f"JSON log: 4 dropped objects, found {len(drops)}\n{js.stderr}")
    for _, kind, what, count in expected:
        match = [d for d in drops if d["dropped"]["kind"] == kind and (what is None or d["dropped"]["what"] == what)]
        check(len(match) == 1 and match[0]["dropped"]["count"] == count and match[0]["file"].endswith("losses.usda"),
              f"JSON log: {kind} {what} x{count}: {match}")

    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "ds")
        r = run(binary, "run", stage, "--frames", "1", "--resolution", "64x64", "--out", out)
        check(r.returncode == 0, f"run: exit {r.returncode}\n{r.stderr}")
        check(r.stderr.count("prims of type BasisCurves") == 1, f"run says each loss once:\n{r.stderr}")
        summary = json.load(open(os.path.join(out, "run_summary.json")))
        kinds = sorted(d["kind"] for d in summary.get("dropped", []))
        check(kinds == ["applied_schema", "material_network", "prim_type", "prim_type"],
              f"run_summary.json dropped: {summary.get('dropped')}")

        dark = os.path.join(source, "tests/data/usd/dropped/dark_unlabelled.yaml")
        out = os.path.join(tmp, "dark")
        r = run(binary, "run", dark, "--out", out)
        check(r.returncode == 0, f"dark run: exit {r.returncode}\n{r.stderr}")
        check(r.stderr.count("no prim on the stage has a semantic label") == 1, f"no-label warning once:\n{r.stderr}")
        check(r.stderr.count("is black (over 99.5 % of its pixels)") == 1, f"black-frame warning once:\n{r.stderr}")
        check("camera /World/Camera" in r.stderr and "1 light (/World/Lamp)" in r.stderr,
              f"the black-frame warning names the camera and its lights:\n{r.stderr}")
        summary = json.load(open(os.path.join(out, "run_summary.json")))
        check(len(summary.get("warnings", [])) == 2, f"run_summary.json warnings: {summary.get('warnings')}")

        lit = os.path.join(source, "tests/data/usd/cube_camera.usda")
        r = run(binary, "run", lit, "--frames", "1", "--resolution", "64x64", "--out", os.path.join(tmp, "lit"))
        check(r.returncode == 0 and "is black" not in r.stderr and "semantic label" not in r.stderr,
              f"a lit, labelled stage warns of neither:\n{r.stderr}")
    return finish("usd dropped: ok")


if __name__ == "__main__":
    sys.exit(main())
