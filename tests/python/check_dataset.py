#!/usr/bin/python3
"""A BasicWriter dataset read the way users read it (numpy, PIL, json):
names, dtypes and shapes; tight boxes equal the instance masks' bounds;
loose boxes contain them; occlusion 0 for a free cube and about 0.5 for a
half-covered one; 3D boxes projected with camera_params land on the loose
boxes; distance to the camera vs the image plane follows the ray angle;
colours follow Replicator's hash; and the bytes do not depend on the thread
count, while another seed changes them."""
import glob
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

from checklib import check, dataset_hashes, finish

BOX2D = [("semanticId", "<u4"), ("x_min", "<i4"), ("y_min", "<i4"), ("x_max", "<i4"), ("y_max", "<i4"),
         ("occlusionRatio", "<f4")]
BOX3D = [("semanticId", "<u4"), ("x_min", "<f4"), ("y_min", "<f4"), ("z_min", "<f4"), ("x_max", "<f4"),
         ("y_max", "<f4"), ("z_max", "<f4"), ("transform", "<f4", (4, 4)), ("occlusionRatio", "<f4")]
def run(binary, scene, out, *extra):
    subprocess.run([binary, "run", scene, "--out", out, *extra], check=True, capture_output=True)


def replicator_color(i):
    if i == 0:
        return (0, 0, 0, 0)
    if i == 1:
        return (0, 0, 0, 255)
    h = i
    h ^= h >> 16
    h = (h * 0x85EBCA6B) & 0xFFFFFFFFFFFFFFFF
    h ^= h >> 13
    h = (h * 0xC2B2AE35) & 0xFFFFFFFFFFFFFFFF
    h ^= h >> 16
    hue = math.fmod(i * (1 / 1.618033988749895), 1.0)
    hue = math.fmod(hue + 0.1 * (h & 0xFFFF) / 65536.0, 1.0)
    sat = 0.7 + 0.3 * ((h >> 16) & 0xFF) / 255.0
    val = 0.8 + 0.2 * ((h >> 8) & 0xFF) / 255.0
    sector = int(hue * 6) % 6
    f = hue * 6 - int(hue * 6)
    p, q, t = val * (1 - sat), val * (1 - sat * f), val * (1 - sat * (1 - f))
    r, g, b = [(val, t, p), (q, val, p), (p, val, t), (p, q, val), (t, p, val), (val, p, q)][sector]
    return (int(r * 255), int(g * 255), int(b * 255), 255)


def check_frame(out, x):
    rgb = np.asarray(Image.open(f"{out}/rgb_{x}.png"))
    check(rgb.shape == (240, 320, 4) and rgb.dtype == np.uint8, f"rgb {rgb.shape}")
    for kind in ("distance_to_camera", "distance_to_image_plane"):
        d = np.load(f"{out}/{kind}_{x}.npy")
        check(d.dtype == np.float32 and d.shape == (240, 320), f"{kind} {d.dtype} {d.shape}")
        grey = Image.open(f"{out}/{kind}_{x}.png")
        check(grey.mode == "L" and np.asarray(grey).max() == 254, f"{kind} png {grey.mode}")
    # Distances: camera vs image plane follow the ray angle of the intrinsics.
    params = json.load(open(f"{out}/camera_params_{x}.json"))
    dc, dp = np.load(f"{out}/distance_to_camera_{x}.npy"), np.load(f"{out}/distance_to_image_plane_{x}.npy")
    proj = np.array(params["cameraProjection"]).reshape(4, 4).T
    for (px, py) in [(5, 5), (160, 120), (300, 200)]:
        nx, ny = (px + 0.5) / 320 * 2 - 1, 1 - (py + 0.5) / 240 * 2
        ray = np.array([nx / proj[0, 0], ny / proj[1, 1], 1.0])
        check(abs(dc[py, px] / dp[py, px] - np.linalg.norm(ray)) < 1e-4, f"distance ratio at {px},{py}")
    check(params["renderProductResolution"] == [320, 240], "resolution in camera params")
    # Segmentation: colours from the hash, labels keyed by colour text.
    sem = np.asarray(Image.open(f"{out}/semantic_segmentation_{x}.png"))
    labels = json.load(open(f"{out}/semantic_segmentation_labels_{x}.json"))
    colours = {tuple(c) for c in sem.reshape(-1, 4)}
    for key in labels:
        check(tuple(int(v) for v in key.strip("()").split(", ")) in colours, f"label colour {key} not in image")
    tight = np.load(f"{out}/bounding_box_2d_tight_{x}.npy")
    loose = np.load(f"{out}/bounding_box_2d_loose_{x}.npy")
    check(tight.dtype == np.dtype(BOX2D) and loose.dtype == np.dtype(BOX2D), "box dtypes")
    for sid in set(tight["semanticId"]):
        check(replicator_color(int(sid)) in colours, f"semantic id {sid} colour not in image")
    # Tight boxes are the bounds of each entity's instance mask.
    inst = np.asarray(Image.open(f"{out}/instance_segmentation_{x}.png")).astype(np.uint32)
    mapping = json.load(open(f"{out}/instance_segmentation_mapping_{x}.json"))
    id_of = {path: int(key) for key, path in mapping.items()}
    paths = json.load(open(f"{out}/bounding_box_2d_tight_prim_paths_{x}.json"))
    check(len(paths) == len(tight), "prim paths align with rows")
    for row, path in zip(tight, paths):
        ys, xs = np.nonzero(inst == id_of[path])
        check((row["x_min"], row["y_min"], row["x_max"], row["y_max"]) == (xs.min(), ys.min(), xs.max(), ys.max()),
              f"tight box of {path}: {row} vs mask bounds")
    loose_paths = json.load(open(f"{out}/bounding_box_2d_loose_prim_paths_{x}.json"))
    loose_by_path = dict(zip(loose_paths, loose))
    for row, path in zip(tight, paths):
        l = loose_by_path[path]
        check(l["x_min"] <= row["x_min"] and l["y_min"] <= row["y_min"] and l["x_max"] >= row["x_max"]
              and l["y_max"] >= row["y_max"], f"loose box of {path} does not contain the tight box")
    occ = dict(zip(paths, tight["occlusionRatio"]))
    check(abs(occ["/World/Free"]) < 1e-6, f"free cube occlusion {occ['/World/Free']}")
    check(abs(occ["/World/Back"] - 0.5) <= 0.05, f"half-covered cube occlusion {occ['/World/Back']}")
    # 3D boxes projected with the camera parameters land on the loose boxes.
    b3 = np.load(f"{out}/bounding_box_3d_{x}.npy")
    check(b3.dtype == np.dtype(BOX3D), "3D box dtype")
    paths3 = json.load(open(f"{out}/bounding_box_3d_prim_paths_{x}.json"))
    view = np.array(params["cameraViewTransform"]).reshape(4, 4)
    projection = np.array(params["cameraProjection"]).reshape(4, 4)
    for row, path in zip(b3, paths3):
        if path not in ("/World/Free", "/World/Back"):
            continue
        corners = np.array([[xx, yy, zz, 1.0] for xx in (row["x_min"], row["x_max"]) for yy in (row["y_min"], row["y_max"])
                            for zz in (row["z_min"], row["z_max"])])
        clip = corners @ row["transform"] @ view @ projection  # row vectors, Gf layout
        ndc = clip[:, :2] / clip[:, 3:4]
        px, py = (ndc[:, 0] + 1) * 320 / 2, (1 - ndc[:, 1]) * 240 / 2
        l = loose_by_path[path]
        check(abs(px.min() - l["x_min"]) <= 1 and abs(px.max() - (l["x_max"] + 1)) <= 1
              and abs(py.min() - l["y_min"]) <= 1 and abs(py.max() - (l["y_max"] + 1)) <= 1,
              f"3D box of {path} projects to {px.min():.1f}..{px.max():.1f} x {py.min():.1f}..{py.max():.1f}, loose {l}")
    o = np.load(f"{out}/occlusion_{x}.npy")
    check(o.dtype == np.dtype([("instanceId", "<u4"), ("semanticId", "<u4"), ("occlusionRatio", "<f4")]), "occlusion dtype")
    normals = np.asarray(Image.open(f"{out}/normals_{x}.png"))
    check(normals.shape == (240, 320, 4), "normals png")
    pc = np.load(f"{out}/pointcloud_{x}.npy")
    check(pc.dtype == np.float32 and pc.shape[1] == 3 and len(pc) > 100, f"pointcloud {pc.shape}")
    check(np.load(f"{out}/pointcloud_rgb_{x}.npy").shape == (len(pc), 4), "pointcloud rgb")
    check(abs(pc[:, 2].min()) < 0.01, "the floor's points lie at z = 0")
    idmap = json.load(open(f"{out}/instance_id_segmentation_mapping_{x}.json"))
    check("/World/Ball" in idmap.values(), "instance id mapping names the unlabelled sphere")


def decode_rle(counts, height, width):
    flat = np.zeros(height * width, dtype=np.uint8)
    position, value = 0, 0
    for run in counts:
        flat[position:position + run] = value
        position += run
        value = 1 - value
    check(position == height * width, "RLE counts do not cover the image")
    return flat.reshape(width, height).T  # column-major, as COCO stores it


def check_coco(out):
    coco = json.load(open(f"{out}/coco_instances.json"))
    check(not glob.glob(f"{out}/*.partial"), "COCO stream files left behind")
    ids = [a["id"] for a in coco["annotations"]]
    check(len(ids) == len(set(ids)) and len(ids) > 0, "annotation ids are not unique")
    check(len({i["id"] for i in coco["images"]}) == 3, "one image per frame")
    names = {c["name"] for c in coco["categories"]}
    check(names == {"floor", "crate", "cover"}, f"categories {names}")
    images = {i["id"]: i["file_name"] for i in coco["images"]}
    for a in coco["annotations"]:
        x = images[a["image_id"]][4:8]
        check(os.path.exists(f"{out}/{images[a['image_id']]}"), "image file named by COCO exists")
        h, w = a["segmentation"]["size"]
        mask = decode_rle(a["segmentation"]["counts"], h, w)
        inst = np.asarray(Image.open(f"{out}/instance_segmentation_{x}.png")).astype(np.uint32)
        mapping = json.load(open(f"{out}/instance_segmentation_mapping_{x}.json"))
        expected = inst == {p: int(k) for k, p in mapping.items()}[a["prim_path"]]
        check((mask.astype(bool) == expected).all(), f"RLE of {a['prim_path']} differs from its instance mask")
        ys, xs = np.nonzero(expected)
        check(a["bbox"] == [int(xs.min()), int(ys.min()), int(xs.max() - xs.min() + 1), int(ys.max() - ys.min() + 1)],
              f"COCO bbox of {a['prim_path']}")
        check(a["area"] == int(expected.sum()) and a["iscrowd"] == 0, "COCO area / iscrowd")


def main():
    binary, scene = sys.argv[1:3]
    with tempfile.TemporaryDirectory() as tmp:
        run(binary, scene, f"{tmp}/one", "--threads", "1")
        run(binary, scene, f"{tmp}/four", "--threads", "4")
        run(binary, scene, f"{tmp}/again", "--threads", "2")
        run(binary, scene, f"{tmp}/other", "--seed", "5")
        one, four, again, other = (dataset_hashes(f"{tmp}/{n}") for n in ("one", "four", "again", "other"))
        check(one == four, "threads 1 and 4 wrote different bytes")
        check(one == again, "the same seed wrote different bytes")
        check(one != other, "another seed wrote the same bytes")
        check(open(f"{tmp}/one/metadata.txt").read() ==
              '{"name": "BasicWriter", "version": "0.0.2", "replicator_global_seed:": 4}', "metadata.txt")
        check(not glob.glob(f"{tmp}/one/**/*.tmp-*", recursive=True), "temporary files left behind")
        for x in ("0000", "0001", "0002"):
            check_frame(f"{tmp}/one", x)
        # The dataset's own files (the hashes above also cover .sdgbehave/):
        # metadata, 29 per frame, COCO, contact sheet, manifest.
        visible = [name for name in one if not name.startswith(".sdgbehave")]
        check(len(visible) == 1 + 3 * 29 + 3, f"{len(visible)} files")
        check_coco(f"{tmp}/one")
        summary = json.load(open(f"{tmp}/one/run_summary.json"))
        check(summary["frames"] == 3 and summary["seed"] == 4 and summary["files_written"] == len(visible) + 1,  # + run_summary.json
              f"run summary {summary}")
        check(set(summary["seconds"]) == {"load", "preroll", "behaviors", "render", "annotate",
                                          "encode_write_all_threads", "total"}, "summary stages")
        check(summary["renderer"]["backend"] == "osmesa" and summary["peak_rss_mb"] > 0, "summary renderer, memory")
    return finish()


if __name__ == "__main__":
    sys.exit(main())
