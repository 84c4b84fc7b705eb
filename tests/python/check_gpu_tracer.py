#!/usr/bin/python3
"""render.pathtracer from the outside, on the annotators scene at 64 x 48
(llvmpipe in CI, a GPU elsewhere):
- render.pathtracer: gpu writes the dataset: the same labels as the CPU
  tracer's run, a radiance (hdr_color) that is not the CPU tracer's bytes
  (the two are not byte-identical) but close to it, and byte-identical on a
  rerun; with its denoiser, 2 shards merged equal one run;
- a device without OpenGL 4.3 compute (Mesa told to offer 3.3) fails the
  gpu choice with exit 1 and a message saying why, and the auto choice
  traces on the CPU: the same bytes as render.pathtracer: cpu.

usage: check_gpu_tracer.py SDGBEHAVE SCENE    (numpy, PIL)"""
import fnmatch
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

from checklib import check, dataset_hashes, finish

COLOUR = ["rgb_*", "hdr_color_*", "contact_sheet.png", "manifest.jsonl", ".sdgbehave/*", "pointcloud*"]
ARGS = ["--render-mode", "pathtraced", "--samples", "8", "--frames", "1", "--set", "render.resolution=[64, 48]",
        "--set", "writer.BasicWriter.hdr_color=true"]


def run(binary, scene, out, tracer, env=None):
    return subprocess.run([binary, "run", scene, "--out", out, "--overwrite", *ARGS, "--set",
                           f"render.pathtracer={tracer}"], capture_output=True, text=True, env=env)


def labels(hashes):
    return {k: v for k, v in hashes.items() if not any(fnmatch.fnmatch(k, pattern) for pattern in COLOUR)}


def main():
    binary, scene = sys.argv[1:3]
    # Mesa's EGL alone, told to offer OpenGL 3.3: no compute shaders.
    no_compute = dict(os.environ, MESA_GL_VERSION_OVERRIDE="3.3",
                      __EGL_VENDOR_LIBRARY_FILENAMES="/usr/share/glvnd/egl_vendor.d/50_mesa.json")
    with tempfile.TemporaryDirectory() as tmp:
        gpu = run(binary, scene, f"{tmp}/gpu", "gpu")
        if gpu.returncode == 1 and "cannot run here" in gpu.stderr:
            print(f"skipped: no GPU tracer on this machine: {gpu.stderr.strip()[-300:]}")
            sys.exit(77)
        check(gpu.returncode == 0, f"render.pathtracer gpu: exit {gpu.returncode}: {gpu.stderr.strip()[-400:]}")
        again = run(binary, scene, f"{tmp}/again", "gpu")
        cpu = run(binary, scene, f"{tmp}/cpu", "cpu")
        check(again.returncode == 0 and cpu.returncode == 0, f"reruns failed: {again.stderr[-300:]} {cpu.stderr[-300:]}")
        g, a, c = (dataset_hashes(f"{tmp}/{d}") for d in ("gpu", "again", "cpu"))
        check(g == a, "two GPU runs differ: " + str(sorted(k for k in g if g[k] != a.get(k)))[:300])
        check(labels(g) == labels(c), "labels differ between the tracers")
        check(len(labels(g)) > 20, f"only {len(labels(g))} label files compared")
        # One sample stream, two tracers: close, not the same bytes.
        check(g["hdr_color_0000.npy"] != c["hdr_color_0000.npy"], "the GPU tracer's radiance is the CPU tracer's bytes")
        hg, hc = np.load(f"{tmp}/gpu/hdr_color_0000.npy"), np.load(f"{tmp}/cpu/hdr_color_0000.npy")
        check(abs(hg.mean() / hc.mean() - 1) < 0.02, f"mean radiance: gpu {hg.mean():.4g}, cpu {hc.mean():.4g}")
        pg = np.asarray(Image.open(f"{tmp}/gpu/rgb_0000.png"), dtype=np.float64)[..., :3]
        pc = np.asarray(Image.open(f"{tmp}/cpu/rgb_0000.png"), dtype=np.float64)[..., :3]
        check(np.abs(pg - pc).mean() < 2, f"rgb: mean difference {np.abs(pg - pc).mean():.2f} of 255")

        # The GPU denoiser too, split into shards: every frame's bytes depend only on the seed, frame and pixel.
        two = ARGS[:5] + ["2"] + ARGS[6:] + ["--denoise", "--set", "render.pathtracer=gpu"]
        whole = subprocess.run([binary, "run", scene, "--out", f"{tmp}/whole", *two], capture_output=True, text=True)
        check(whole.returncode == 0, f"2 frames denoised: exit {whole.returncode}: {whole.stderr[-300:]}")
        for i in (0, 1):
            subprocess.run([binary, "run", scene, "--out", f"{tmp}/shards", *two, "--shard", f"{i}/2"], check=True,
                           capture_output=True)
        subprocess.run([binary, "merge", f"{tmp}/shards"], check=True, capture_output=True)
        w, sh = dataset_hashes(f"{tmp}/whole"), dataset_hashes(f"{tmp}/shards")
        for name in ("rgb_0000.png", "rgb_0001.png", "hdr_color_0000.npy", "hdr_color_0001.npy"):
            check(name in w and sh.get(name) == w[name], f"{name} differs between 2 shards and one run")
        check(w["hdr_color_0000.npy"] != g["hdr_color_0000.npy"], "--denoise changed nothing")

        refused = run(binary, scene, f"{tmp}/refused", "gpu", no_compute)
        check(refused.returncode == 1, f"gpu without compute: exit {refused.returncode}, expected 1")
        check("render.pathtracer: gpu: the GPU path tracer cannot run here" in refused.stderr and
              "4.3" in refused.stderr, f"gpu without compute says: {refused.stderr.strip()[-300:]}")
        check(not os.path.exists(f"{tmp}/refused/rgb_0000.png"), "a refused run wrote frames")
        fallback = run(binary, scene, f"{tmp}/auto", "auto", no_compute)
        check(fallback.returncode == 0, f"auto without compute: exit {fallback.returncode}: {fallback.stderr[-300:]}")
        auto = dataset_hashes(f"{tmp}/auto")
        check(labels(auto) == labels(c) and auto["rgb_0000.png"] == c["rgb_0000.png"],
              "auto without compute is not the CPU tracer's dataset")
    sys.exit(finish())


if __name__ == "__main__":
    main()
