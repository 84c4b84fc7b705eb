#!/usr/bin/python3
"""OSMesa and EGL (Mesa's surfaceless platform here; a GPU on render boxes)
render the same scene: labels agree (semantic ids exact except at most 1 %
of pixels, which can only sit on silhouettes; boxes within 1 pixel), depth
within 1 mm plus 0.1 % where both see geometry, colour within 3 levels on
average. The summary names the back end and device. Errors: an unknown
back end is a usage error (exit 2); --gpu with osmesa, a GPU index on a
machine without that GPU, or SDGBEHAVE_VISIBLE_GPUS malformed or naming a GPU
the machine lacks, exits 1 naming what was tried."""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image


from checklib import check, failures, finish


def run(binary, scene, out, *flags):
    return subprocess.run([binary, "run", scene, "--out", out, "--frames", "3", "--resolution", "128x128", *flags],
                          capture_output=True, text=True)


def main():
    binary, scene = (os.path.abspath(a) for a in sys.argv[1:3])
    with tempfile.TemporaryDirectory() as tmp:
        a, b = f"{tmp}/osmesa", f"{tmp}/egl"
        ra, rb = run(binary, scene, a, "--backend", "osmesa"), run(binary, scene, b, "--backend", "egl")
        check(ra.returncode == 0, f"osmesa: {ra.stderr.strip()[-300:]}")
        if rb.returncode != 0:
            print(f"EGL run failed: {rb.stderr.strip()[-400:]}")
            return 1
        sa, sb = (json.load(open(f"{d}/run_summary.json")) for d in (a, b))
        check(sa["renderer"]["backend"] == "osmesa" and sb["renderer"]["backend"] == "egl",
              f"summaries name {sa['renderer']} and {sb['renderer']}")
        check(sb["renderer"]["device"] != "" and sb["renderer"]["gl_renderer"] != "", f"EGL device: {sb['renderer']}")
        for frame in ("0000", "0001", "0002"):
            seg = [np.asarray(Image.open(f"{d}/semantic_segmentation_{frame}.png")) for d in (a, b)]
            differ = np.any(seg[0] != seg[1], axis=-1).mean()
            check(differ <= 0.01, f"frame {frame}: {differ:.2%} of semantic pixels differ")
            boxes = [np.load(f"{d}/bounding_box_2d_tight_{frame}.npy") for d in (a, b)]
            check(len(boxes[0]) == len(boxes[1]), f"frame {frame}: {len(boxes[0])} vs {len(boxes[1])} boxes")
            for x, y in zip(*boxes):
                for k in ("x_min", "y_min", "x_max", "y_max"):
                    check(abs(int(x[k]) - int(y[k])) <= 1, f"frame {frame}: box {k} {x[k]} vs {y[k]}")
            depth = [np.load(f"{d}/distance_to_image_plane_{frame}.npy") for d in (a, b)]
            both = np.isfinite(depth[0]) & np.isfinite(depth[1])
            check(both.mean() > 0.5, f"frame {frame}: little geometry")
            err = np.abs(depth[0][both] - depth[1][both]) - (0.001 + 0.001 * depth[0][both])
            check((err <= 0).mean() >= 0.99, f"frame {frame}: depth differs beyond tolerance at {(err > 0).mean():.2%}")
            rgb = [np.asarray(Image.open(f"{d}/rgb_{frame}.png")).astype(int) for d in (a, b)]
            check(np.abs(rgb[0] - rgb[1]).mean() <= 3, f"frame {frame}: colour differs by {np.abs(rgb[0] - rgb[1]).mean():.2f}")
        bad = run(binary, scene, f"{tmp}/x", "--backend", "vulkan")
        check(bad.returncode == 2 and "vulkan" in bad.stderr, f"unknown back end: {bad.returncode} {bad.stderr.strip()}")
        bad = run(binary, scene, f"{tmp}/y", "--backend", "osmesa", "--gpu", "0")
        check(bad.returncode == 1 and "needs the EGL back end" in bad.stderr, f"--gpu with osmesa: {bad.stderr.strip()}")
        bad = run(binary, scene, f"{tmp}/z", "--backend", "egl", "--gpu", "7")
        check(bad.returncode == 1 and "EGL back end" in bad.stderr and "--gpu 7" in bad.stderr,
              f"--gpu 7: {bad.returncode} {bad.stderr.strip()}")
        # SDGBEHAVE_VISIBLE_GPUS, read where every GL context finds its device (render/egl).
        env = dict(os.environ, SDGBEHAVE_VISIBLE_GPUS="0,x")
        bad = subprocess.run([binary, "run", scene, "--out", f"{tmp}/v", "--frames", "1", "--resolution", "32x32",
                              "--backend", "egl"], capture_output=True, text=True, env=env)
        check(bad.returncode == 1 and "SDGBEHAVE_VISIBLE_GPUS=0,x" in bad.stderr and "'x'" in bad.stderr,
              f"a malformed SDGBEHAVE_VISIBLE_GPUS: {bad.returncode} {bad.stderr.strip()[-300:]}")
        env["SDGBEHAVE_VISIBLE_GPUS"] = "99"
        bad = subprocess.run([binary, "run", scene, "--out", f"{tmp}/w", "--frames", "1", "--resolution", "32x32",
                              "--backend", "egl"], capture_output=True, text=True, env=env)
        check(bad.returncode == 1 and "names GPU 99" in bad.stderr,
              f"SDGBEHAVE_VISIBLE_GPUS naming a GPU the machine lacks: {bad.returncode} {bad.stderr.strip()[-300:]}")
        check(sb["renderer"].get("color", "") != "", f"the summary names what made the colour: {sb['renderer']}")
    return finish("ok")


if __name__ == "__main__":
    sys.exit(main())
