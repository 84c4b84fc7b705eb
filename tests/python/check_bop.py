#!/usr/bin/python3
"""The BOP writer's output read the way the BOP toolkit reads it (its
conventions, checked without installing it): the folder layout and the JSON
keys and types of its loaders; every object model reprojected with
cam_R_m2c / cam_t_m2c / cam_K matches its written silhouette mask (IoU >=
0.98) and its visible mask where nothing hides it; the written depth
matches the models' depth; shards merged and a resumed run give the same
bytes as a whole run."""
import glob
import json
import os
import struct
import subprocess
import sys
import tempfile

import numpy as np
import yaml
from PIL import Image

from checklib import check, dataset_hashes, failures, finish

MIN_IOU = 0.98          # the bar for unoccluded objects (edge pixels differ by rounding only)
DEPTH_TOLERANCE_MM = 3  # 0.2 mm depth steps; the rasterizer's depth is 24-bit, the floats here double


def run(binary, scene, out, *flags):
    p = subprocess.run([binary, "run", scene, "--out", out, "--overwrite", *flags], capture_output=True, text=True)
    check(p.returncode == 0, f"run {flags}: exit {p.returncode}: {p.stderr.strip()[-500:]}")


def load_ply(path):
    """A binary little-endian PLY as the toolkit's load_ply reads it: x y z nx ny nz, triangles."""
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    check(header[1] == "format binary_little_endian 1.0", f"{path}: {header[1]}")
    vertices = int(next(l for l in header if l.startswith("element vertex")).split()[-1])
    faces = int(next(l for l in header if l.startswith("element face")).split()[-1])
    props = [l.split()[-1] for l in header if l.startswith("property float")]
    check(props == ["x", "y", "z", "nx", "ny", "nz"], f"{path}: vertex properties {props}")
    check("property list uchar int vertex_indices" in header, f"{path}: no vertex_indices list")
    v = np.frombuffer(data, dtype="<f4", count=vertices * 6, offset=end).reshape(vertices, 6)
    f = np.frombuffer(data, dtype=np.dtype([("n", "u1"), ("i", "<i4", 3)]), count=faces, offset=end + vertices * 24)
    check(bool(np.all(f["n"] == 3)), f"{path}: a face is not a triangle")
    return v[:, :3].astype(np.float64), f["i"].astype(np.int64)


def rasterize(points_cam, faces, K, w, h):
    """Depth (mm) of the model at each pixel centre (i + 0.5, as the toolkit's renderers draw with K); 0 outside."""
    depth = np.zeros((h, w))
    z = points_cam[:, 2]
    uv = (K @ (points_cam.T / z)).T[:, :2]
    ys, xs = np.mgrid[0:h, 0:w] + 0.5
    for tri in faces:
        if np.any(z[tri] <= 0):
            continue
        (x0, y0), (x1, y1), (x2, y2) = uv[tri]
        area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        if abs(area) < 1e-12:
            continue
        lo_x, hi_x = max(int(np.floor(min(x0, x1, x2))), 0), min(int(np.ceil(max(x0, x1, x2))), w)
        lo_y, hi_y = max(int(np.floor(min(y0, y1, y2))), 0), min(int(np.ceil(max(y0, y1, y2))), h)
        if lo_x >= hi_x or lo_y >= hi_y:
            continue
        px, py = xs[lo_y:hi_y, lo_x:hi_x], ys[lo_y:hi_y, lo_x:hi_x]
        b0 = ((x1 - px) * (y2 - py) - (x2 - px) * (y1 - py)) / area
        b1 = ((x2 - px) * (y0 - py) - (x0 - px) * (y2 - py)) / area
        b2 = 1 - b0 - b1
        inside = (b0 >= 0) & (b1 >= 0) & (b2 >= 0)
        # Perspective-correct depth: 1/z is linear on the screen.
        zz = 1.0 / (b0 / z[tri[0]] + b1 / z[tri[1]] + b2 / z[tri[2]])
        block = depth[lo_y:hi_y, lo_x:hi_x]
        closer = inside & ((block == 0) | (zz < block))
        block[closer] = zz[closer]
    return depth


def iou(a, b):
    union = np.logical_or(a, b).sum()
    return 1.0 if union == 0 else np.logical_and(a, b).sum() / union


def is_int_list(value, n):
    return isinstance(value, list) and len(value) == n and all(isinstance(x, int) for x in value)


def is_float_list(value, n):
    return isinstance(value, list) and len(value) == n and all(isinstance(x, (int, float)) for x in value)


def check_layout(out, writer):
    camera = json.load(open(f"{out}/camera.json"))
    check(sorted(camera) == ["cx", "cy", "depth_scale", "fx", "fy", "height", "width"], f"camera.json keys {sorted(camera)}")
    info = json.load(open(f"{out}/models/models_info.json"))
    ids = sorted(str(i + 1) for i in range(len(writer["objects"])))
    check(sorted(info) == ids, f"models_info ids {sorted(info)}, expected {ids}")
    for obj_id, entry in info.items():
        for key in ("diameter", "min_x", "min_y", "min_z", "size_x", "size_y", "size_z"):
            check(isinstance(entry.get(key), float), f"models_info {obj_id}.{key}: {entry.get(key)!r}")
        check(os.path.exists(f"{out}/models/obj_{int(obj_id):06d}.ply"), f"no model for obj {obj_id}")
    if writer.get("symmetries"):  # bop.yaml's: a can about z, a box in two discrete ways
        check(info["2"].get("symmetries_continuous") == [{"axis": [0.0, 0.0, 1.0], "offset": [0.0, 0.0, 0.0]}],
              f"can symmetry {info['2'].get('symmetries_continuous')}")
        discrete = info["1"].get("symmetries_discrete", [])
        check(len(discrete) == 2 and all(is_float_list(m, 16) for m in discrete), f"box symmetries {discrete}")
    scenes = sorted(glob.glob(f"{out}/train_pbr/*"))
    check([os.path.basename(s) for s in scenes] == ["000000", "000001"], f"scenes {scenes}")
    for scene in scenes:
        cams = json.load(open(f"{scene}/scene_camera.json"))
        gts = json.load(open(f"{scene}/scene_gt.json"))
        infos = json.load(open(f"{scene}/scene_gt_info.json"))
        check(sorted(cams) == ["0", "1", "2"] and sorted(gts) == sorted(cams) == sorted(infos), f"{scene}: image ids")
        for im, cam in cams.items():
            check(is_float_list(cam.get("cam_K"), 9) and is_float_list(cam.get("cam_R_w2c"), 9)
                  and is_float_list(cam.get("cam_t_w2c"), 3) and cam.get("depth_scale") == writer.get("depth_scale", 1.0), f"{scene} cam {im}: {cam}")
            for gt in gts[im]:
                check(is_float_list(gt.get("cam_R_m2c"), 9) and is_float_list(gt.get("cam_t_m2c"), 3)
                      and isinstance(gt.get("obj_id"), int), f"{scene} gt {im}: {gt}")
            for gi in infos[im]:
                check(is_int_list(gi.get("bbox_obj"), 4) and is_int_list(gi.get("bbox_visib"), 4)
                      and all(isinstance(gi.get(k), int) for k in ("px_count_all", "px_count_valid", "px_count_visib"))
                      and isinstance(gi.get("visib_fract"), float), f"{scene} gt_info {im}: {gi}")
            check(len(gts[im]) == len(infos[im]), f"{scene} {im}: gt and gt_info lengths")
        # The toolkit's save_json layout: one line per image id.
        text = open(f"{scene}/scene_gt.json").read()
        check(text.startswith('{\n  "0": [') and text.endswith("\n}"), f"{scene}/scene_gt.json layout: {text[:40]!r}")


def check_geometry(out):
    models = {int(p[-10:-4]): load_ply(p) for p in glob.glob(f"{out}/models/obj_*.ply")}
    checked = 0
    for scene in sorted(glob.glob(f"{out}/train_pbr/*")):
        cams = json.load(open(f"{scene}/scene_camera.json"))
        gts = json.load(open(f"{scene}/scene_gt.json"))
        infos = json.load(open(f"{scene}/scene_gt_info.json"))
        for im in sorted(cams, key=int):
            K = np.array(cams[im]["cam_K"]).reshape(3, 3)
            scale = cams[im]["depth_scale"]
            depth = np.asarray(Image.open(f"{scene}/depth/{int(im):06d}.png")).astype(np.float64) * scale
            rgb = Image.open(f"{scene}/rgb/{int(im):06d}.png")
            check(rgb.mode == "RGB", f"rgb mode {rgb.mode}")
            h, w = depth.shape
            for gt_id, (gt, gi) in enumerate(zip(gts[im], infos[im])):
                pts, faces = models[gt["obj_id"]]
                R = np.array(gt["cam_R_m2c"]).reshape(3, 3)
                t = np.array(gt["cam_t_m2c"])
                model_depth = rasterize(pts @ R.T + t, faces, K, w, h)
                projected = model_depth > 0
                mask = np.asarray(Image.open(f"{scene}/mask/{int(im):06d}_{gt_id:06d}.png")) == 255
                visib = np.asarray(Image.open(f"{scene}/mask_visib/{int(im):06d}_{gt_id:06d}.png")) == 255
                name = f"{scene[-6:]}/{im} obj {gt['obj_id']}"
                score = iou(projected, mask)
                check(score >= MIN_IOU, f"{name}: reprojected model vs mask IoU {score:.4f}")
                check(int(mask.sum()) == gi["px_count_all"] and int(visib.sum()) == gi["px_count_visib"],
                      f"{name}: pixel counts {mask.sum()}/{gi['px_count_all']} {visib.sum()}/{gi['px_count_visib']}")
                check(not np.any(visib & ~mask), f"{name}: visible pixels outside the silhouette")
                if gi["visib_fract"] > 0.999:
                    score = iou(projected, visib)
                    check(score >= MIN_IOU, f"{name}: unoccluded, reprojected model vs mask_visib IoU {score:.4f}")
                both = visib & projected & (depth > 0)
                if both.sum() > 20:
                    error = np.abs(depth[both] - model_depth[both])
                    check(np.percentile(error, 99) <= DEPTH_TOLERANCE_MM,
                          f"{name}: depth differs from the model's by {np.percentile(error, 99):.2f} mm (99th pct)")
                if gi["px_count_visib"]:
                    ys, xs = np.nonzero(visib)
                    check(gi["bbox_visib"] == [int(xs.min()), int(ys.min()), int(xs.max() - xs.min()), int(ys.max() - ys.min())],
                          f"{name}: bbox_visib {gi['bbox_visib']}")
                checked += 1
    check(checked >= 12, f"only {checked} object instances were checked")
    return checked


def main():
    binary, scene = (os.path.abspath(a) for a in sys.argv[1:3])
    with tempfile.TemporaryDirectory() as tmp:
        whole = f"{tmp}/whole"
        run(binary, scene, whole)
        if failures:
            return finish()
        with open(scene) as f:
            writer = yaml.safe_load(f)["writer"]
        check_layout(whole, writer)
        checked = check_geometry(whole)
        reference = dataset_hashes(whole)
        sharded = f"{tmp}/sharded"
        for i in range(3):
            run(binary, scene, sharded, "--shard", f"{i}/3") if i == 0 else subprocess.run(
                [binary, "run", scene, "--out", sharded, "--shard", f"{i}/3"], capture_output=True)
        p = subprocess.run([binary, "merge", sharded], capture_output=True, text=True)
        check(p.returncode == 0, f"merge: {p.stderr.strip()[-300:]}")
        check(dataset_hashes(sharded) == reference, "3 shards merged differ from the whole run")
        # --resume after losing a frame's files redoes that frame only, to the same bytes.
        os.remove(f"{whole}/train_pbr/000001/rgb/000001.png")
        p = subprocess.run([binary, "run", scene, "--out", whole, "--resume"], capture_output=True, text=True)
        check(p.returncode == 0, f"resume: {p.stderr.strip()[-300:]}")
        check(dataset_hashes(whole) == reference, "a resumed run differs from the whole run")
        return finish(f"ok: {checked} object instances reprojected onto their masks and depth")


if __name__ == "__main__":
    sys.exit(main())
