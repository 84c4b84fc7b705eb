#!/usr/bin/python3
"""Every scene in scenes/examples/ runs end to end (small frames), and the
writer examples produce their layouts: several cameras under
<camera>/<annotator>/ or, with use_common_output_dir, <annotator>/<camera>_;
COCO next to the BasicWriter files."""
import glob
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

from checklib import failures, finish


def run(binary, scene, out, *extra):
    result = subprocess.run([binary, "run", scene, "--out", out, "--frames", "2", "--resolution", "64x48", *extra],
                            capture_output=True, text=True)
    return result


def main():
    binary, examples = sys.argv[1:3]
    with tempfile.TemporaryDirectory() as tmp:
        for scene in sorted(glob.glob(f"{examples}/*.yaml")):
            out = f"{tmp}/{os.path.basename(scene)}"
            result = run(binary, scene, out)
            if result.returncode != 0:
                failures.append(f"{scene}: exit {result.returncode}\n{result.stderr}")
            elif not os.path.exists(f"{out}/metadata.txt") or not os.path.exists(f"{out}/run_summary.json"):
                failures.append(f"{scene}: metadata.txt or run_summary.json missing")
        multi = f"{tmp}/writer_multi_camera.yaml"
        for camera in ("Left", "Right"):
            image = f"{multi}/{camera}/rgb/rgb_0001.png"
            if not os.path.exists(image) or Image.open(image).size != (64, 48):
                failures.append(f"missing or wrong size: {image}")
            if not os.path.exists(f"{multi}/{camera}/bounding_box_2d_tight/bounding_box_2d_tight_0000.npy"):
                failures.append(f"{camera}: no bounding boxes in the legacy layout")
        common = f"{tmp}/common"
        run(binary, f"{examples}/writer_multi_camera.yaml", common, "--set", "writer.use_common_output_dir=true")
        for path in ("rgb/Left_rgb_0000.png", "rgb/Right_rgb_0001.png", "camera_params/Left_camera_params_0000.json"):
            if not os.path.exists(f"{common}/{path}"):
                failures.append(f"use_common_output_dir: missing {path}")
        coco = json.load(open(f"{tmp}/writer_coco.yaml/coco_instances.json"))
        if len(coco["images"]) != 2 or not coco["annotations"]:
            failures.append("writer_coco: unexpected COCO content")
        if not os.path.exists(f"{tmp}/writer_depth_and_normals.yaml/distance_to_camera_0000.png"):
            failures.append("writer_depth_and_normals: no colorized depth")
        seg = f"{tmp}/writer_segmentation.yaml"
        for name in ("semantic_segmentation", "instance_id_segmentation", "instance_segmentation"):
            image = Image.open(f"{seg}/{name}_0000.png")
            if image.mode not in ("I", "I;16"):
                failures.append(f"writer_segmentation: {name} is {image.mode}, not raw 16-bit ids")
        labels = json.load(open(f"{seg}/semantic_segmentation_labels_0000.json"))
        if {v.get("class") for v in labels.values()} != {"floor", "crate", "ball"}:
            failures.append(f"writer_segmentation: labels {labels}")
        bop = f"{tmp}/writer_bop.yaml"
        for path in ("camera.json", "models/models_info.json", "models/obj_000001.ply", "train_pbr/000000/scene_gt.json",
                     "train_pbr/000000/mask_visib/000001_000000.png", "rgb_0000.png"):
            if not os.path.exists(f"{bop}/{path}"):
                failures.append(f"writer_bop: missing {path}")
        flow = f"{tmp}/writer_flow.yaml"
        if np.load(f"{flow}/forward_flow_0000.npy").shape != (48, 64, 2) or \
                np.load(f"{flow}/motion_vectors_0001.npy").shape != (48, 64, 4):
            failures.append("writer_flow: unexpected flow or motion vector shapes")
        boxes = f"{tmp}/writer_boxes.yaml"
        tight = np.load(f"{boxes}/bounding_box_2d_tight_0000.npy")
        loose = np.load(f"{boxes}/bounding_box_2d_loose_0000.npy")
        paths = json.load(open(f"{boxes}/bounding_box_2d_tight_prim_paths_0000.json"))
        back = paths.index("/World/Back") if "/World/Back" in paths else None
        if back is None or not tight[back]["occlusionRatio"] > 0.1:
            failures.append(f"writer_boxes: the back crate should be partly hidden: {tight}")
        for t, l in zip(tight, loose):
            if not (l["x_min"] <= t["x_min"] and l["y_min"] <= t["y_min"] and l["x_max"] >= t["x_max"]
                    and l["y_max"] >= t["y_max"]):
                failures.append(f"writer_boxes: loose {l} does not contain tight {t}")
        if len(np.load(f"{boxes}/bounding_box_3d_0000.npy")) != 2:
            failures.append("writer_boxes: expected two 3D boxes")
    return finish()


if __name__ == "__main__":
    sys.exit(main())
