#!/usr/bin/python3
"""Skinned meshes (UsdSkel) through the CLI, read the way users read datasets.

  check_usd_skel.py BIN REPO   tests/data/usd/skel/arm.usda: four frames, the arm's segmentation mask
                               grows towards +Y as the elbow bends (its box's top rises), whole runs
                               with --threads 1 and 2 write the same bytes; nothing of the skeleton is
                               reported as dropped. Then ../shared/usd-samples/.../CesiumMan.usdz (a
                               walking glTF character): its frames differ over time and nothing of
                               UsdSkel is dropped (exit 77 when the samples are absent).
"""
import glob
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

from checklib import check, dataset_hashes, finish


def sdg(binary, *args):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=300)


def rgb_frames(folder):
    return [np.asarray(Image.open(p).convert("RGB")).astype(int) for p in sorted(glob.glob(os.path.join(folder, "rgb_*.png")))]


def dropped_skel(folder):
    summary = json.load(open(os.path.join(folder, "run_summary.json")))
    return [d for d in summary.get("dropped", []) if "Skel" in d.get("what", "") or "skel" in d.get("what", "")]


def main():
    binary, repo = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as tmp:
        arm = os.path.join(repo, "tests", "data", "usd", "skel", "arm.usda")
        outs = {}
        for threads in ("1", "2"):
            out = os.path.join(tmp, "arm_" + threads)
            r = sdg(binary, "run", arm, "--frames", "4", "--resolution", "96x96", "--threads", threads, "--out", out,
                    "--set", "writer.bounding_box_2d_tight=true")
            check(r.returncode == 0, f"run arm.usda --threads {threads}: exit {r.returncode}: {r.stderr[-400:]}")
            outs[threads] = out
        if all(os.path.isdir(o) for o in outs.values()):
            check(dataset_hashes(outs["1"]) == dataset_hashes(outs["2"]), "arm.usda: --threads 1 and 2 differ")
            frames = rgb_frames(outs["1"])
            check(len(frames) == 4, f"arm.usda: {len(frames)} rgb frames, expected 4")
            if len(frames) == 4:
                check(np.abs(frames[0] - frames[-1]).max() > 0, "arm.usda: the first and last frames are the same")
            tops = []
            for path in sorted(glob.glob(os.path.join(outs["1"], "bounding_box_2d_tight_*.npy"))):
                boxes = np.load(path)
                tops.append(int(boxes["y_min"].min()) if len(boxes) else None)
            check(len(tops) == 4 and None not in tops and tops[-1] < tops[0],
                  f"arm.usda: the arm's box tops {tops}: expected the bent arm to reach higher (smaller y_min)")
            check(dropped_skel(outs["1"]) == [], f"arm.usda: dropped {dropped_skel(outs['1'])}")

        cesium = os.path.normpath(os.path.join(repo, "..", "shared", "usd-samples", "test_assets", "USDZ", "CesiumMan",
                                               "CesiumMan.usdz"))
        if not os.path.exists(cesium):
            code = finish("ok (usd-samples absent: CesiumMan skipped)")
            return code if code else 77
        out = os.path.join(tmp, "cesium")
        r = sdg(binary, "run", cesium, "--frames", "8", "--resolution", "96x96", "--out", out)
        check(r.returncode == 0, f"run CesiumMan.usdz: exit {r.returncode}: {r.stderr[-400:]}")
        if r.returncode == 0:
            frames = rgb_frames(out)
            check(len(frames) == 8 and np.abs(frames[0] - frames[-1]).max() > 40,
                  "CesiumMan.usdz: the first and last frames are (nearly) the same: the character does not move")
            check(dropped_skel(out) == [], f"CesiumMan.usdz: dropped {dropped_skel(out)}")
    return finish()


if __name__ == "__main__":
    sys.exit(main())
