#!/usr/bin/python3
"""render.mode pathtraced from the outside, on the annotators scene:
- every label file (segmentations, boxes, occlusion, distances, normals,
  camera parameters, COCO) is byte-identical to the rasterizer's run: labels
  come from the raster passes, so they pass every label test that run does;
- the colour differs from the rasterizer's, and hdr_color_X.npy holds its
  linear radiance (float32, height x width x 3, finite, >= 0) whose tone
  curve is the rgb PNG;
- --threads 1 and 3 write byte-identical datasets, and 2 shards merged equal
  one run: every pixel's samples depend only on the seed, frame and pixel;
- --denoise changes the colour and nothing else;
- writer.hdr_color without the path tracer is a scene error (exit 2);
- the run summary counts the tracing as render time, the last frame's too
  (it is collected after the frame loop): one frame at 256 samples takes
  longer than at 1, and the difference shows in seconds.render.

usage: check_pathtraced.py SDGBEHAVE SCENE    (numpy, PIL)"""
import fnmatch
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

from checklib import check, dataset_hashes, finish

COLOUR = ["rgb_*", "hdr_color_*", "pointcloud*", "contact_sheet.png", "manifest.jsonl", ".sdgbehave/*"]
PT = ["--render-mode", "pathtraced", "--samples", "4", "--frames", "2"]


def run(binary, scene, out, *extra):
    p = subprocess.run([binary, "run", scene, "--out", out, "--overwrite", *extra], capture_output=True, text=True)
    check(p.returncode == 0, f"run {' '.join(extra)}: exit {p.returncode}: {p.stderr.strip()[-400:]}")


def render_and_total_seconds(binary, scene, out, samples):
    run(binary, scene, out, "--render-mode", "pathtraced", "--samples", str(samples), "--frames", "1",
        "--resolution", "64x48")
    seconds = json.load(open(f"{out}/run_summary.json"))["seconds"]
    return seconds["render"], seconds["total"]


def labels(hashes):
    return {k: v for k, v in hashes.items() if not any(fnmatch.fnmatch(k, pattern) for pattern in COLOUR)}


def tone(radiance, exposure=0.002):
    mapped = 1.0 - np.exp(-radiance.astype(np.float64) * exposure)
    srgb = np.where(mapped <= 0.0031308, mapped * 12.92, 1.055 * np.power(mapped, 1 / 2.4) - 0.055)
    return np.rint(srgb * 255)


def main():
    binary, scene = sys.argv[1:3]
    with tempfile.TemporaryDirectory() as tmp:
        run(binary, scene, f"{tmp}/raster", "--frames", "2")
        run(binary, scene, f"{tmp}/one", *PT, "--threads", "1", "--set", "writer.BasicWriter.hdr_color=true")
        run(binary, scene, f"{tmp}/three", *PT, "--threads", "3", "--set", "writer.BasicWriter.hdr_color=true")
        raster, one, three = (dataset_hashes(f"{tmp}/{d}") for d in ("raster", "one", "three"))
        check(labels(raster) == labels(one), "labels differ between the modes: " +
              str(sorted(k for k in labels(raster) if labels(raster)[k] != labels(one).get(k)))[:300])
        check(len(labels(one)) > 20, f"only {len(labels(one))} label files compared")
        check(raster["rgb_0000.png"] != one["rgb_0000.png"], "the path-traced colour is the rasterizer's")
        check(one == three, "--threads 1 and 3 differ: " + str(sorted(k for k in one if one[k] != three.get(k)))[:300])
        for frame in ("0000", "0001"):
            hdr = np.load(f"{tmp}/one/hdr_color_{frame}.npy")
            check(hdr.dtype == np.float32 and hdr.shape == (240, 320, 3), f"hdr_color {hdr.dtype} {hdr.shape}")
            check(np.isfinite(hdr).all() and (hdr >= 0).all(), "hdr_color has negative or non-finite values")
            rgb = np.asarray(Image.open(f"{tmp}/one/rgb_{frame}.png"))[..., :3].astype(np.float64)
            check(np.abs(tone(hdr) - rgb).max() <= 1, f"rgb_{frame} is not hdr_color's tone curve")
        # Shards: frame 0 and frame 1 by separate processes, merged.
        for i in (0, 1):
            subprocess.run([binary, "run", scene, "--out", f"{tmp}/shards", *PT, "--shard", f"{i}/2",
                            "--set", "writer.BasicWriter.hdr_color=true"], check=True, capture_output=True)
        subprocess.run([binary, "merge", f"{tmp}/shards"], check=True, capture_output=True)
        shards = dataset_hashes(f"{tmp}/shards")
        for name in ("rgb_0000.png", "rgb_0001.png", "hdr_color_0000.npy", "hdr_color_0001.npy"):
            check(shards.get(name) == one[name], f"{name} differs between 2 shards and one run")
        run(binary, scene, f"{tmp}/denoised", *PT, "--denoise")
        denoised = dataset_hashes(f"{tmp}/denoised")
        check(labels(denoised) == labels(one), "--denoise changed a label")
        check(denoised["rgb_0000.png"] != one["rgb_0000.png"], "--denoise changed nothing")
        p = subprocess.run([binary, "run", scene, "--out", f"{tmp}/bad", "--set", "writer.BasicWriter.hdr_color=true"],
                           capture_output=True, text=True)
        check(p.returncode == 2 and "hdr_color: linear radiance comes from the path tracer" in p.stderr,
              f"hdr_color with the rasterizer: exit {p.returncode}: {p.stderr.strip()[-300:]}")
        render_1, total_1 = render_and_total_seconds(binary, scene, f"{tmp}/time1", 1)
        render_256, total_256 = render_and_total_seconds(binary, scene, f"{tmp}/time256", 256)
        check(total_256 - total_1 > 0 and render_256 - render_1 >= 0.5 * (total_256 - total_1),
              f"one frame at 1 and 256 samples: seconds.render {render_1:.3f} and {render_256:.3f}, "
              f"total {total_1:.3f} and {total_256:.3f}: the tracing is not counted as render time")
    sys.exit(finish("path-traced datasets: labels equal the rasterizer's, colour and radiance agree, deterministic"))


if __name__ == "__main__":
    main()
