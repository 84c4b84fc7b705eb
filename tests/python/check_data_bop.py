#!/usr/bin/python3
"""sdgbehave.data's BOP reader (BopDataset, read_ply) on a BOP scene laid out
by hand as the BOP toolkit's docs/bop_datasets_format.md describes it:
splits and scenes found, matrices read row-wise (a rotation that is not
its own transpose), translations in mm, depth times depth_scale, masks,
gt_info merged per instance, images without annotations kept, models read
from ascii and binary PLY, and clear errors for a missing scene and for a
folder that is not a BOP dataset.

usage: check_data_bop.py (PYTHONPATH holds python/)"""
import json
import os
import struct
import sys
import tempfile

import numpy as np
from PIL import Image

from checklib import check, finish
from sdgbehave.data import BopDataset, DatasetError, read_ply

# A tetrahedron, mm.
VERTICES = np.array([[0, 0, 0], [40, 0, 0], [0, 30, 0], [0, 0, 20]], dtype=np.float32)
FACES = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
ANGLE = np.radians(30)
R = np.array([[np.cos(ANGLE), -np.sin(ANGLE), 0], [np.sin(ANGLE), np.cos(ANGLE), 0], [0, 0, 1]])
T = np.array([10.0, -5.0, 600.0])
K = np.array([[500.0, 0, 32.0], [0, 500.0, 24.0], [0, 0, 1]])


def write_json(path, value):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        json.dump(value, f)


def write_png(path, array):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    Image.fromarray(array).save(path)


def make_dataset(root):
    write_json(f"{root}/camera.json", {"cx": 32.0, "cy": 24.0, "depth_scale": 0.1, "fx": 500.0, "fy": 500.0,
                                       "height": 48, "width": 64})
    write_json(f"{root}/models/models_info.json", {"1": {"diameter": 50.0, "min_x": 0.0, "size_x": 40.0}})
    header = ("ply\nformat binary_little_endian 1.0\ncomment made by hand\nelement vertex 4\nproperty float x\n"
              "property float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_indices\n"
              "end_header\n").encode()
    body = VERTICES.astype("<f4").tobytes() + b"".join(struct.pack("<B3i", 3, *f) for f in FACES)
    with open(f"{root}/models/obj_000001.ply", "wb") as f:
        f.write(header + body)
    scene = f"{root}/train_pbr/000000"
    camera = {"cam_K": K.reshape(-1).tolist(), "depth_scale": 0.1, "cam_R_w2c": R.reshape(-1).tolist(),
              "cam_t_w2c": [0.0, 0.0, 1000.0]}
    write_json(f"{scene}/scene_camera.json", {"0": camera, "1": dict(camera, cam_t_w2c=[0.0, 0.0, 900.0])})
    write_json(f"{scene}/scene_gt.json", {"0": [{"cam_R_m2c": R.reshape(-1).tolist(), "cam_t_m2c": T.tolist(),
                                                 "obj_id": 1}], "1": []})
    write_json(f"{scene}/scene_gt_info.json", {"0": [{"bbox_obj": [30, 20, 5, 4], "bbox_visib": [30, 20, 5, 3],
                                                      "px_count_all": 20, "px_count_valid": 20, "px_count_visib": 15,
                                                      "visib_fract": 0.75}], "1": []})
    for im in (0, 1):
        write_png(f"{scene}/rgb/{im:06d}.png", np.full((48, 64, 3), 40 * (im + 1), dtype=np.uint8))
        write_png(f"{scene}/depth/{im:06d}.png", np.full((48, 64), 6000 + im, dtype=np.uint16))
    mask = np.zeros((48, 64), dtype=np.uint8)
    mask[20:24, 30:35] = 255
    write_png(f"{scene}/mask/000000_000000.png", mask)
    mask[23] = 0
    write_png(f"{scene}/mask_visib/000000_000000.png", mask)
    os.makedirs(f"{root}/not_a_split", exist_ok=True)


def main():
    with tempfile.TemporaryDirectory(prefix="sdg_bop_") as root:
        make_dataset(root)
        bop = BopDataset(root)
        check(bop.splits == ["train_pbr"] and bop.scene_ids("train_pbr") == [0], f"splits {bop.splits}")
        check(bop.camera["width"] == 64 and bop.models_info[1]["diameter"] == 50.0, "camera.json, models_info")
        scene = bop.scenes("train_pbr")[0]
        check(len(scene) == 2 and scene.image_ids == [0, 1], f"images {scene.image_ids}")
        image = scene[0]
        check(np.array_equal(image.K, K) and np.allclose(image.R_w2c, R) and image.t_w2c[2] == 1000.0, "camera")
        (instance,) = image.objects
        check(instance["obj_id"] == 1 and np.allclose(instance["R_m2c"], R) and np.allclose(instance["t_m2c"], T),
              f"pose {instance}")
        check(instance["visib_fract"] == 0.75 and instance["bbox_visib"] == [30, 20, 5, 3], "gt_info merged")
        check(scene[1].objects == [] and scene[1].t_w2c[2] == 900.0, "an image without annotations")
        check(image.rgb().shape == (48, 64, 3) and scene[1].rgb()[0, 0, 0] == 80, "rgb")
        depth = image.depth()
        check(depth.dtype == np.float32 and np.allclose(depth, 600.0) and np.allclose(scene[1].depth(), 600.1),
              f"depth x depth_scale: {depth[0, 0]}")
        check(image.mask(0).sum() == 20 and image.mask_visib(0).sum() == 15 and image.mask(0).dtype == bool, "masks")
        model = bop.model(1)
        check(np.array_equal(model["vertices"], VERTICES) and model["faces"].tolist() == [list(f) for f in FACES],
              "binary PLY model")
        pixels, depths = image.project(model["vertices"], 0)
        # The apex (0, 0, 20) mm sits 20 mm nearer the camera along its z: rotation about z keeps z.
        check(np.allclose(depths, [600, 600, 600, 620]), f"depths {depths}")
        # (40, 0, 0) rotated by 30 degrees about z is (34.64, 20, 0): row-wise R, not its transpose.
        expected = K @ (R @ np.array([40.0, 0, 0]) + T)
        check(np.allclose(pixels[1], expected[:2] / expected[2]) and pixels[1][1] > pixels[0][1], f"pixels {pixels}")
        with open(os.path.join(root, "ascii.ply"), "w") as f:
            f.write("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 1\nproperty list uchar int vertex_index\nend_header\n"
                    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n")
        quad = read_ply(os.path.join(root, "ascii.ply"))
        check(quad["faces"].tolist() == [[0, 1, 2], [0, 2, 3]] and quad["vertices"].shape == (4, 3), "ascii quad")
        try:
            bop.scene("train_pbr", 7)
            check(False, "a missing scene opened")
        except DatasetError as e:
            check("no such scene" in str(e) and "[0]" in str(e), f"missing scene: {e}")
        try:
            BopDataset(os.path.join(root, "models"))
            check(False, "models/ opened as a BOP dataset")
        except DatasetError as e:
            check("not a BOP dataset" in str(e), f"not BOP: {e}")
    return finish("ok: BOP scenes, poses, depth, masks and PLY models read as the BOP format lays them out")


if __name__ == "__main__":
    sys.exit(main())
