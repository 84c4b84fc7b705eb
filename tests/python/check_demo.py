#!/usr/bin/python3
"""The warehouse demo end to end at 128 x 128, read the way users read it:
every file opens with numpy, PIL or json with the expected names, shapes and
dtypes; the pre-roll stacked every pallet (settled, in the summary, and the
stacked cartons and bins are labelled entities in the boxes); the contact
sheet exists. The same seed twice gives byte-identical files, --threads 1
and --threads 2 too, and another seed different ones."""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image


from checklib import check, dataset_hashes, failures, finish


def run(binary, scene, out, *flags):
    subprocess.run([binary, "run", scene, "--out", out, "--resolution", "128x128", *flags], check=True,
                   capture_output=True)


def check_folder(out):
    for frame in range(6):
        n = f"{frame:04d}"
        rgb = np.asarray(Image.open(os.path.join(out, f"rgb_{n}.png")))
        check(rgb.shape == (128, 128, 4) and rgb.dtype == np.uint8, f"rgb_{n}: {rgb.shape} {rgb.dtype}")
        check(rgb[..., :3].std() > 5, f"rgb_{n} is flat")
        seg = Image.open(os.path.join(out, f"semantic_segmentation_{n}.png"))
        check(seg.size == (128, 128), f"semantic_segmentation_{n}: {seg.size}")
        seg_labels = json.load(open(os.path.join(out, f"semantic_segmentation_labels_{n}.json")))
        names = {v.get("class") for v in seg_labels.values()}
        check({"pallet", "cardboard_box", "power_drill"} <= names, f"semantic labels {n}: {sorted(map(str, names))}")
        boxes = np.load(os.path.join(out, f"bounding_box_2d_tight_{n}.npy"))
        check(boxes.dtype.names == ("semanticId", "x_min", "y_min", "x_max", "y_max", "occlusionRatio"),
              f"box dtype {boxes.dtype}")
        labels = json.load(open(os.path.join(out, f"bounding_box_2d_tight_labels_{n}.json")))
        paths = json.load(open(os.path.join(out, f"bounding_box_2d_tight_prim_paths_{n}.json")))
        check(len(paths) == len(boxes), f"boxes {n}: {len(boxes)} rows, {len(paths)} paths")
        stacked = [p for p in paths if p.startswith("/Behaviors/volumeStackRandomizer/Assets/Pallet_0")]
        check(len(stacked) >= 2, f"frame {n}: only {len(stacked)} stacked assets have boxes")
        for row, path in zip(boxes, paths):
            check(0 <= row["x_min"] <= row["x_max"] < 128 and 0 <= row["y_min"] <= row["y_max"] < 128,
                  f"box of {path} outside the image: {row}")
            check(str(row["semanticId"]) in labels, f"box of {path}: id {row['semanticId']} has no label")
        depth = np.load(os.path.join(out, f"distance_to_image_plane_{n}.npy"))
        check(depth.shape == (128, 128) and depth.dtype == np.float32, f"depth {n}: {depth.shape} {depth.dtype}")
        finite = depth[np.isfinite(depth)]
        check(finite.size > 0 and finite.min() > 0.5 and finite.max() < 60, f"depth {n} range")
        params = json.load(open(os.path.join(out, f"camera_params_{n}.json")))
        check({"cameraFocalLength", "cameraViewTransform", "cameraProjection", "renderProductResolution"} <= set(params),
              f"camera_params {n}: {sorted(params)}")
    check(os.path.exists(os.path.join(out, "metadata.txt")), "no metadata.txt")
    sheet = Image.open(os.path.join(out, "contact_sheet.png"))
    check(sheet.size[0] >= 2 * 128 and sheet.size[1] >= 2 * 128, f"contact sheet {sheet.size}")
    summary = json.load(open(os.path.join(out, "run_summary.json")))
    settle = summary.get("settle", [])
    check(len(settle) == 4, f"settle reports: {len(settle)}")
    for r in settle:
        check(r["settled"] and 2 <= r["assets"] <= 15, f"settle report {r}")
        check(r["max_penetration_surface"] < 0.005 and r["max_penetration_assets"] < 0.01, f"penetration {r}")
    check(summary["frames"] == 6 and summary["seed"] == 10, f"summary {summary['frames']} {summary['seed']}")


def main():
    binary, scene = sys.argv[1:3]
    with tempfile.TemporaryDirectory() as tmp:
        a, b, c, d = (os.path.join(tmp, x) for x in "abcd")
        run(binary, scene, a, "--seed", "10", "--threads", "2")
        check_folder(a)
        run(binary, scene, b, "--seed", "10", "--threads", "1")
        run(binary, scene, c, "--seed", "11", "--threads", "2")
        ha, hb, hc = dataset_hashes(a), dataset_hashes(b), dataset_hashes(c)
        check(ha == hb, "--threads 1 and --threads 2 (same seed) differ: " +
              ", ".join(k for k in ha if ha.get(k) != hb.get(k))[:300])
        run(binary, scene, d, "--seed", "10", "--threads", "2")
        check(ha == dataset_hashes(d), "the same seed twice gave different files")
        check(ha.keys() == hc.keys() and ha != hc, "another seed gave the same files")
        check(ha["rgb_0000.png"] != hc["rgb_0000.png"], "another seed gave the same first image")
    return finish(f"ok: {len(ha)} files checked, deterministic across threads and runs")


if __name__ == "__main__":
    sys.exit(main())
