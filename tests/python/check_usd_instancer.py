#!/usr/bin/python3
"""A USD PointInstancer end to end, read the way users read datasets (numpy, PIL, json).

  check_usd_instancer.py BIN REPO    tests/data/usd/instancer/instancer.usda runs to a dataset where
                                     each visible instance (ids 10, 11, 14: 12 is in invisibleIds, 13
                                     in inactiveIds) has its own 2D and 3D box labelled with its
                                     prototype's class, the turned and stretched instance 14 has a
                                     taller box than instance 10, and no labelled pixel lies outside
                                     the instances' boxes: the prototypes are not drawn where they
                                     stand (in view, above the row). With motion vectors, instance
                                     11 (velocity 0.5 along x) moves and instance 10 (none) does not.
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

from checklib import check, finish


def main():
    binary, repo = sys.argv[1], sys.argv[2]
    scene = os.path.join(repo, "tests", "data", "usd", "instancer", "instancer.usda")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        result = subprocess.run([binary, "run", scene, "--frames", "1", "--out", out,
                                 "--set", "writer.bounding_box_3d=true"],
                                capture_output=True, text=True, timeout=300)
        check(result.returncode == 0, f"run instancer.usda: exit {result.returncode}: {result.stderr}")
        if result.returncode != 0:
            return finish()
        check("PointInstancer" not in result.stderr, f"the instancer is still reported as dropped: {result.stderr}")
        boxes = np.load(os.path.join(out, "bounding_box_2d_tight_0000.npy"))
        labels = json.load(open(os.path.join(out, "bounding_box_2d_tight_labels_0000.json")))
        paths = json.load(open(os.path.join(out, "bounding_box_2d_tight_prim_paths_0000.json")))
        names = {int(k): v.get("class") for k, v in labels.items()}
        expected = {"/World/Scatter/instance_10": "crate", "/World/Scatter/instance_11": "ball",
                    "/World/Scatter/instance_14": "crate"}
        check(sorted(paths) == sorted(expected), f"2D boxes of {paths}, expected one per visible instance {sorted(expected)}")
        by_path = {}
        for path, box in zip(paths, boxes):
            by_path[path] = box
            check(names.get(int(box["semanticId"])) == expected.get(path),
                  f"{path}: labelled {names.get(int(box['semanticId']))}, expected {expected.get(path)}")
        check(len({int(b["semanticId"]) for b in boxes}) == 2, "two classes expected among the boxes")
        if "/World/Scatter/instance_10" in by_path and "/World/Scatter/instance_14" in by_path:
            a, b = by_path["/World/Scatter/instance_10"], by_path["/World/Scatter/instance_14"]
            check(int(b["y_max"]) - int(b["y_min"]) > int(a["y_max"]) - int(a["y_min"]) + 10,
                  f"instance 14 (scaled 2 in z) is not taller than instance 10: {b} vs {a}")
            check(int(b["x_min"]) > int(a["x_max"]), f"instance 14 (x = 2) is not right of instance 10 (x = -2): {b}, {a}")

        paths3d = json.load(open(os.path.join(out, "bounding_box_3d_prim_paths_0000.json")))
        check(sorted(paths3d) == sorted(expected), f"3D boxes of {paths3d}, expected {sorted(expected)}")

        # Every labelled pixel lies inside an instance's box: nothing is drawn
        # at the prototypes' own place.
        seg = np.asarray(Image.open(os.path.join(out, "semantic_segmentation_0000.png")).convert("RGBA"))
        seg_labels = json.load(open(os.path.join(out, "semantic_segmentation_labels_0000.json")))
        labelled = np.zeros(seg.shape[:2], bool)
        for colour, label in seg_labels.items():
            if label.get("class") in ("crate", "ball"):
                rgba = np.array([int(c) for c in colour.strip("()").split(",")])
                labelled |= (seg == rgba).all(axis=2)
        inside = np.zeros(seg.shape[:2], bool)
        for box in boxes:
            inside[int(box["y_min"]):int(box["y_max"]) + 1, int(box["x_min"]):int(box["x_max"]) + 1] = True
        check(labelled.sum() > 300, f"only {labelled.sum()} labelled pixels")
        check((labelled & ~inside).sum() == 0,
              f"{(labelled & ~inside).sum()} labelled pixels outside the instances' boxes (a prototype drawn in place?)")

        # Velocities move instances on the timeline: instance 11 (0.5 units/s along x) has motion
        # vectors along x, instance 10 (still) has none.
        moving = os.path.join(tmp, "moving")
        result = subprocess.run([binary, "run", scene, "--frames", "3", "--out", moving,
                                 "--set", "writer.motion_vectors=true"], capture_output=True, text=True, timeout=300)
        check(result.returncode == 0, f"run instancer.usda with motion vectors: exit {result.returncode}: {result.stderr}")
        if result.returncode == 0:
            motion = np.load(os.path.join(moving, "motion_vectors_0002.npy"))
            boxes2 = np.load(os.path.join(moving, "bounding_box_2d_tight_0002.npy"))
            paths2 = json.load(open(os.path.join(moving, "bounding_box_2d_tight_prim_paths_0002.json")))
            inside_of = {p: b for p, b in zip(paths2, boxes2)}

            def mean_abs_x(path):
                b = inside_of[path]
                window = motion[int(b["y_min"]):int(b["y_max"]) + 1, int(b["x_min"]):int(b["x_max"]) + 1, 0]
                return float(np.abs(window).mean())

            if "/World/Scatter/instance_11" in inside_of and "/World/Scatter/instance_10" in inside_of:
                still, moved = mean_abs_x("/World/Scatter/instance_10"), mean_abs_x("/World/Scatter/instance_11")
                print(f"motion along x: moving {moved:.4f}, still {still:.6f}")
                check(moved > 0.01 and still < 1e-6,
                      f"motion vectors along x: {moved} in moving instance 11, {still} in still instance 10")
            else:
                check(False, f"frame 2's boxes {paths2} lack instances 10 and 11")
    return finish()


if __name__ == "__main__":
    sys.exit(main())
