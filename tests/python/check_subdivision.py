#!/usr/bin/python3
"""Subdivision surfaces through the CLI, read the way users read datasets.

  check_subdivision.py BIN REPO   tests/data/usd/subdivision.usda runs at the default level and at
                                  render.subdivision_level none: both frames show the three meshes,
                                  and they differ only because the refined surfaces are rounded (the
                                  cage drawn as authored covers more pixels); a level outside the
                                  table is exit 2 naming the setting. Then Pixar's
                                  ../shared/usd-samples/full_assets/Teapot/Teapot.usd (meshes that
                                  author subdivisionScheme catmullClark): validate and run
                                  exit 0 at the default level and at none, and both frames show the
                                  teapot (exit 77 when the samples are absent).
"""
import glob
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

from checklib import check, finish


def sdg(binary, *args, timeout=300):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=timeout)


def first_rgb(folder):
    images = sorted(glob.glob(os.path.join(folder, "**", "rgb_*.png"), recursive=True))
    return np.asarray(Image.open(images[0]).convert("RGB")).astype(int) if images else None


def covered(rgb):
    """Pixels that are not the background (the top-left pixel's colour)."""
    return int((np.abs(rgb - rgb[0, 0]).sum(axis=2) > 24).sum())


def main():
    binary, repo = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as tmp:
        stage = os.path.join(repo, "tests", "data", "usd", "subdivision.usda")
        frames = {}
        for level in ("2", "none"):
            out = os.path.join(tmp, "level_" + level)
            r = sdg(binary, "run", stage, "--frames", "1", "--out", out, "--set", f"render.subdivision_level={level}")
            check(r.returncode == 0, f"run subdivision.usda at level {level}: exit {r.returncode}: {r.stderr}")
            frames[level] = first_rgb(out)
            check(frames[level] is not None, f"level {level}: no rgb image in {out}")
        if all(f is not None for f in frames.values()):
            refined, cage = covered(frames["2"]), covered(frames["none"])
            check(refined > 2000, f"the refined frame shows {refined} pixels of geometry, expected the meshes")
            # The rounded surfaces lie inside their cages: fewer pixels, not none.
            check(0.6 * cage < refined < 0.97 * cage,
                  f"refined meshes cover {refined} pixels against the cage's {cage}: expected somewhat fewer")
        r = sdg(binary, "validate", stage, "--set", "render.subdivision_level=9")
        check(r.returncode == 2 and "subdivision_level" in r.stderr,
              f"level 9: exit {r.returncode}, expected 2 naming render.subdivision_level: {r.stderr}")

        teapot = os.path.normpath(os.path.join(repo, "..", "shared", "usd-samples", "full_assets", "Teapot", "Teapot.usd"))
        if not os.path.exists(teapot):
            code = finish("ok (usd-samples absent: the teapot skipped)")
            return code if code else 77
        r = sdg(binary, "validate", teapot)
        check(r.returncode == 0, f"validate Teapot.usd: exit {r.returncode}: {r.stderr}")
        for level in ("2", "none"):
            out = os.path.join(tmp, "teapot_" + level)
            r = sdg(binary, "run", teapot, "--frames", "1", "--resolution", "128x128", "--out", out,
                    "--set", f"render.subdivision_level={level}")
            check(r.returncode == 0, f"run Teapot.usd at level {level}: exit {r.returncode}: {r.stderr}")
            rgb = first_rgb(out)
            shown = covered(rgb) if rgb is not None else 0
            check(shown > 500, f"Teapot.usd at level {level}: the frame shows {shown} pixels of geometry")
    return finish()


if __name__ == "__main__":
    sys.exit(main())
