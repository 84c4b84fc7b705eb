#!/usr/bin/python3
"""`sdgbehave new-behavior` writes a starter script and a scene that run as
is (timeline and event-driven templates), that describe lists with its
variables, and that a second call does not overwrite; a bad name exits 2.

usage: check_new_behavior.py SDGBEHAVE"""
import json
import os
import subprocess
import sys
import tempfile

from checklib import check, finish


def sdg(binary, *args, cwd):
    return subprocess.run([binary, *args], capture_output=True, text=True, cwd=cwd, timeout=300)


def main():
    binary = os.path.abspath(sys.argv[1])
    with tempfile.TemporaryDirectory() as tmp:
        for name, stem, flags in (("randomScale", "random_scale", []), ("dropper", "dropper", ["--events"])):
            made = sdg(binary, "new-behavior", name, "--out", "mine", *flags, cwd=tmp)
            check(made.returncode == 0, f"new-behavior {name}: {made.returncode} {made.stderr}")
            script, scene = f"mine/{stem}.py", f"mine/{stem}.yaml"
            check(os.path.isfile(os.path.join(tmp, script)) and os.path.isfile(os.path.join(tmp, scene)),
                  f"{name}: files missing")
            run = sdg(binary, "run", scene, "--frames", "3", "--resolution", "64x64", "--out", f"out_{stem}", cwd=tmp)
            check(run.returncode == 0, f"run {scene}: {run.returncode} {run.stderr[-800:]}")
            check(os.path.isfile(os.path.join(tmp, f"out_{stem}", "rgb_0002.png")), f"{name}: no third frame")
            described = sdg(binary, "describe", name, "--script", script, "--format", "json", cwd=tmp)
            check(described.returncode == 0, f"describe {name}: {described.stderr}")
            if described.returncode == 0:
                spec = json.loads(described.stdout)["behaviors"][0]
                check(spec["source"] == script, f"{name}: source {spec['source']}")
                check(all(v["doc"] for v in spec["variables"]), f"{name}: a variable without doc")
            again = sdg(binary, "new-behavior", name, "--out", "mine", *flags, cwd=tmp)
            check(again.returncode == 2 and "exists already; pass --overwrite" in again.stderr,
                  f"{name}: a second call gave {again.returncode} {again.stderr}")
        bad = sdg(binary, "new-behavior", "Random-Scale", cwd=tmp)
        check(bad.returncode == 2 and "camelCase identifier" in bad.stderr, f"bad name: {bad.returncode} {bad.stderr}")
    return finish("both templates run as written; no overwrite; bad names refused")


if __name__ == "__main__":
    sys.exit(main())
