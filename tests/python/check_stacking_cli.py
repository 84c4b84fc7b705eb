#!/usr/bin/python3
"""Stacking from the command line: --save-stage writes a scene that reloads
with the stacks in place (and no events), so rendering it gives the same
image; renderSimulation writes one image per physics step; an unsettled
stack with physics.require_settled exits 1 naming the surface."""
import glob
import os
import subprocess
import sys
import tempfile

import yaml
from PIL import Image


from checklib import check, failures, finish


def main():
    binary, scene = (os.path.abspath(a) for a in sys.argv[1:3])
    small = ["--resolution", "64x64"]
    with tempfile.TemporaryDirectory() as tmp:
        saved = os.path.join(tmp, "stacked.yaml")
        subprocess.run([binary, "run", scene, "--out", f"{tmp}/a", *small, "--save-stage", saved], check=True,
                       capture_output=True)
        doc = yaml.safe_load(open(saved))
        check("events" not in doc, "the saved scene still has its events")
        stacked = [p for p in doc["prims"] if p.startswith("/Behaviors/volumeStackRandomizer/Assets/")]
        check(len(stacked) >= 2 + 6 * 2, f"the saved scene has {len(stacked)} stacked prims")
        check(all(os.path.isabs(r) for r in doc.get("asset_roots", [])), "asset roots are not absolute")
        # From another working directory, the saved scene renders the same stacks.
        subprocess.run([binary, "run", saved, "--out", f"{tmp}/b", *small], check=True, capture_output=True, cwd="/")
        a = open(f"{tmp}/a/rgb_0000.png", "rb").read()
        b = open(f"{tmp}/b/rgb_0000.png", "rb").read()
        check(a == b, "the saved scene renders a different image")

        subprocess.run([binary, "run", scene, "--out", f"{tmp}/sim", *small, "--set",
                        "/World/Pallets.exposedVar:volumeStackRandomizer:renderSimulation=true"],
                       check=True, capture_output=True)
        frames = sorted(glob.glob(f"{tmp}/sim/simulation/Cam/rgb_*.png"))
        check(len(frames) >= 360, f"{len(frames)} simulation frames")
        if frames:
            check(Image.open(frames[0]).size == (64, 64), "simulation frame size")
            check(open(frames[0], "rb").read() != open(frames[-1], "rb").read(), "the simulation does not move")

        bad = subprocess.run([binary, "run", scene, "--no-render", "--set", "physics.require_settled=true",
                              "--set", "physics.max_settle_steps=0", "--set", "physics.settle_linear_speed=0",
                              "--set", "physics.settle_angular_speed=0"], capture_output=True, text=True)
        check(bad.returncode == 1, f"require_settled exit {bad.returncode}")
        check("still moves" in bad.stderr and "/World/Pallets/A" in bad.stderr, f"message: {bad.stderr.strip()}")
    return finish("ok")


if __name__ == "__main__":
    sys.exit(main())
