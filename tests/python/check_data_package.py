#!/usr/bin/python3
"""sdgbehave.data (python/) on small datasets the CLI writes:

- every annotator of tests/data/writer/annotators.yaml reads into numpy with
  the documented dtypes and shapes; colourised and raw segmentation decode to
  the same ids; tight boxes are the bounds of the instance masks; 3D box
  corners projected with the camera land on the loose boxes, through the
  projection matrix and through K in OpenCV axes alike;
- a sharded and merged run reads as the same frames in the same order as a
  whole run; two cameras, in both folder layouts, read as (frame, camera) in
  order;
- a folder that is not a finished dataset is refused with a clear error: no
  manifest, an unmerged sharded run, a file changed, missing or truncated, an
  incomplete manifest; `sdgbehave verify` fails on the same folders;
- a missing annotator names the writer option that makes it.

usage: check_data_package.py SDGBEHAVE_BINARY SOURCE_DIR (PYTHONPATH holds python/)"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

from checklib import check, finish
from sdgbehave.data import Dataset, DatasetError, MissingAnnotation


def run(binary, scene, out, *extra):
    result = subprocess.run([binary, "run", scene, "--out", out, "--quiet", *extra], capture_output=True, text=True)
    if result.returncode != 0:
        raise SystemExit(f"FAIL: sdgbehave run {scene} {' '.join(extra)} exited {result.returncode}:\n{result.stderr}")


def refused(folder, words, **kwargs):
    """The error opening `folder` (failing when it opens or the message lacks a word)."""
    try:
        Dataset(folder, **kwargs)
    except DatasetError as e:
        for word in words:
            check(word in str(e), f"{folder}: the error lacks {word!r}:\n{e}")
        return str(e)
    check(False, f"{folder} opened, expected a DatasetError with {words}")
    return ""


def verify_exit(binary, folder):
    return subprocess.run([binary, "verify", folder], capture_output=True, text=True).returncode


def check_annotators(binary, source, work):
    scene = os.path.join(source, "tests/data/writer/annotators.yaml")
    colour, raw = os.path.join(work, "colour"), os.path.join(work, "raw")
    run(binary, scene, colour, "--resolution", "96x72", "--frames", "2")
    run(binary, scene, raw, "--resolution", "96x72", "--frames", "2",
        "--set", "writer.BasicWriter.colorize_semantic_segmentation=false",
        "--set", "writer.BasicWriter.colorize_instance_id_segmentation=false")
    data, plain = Dataset(colour), Dataset(raw)
    check(len(data) == 2 and [f.number for f in data] == [0, 1], f"frames {[f.number for f in data]}")
    check(data.cameras == ["Camera"] and data.resolution == (96, 72) and data.seed == 4,
          f"cameras {data.cameras}, resolution {data.resolution}, seed {data.seed}")
    check(data.classes() == ["cover", "crate", "floor"], f"classes {data.classes()}")
    for frame, other in zip(data, plain):
        rgb = frame.rgb()
        check(rgb.shape == (72, 96, 3) and rgb.dtype == np.uint8, f"rgb {rgb.shape} {rgb.dtype}")
        check(frame.rgba().shape == (72, 96, 4), "rgba")
        semantic, semantic_raw = frame.semantic_segmentation(), other.semantic_segmentation()
        check(semantic.ids.dtype == np.uint32 and semantic.ids.shape == (72, 96), f"semantic {semantic.ids.dtype}")
        check(np.array_equal(semantic.ids, semantic_raw.ids), "colourised and raw semantic ids differ")
        check(semantic.labels == semantic_raw.labels, f"labels {semantic.labels} vs {semantic_raw.labels}")
        names = {v.get("class") for v in semantic.labels.values()}
        check({"floor", "crate", "BACKGROUND"} <= names or {"floor", "crate"} <= names, f"semantic labels {names}")
        ids_raw = other.instance_id_segmentation()
        ids_colour = frame.instance_id_segmentation()
        check(np.array_equal(ids_raw.ids, ids_colour.ids) and ids_raw.paths == ids_colour.paths,
              "colourised and raw instance ids differ")
        check("/World/Ball" in ids_colour.paths.values(), f"instance id paths {ids_colour.paths}")

        tight, loose = frame.bounding_box_2d_tight(), frame.bounding_box_2d_loose()
        check(tight.xyxy.dtype == np.int32 and tight.xyxy.shape == (len(tight), 4), f"tight {tight.xyxy.shape}")
        check(set(tight.label_names()) == {"floor", "crate", "cover"}, f"tight labels {tight.label_names()}")
        floats = tight.xyxy_float()
        check(floats.dtype == np.float32 and np.array_equal(floats[:, 2:], tight.xyxy[:, 2:] + 1), "xyxy_float")
        for sid in tight.semantic_ids:
            check(np.any(semantic.ids == sid), f"semantic id {sid} of a box is not in the semantic mask")
        instances = frame.instance_segmentation()
        id_of = {path: ident for ident, path in instances.paths.items()}
        for box, path in zip(tight.xyxy, tight.prim_paths):
            ys, xs = np.nonzero(instances.mask(id_of[path]))
            check(tuple(box) == (xs.min(), ys.min(), xs.max(), ys.max()), f"tight box of {path} {box}")
        check(instances.labels[id_of["/World/Free"]] == {"class": "crate"}, f"instance labels {instances.labels}")
        occlusion = dict(zip(tight.prim_paths, tight.occlusion))
        check(abs(occlusion["/World/Back"] - 0.5) <= 0.06, f"occlusion {occlusion}")

        camera = frame.camera_params()
        check(camera.resolution == (96, 72) and camera.K is not None, f"camera {camera.resolution}")
        boxes = frame.bounding_box_3d()
        loose_of = dict(zip(loose.prim_paths, loose.xyxy))
        for corners, path in zip(boxes.corners(), boxes.prim_paths):
            if path not in ("/World/Free", "/World/Back"):
                continue
            pixels, depth = camera.project(corners)
            check(np.all(depth > 0), f"{path}: corners behind the camera")
            # OpenCV pinhole: K @ (R|t) in OpenCV axes gives the same pixels.
            cv = (np.c_[corners, np.ones(8)] @ camera.world_to_camera_cv.T)[:, :3]
            uv = (cv @ camera.K.T)[:, :2] / cv[:, 2:3]
            check(np.abs(uv - pixels).max() < 1e-6, f"{path}: K projects to {uv} vs {pixels}")
            # Pixel centres at integers: a covered pixel's centre lies within the projected corners'
            # extent, and the extent's ends (corner tips, thin wedges) within 1.5 px of a covered one.
            lo, hi = pixels.min(axis=0), pixels.max(axis=0)
            box = loose_of[path].astype(np.float64)
            check(np.all(lo - 0.01 <= box[:2]) and np.all(box[2:] <= hi + 0.01) and np.all(box[:2] - lo < 1.5)
                  and np.all(hi - box[2:] < 1.5), f"{path}: 3D box projects to {lo}..{hi}, loose box {box}")
        depth = frame.depth()
        check(depth.dtype == np.float32 and depth.shape == (72, 96), f"depth {depth.shape}")
        hit = semantic.ids != 0
        check(np.all(np.isfinite(depth[hit])) and np.all(np.isinf(depth[~hit])), "depth finite exactly where hit")
        check(np.array_equal(frame.distance_to_image_plane(), depth), "depth() is distance_to_image_plane")
        check(frame.distance_to_camera().shape == (72, 96), "distance_to_camera")
        normals = frame.normals()
        lengths = np.linalg.norm(normals[hit], axis=1)
        check(np.all(np.abs(lengths - 1) < 0.02), f"normals lengths {lengths.min()}..{lengths.max()}")
        cloud = frame.pointcloud()
        check(cloud["points"].shape[1] == 3 and len(cloud["rgb"]) == len(cloud["points"]), "pointcloud")
        check(frame.occlusion().dtype.names == ("instanceId", "semanticId", "occlusionRatio"), "occlusion")
        try:
            frame.hdr_color()
            check(False, "hdr_color read from a rasterized run")
        except MissingAnnotation as e:
            check("writer.hdr_color: true" in str(e), f"missing annotation message: {e}")
    coco = data.coco()
    check(len(coco["images"]) == 2, f"coco images {len(coco['images'])}")
    return colour


def check_shards(binary, source, work):
    scene = os.path.join(source, "tests/data/scale/shards.yaml")
    whole, sharded = os.path.join(work, "whole"), os.path.join(work, "sharded")
    run(binary, scene, whole, "--frames", "2", "--iterations", "2")
    for shard in ("1/3", "0/3", "2/3"):
        run(binary, scene, sharded, "--frames", "2", "--iterations", "2", "--shard", shard)
    refused(sharded, ["no manifest.jsonl", "manifest.shard-", "sdgbehave merge"])
    check(verify_exit(binary, sharded) == 0, "verify of the unmerged shards (it reads their manifests)")
    subprocess.run([binary, "merge", sharded, "--quiet"], check=True, capture_output=True)
    a, b = Dataset(whole), Dataset(sharded)
    check([f.number for f in b] == [0, 1, 2, 3], f"merged frames {[f.number for f in b]}")
    for x, y in zip(a, b):
        check(np.array_equal(x.rgb(), y.rgb()) and np.array_equal(x.semantic_segmentation().ids,
                                                                  y.semantic_segmentation().ids),
              f"frame {x.number} differs between the whole and the sharded run")


def check_cameras(binary, source, work):
    scene = os.path.join(source, "scenes/examples/writer_multi_camera.yaml")
    for layout, extra in (("folders", ()), ("common", ("--set", "writer.use_common_output_dir=true"))):
        out = os.path.join(work, "cameras_" + layout)
        run(binary, scene, out, "--resolution", "64x48", *extra)
        data = Dataset(out)
        order = [(f.number, f.camera) for f in data]
        check(order == [(0, "Left"), (0, "Right"), (1, "Left"), (1, "Right")], f"{layout}: order {order}")
        for f in data:
            check(f.rgb().shape == (48, 64, 3) and len(f.bounding_box_2d_tight()) > 0, f"{layout}: {f}")
            check(f.camera in f.path("rgb"), f"{layout}: {f.path('rgb')} is not the {f.camera} camera's")
        right = Dataset(out, camera="Right")
        check([f.camera for f in right] == ["Right", "Right"], "camera= keeps one render product")
        check(not np.array_equal(data.frame(0, "Left").rgb(), data.frame(0, "Right").rgb()), "two cameras alike")
        refused(out, ["no render product 'Middle'", "Left, Right"], camera="Middle")


def check_refusals(binary, dataset, work):
    def copy(name):
        target = os.path.join(work, name)
        shutil.copytree(dataset, target)
        return target

    empty = os.path.join(work, "empty")
    os.makedirs(empty)
    refused(empty, ["not a finished sdgbehave dataset", "no manifest.jsonl"])
    refused(os.path.join(work, "nonexistent"), ["not a folder"])

    changed = copy("changed")
    path = os.path.join(changed, "rgb_0001.png")
    data = bytearray(open(path, "rb").read())
    data[-20] ^= 0xFF
    open(path, "wb").write(bytes(data))
    refused(changed, ["rgb_0001.png: sha256 differs from the manifest"])
    check(len(Dataset(changed, verify=False)) == 2, "verify=False opens a folder whose bytes changed")
    check(verify_exit(binary, changed) == 1, "sdgbehave verify accepted a changed file")

    missing = copy("missing")
    os.remove(os.path.join(missing, "semantic_segmentation_0000.png"))
    refused(missing, ["semantic_segmentation_0000.png: missing"], verify=False)
    check(verify_exit(binary, missing) == 1, "sdgbehave verify accepted a missing file")

    truncated = copy("truncated")
    with open(os.path.join(truncated, "distance_to_camera_0000.npy"), "r+b") as f:
        f.truncate(100)
    refused(truncated, ["distance_to_camera_0000.npy: 100 bytes, the manifest says"], verify=False)

    incomplete = copy("incomplete")
    manifest = os.path.join(incomplete, "manifest.jsonl")
    lines = open(manifest).read().splitlines(keepends=True)
    open(manifest, "w").write("".join(lines[:-1]))
    refused(incomplete, ["the run is incomplete (1 of 2", "frame 1 of Camera", "--resume"])
    check(verify_exit(binary, incomplete) == 1, "sdgbehave verify accepted an incomplete run")


def main():
    binary, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    with tempfile.TemporaryDirectory(prefix="sdg_data_") as work:
        dataset = check_annotators(binary, source, work)
        check_refusals(binary, dataset, work)
        check_shards(binary, source, work)
        check_cameras(binary, source, work)
    return finish("ok: sdgbehave.data reads every annotator, shards, cameras; refuses unfinished folders")


if __name__ == "__main__":
    sys.exit(main())
