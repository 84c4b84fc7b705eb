#!/usr/bin/python3
"""sdgbehave.data on the BopWriter's and the flow annotators' output of one
run (tests/data/data_package/bop_flow.yaml), each checked against the
BasicWriter's files of the same frames:

- Dataset(out).bop() reads one scene per iteration and one image per frame;
  each instance's model, projected with cam_K, cam_R_m2c and cam_t_m2c,
  spans its full mask (pixel centres at +0.5, BOP's convention); the BOP
  rgb is the BasicWriter's rgb; the BOP depth (mm, depth_scale) is the
  distance to the image plane; cam_K is Camera.K moved by half a pixel;
- a run of two iterations, whole and as two merged shards, reads as the
  same BOP scenes and images in the same order;
- forward_flow, backward_flow and motion_vectors read with their documented
  shapes; an iteration's first frame has no backward motion and its last no
  forward flow; motion_vectors' last two channels are 0.

Exits 77 (skipped) while the sdgbehave binary has no BopWriter or flow
annotators (issue 32, items 1 and 2).

usage: check_data_bop_flow.py SDGBEHAVE_BINARY SOURCE_DIR (PYTHONPATH holds python/)"""
import os
import subprocess
import sys
import tempfile

import numpy as np

from checklib import check, finish
from sdgbehave.data import Dataset


def check_bop(data):
    bop = data.bop()
    check(bop.splits == ["train_pbr"] and bop.scene_ids("train_pbr") == [0], f"splits {bop.splits}")
    scene = bop.scene("train_pbr", 0)
    check(scene.image_ids == [0, 1, 2], f"image ids {scene.image_ids}")
    model = bop.model(1)
    for image, frame in zip(scene, data):
        check(np.array_equal(image.rgb(), frame.rgb()), f"image {image.image_id}: BOP rgb differs from rgb_X.png")
        camera = frame.camera_params()
        check(np.allclose(image.K, camera.K + np.array([[0, 0, 0.5], [0, 0, 0.5], [0, 0, 0]])),
              f"cam_K {image.K} vs Camera.K {camera.K} + 0.5")
        reference = frame.distance_to_image_plane() * 1000.0
        depth = image.depth()
        valid = (depth > 0) & np.isfinite(reference)
        check(valid.sum() > 0.9 * depth.size and np.abs(depth - reference)[valid].max() <= image.depth_scale,
              f"image {image.image_id}: BOP depth differs from distance_to_image_plane")
        check(len(image.objects) == 2 and all(o["obj_id"] == 1 for o in image.objects), f"{image.objects}")
        for gt, instance in enumerate(image.objects):
            pixels, depths = image.project(model["vertices"], gt)
            ys, xs = np.nonzero(image.mask(gt))
            lo, hi = pixels.min(axis=0), pixels.max(axis=0)
            first, last = np.array([xs.min(), ys.min()]) + 0.5, np.array([xs.max(), ys.max()]) + 0.5
            check(np.all(lo - 0.01 <= first) and np.all(last <= hi + 0.01) and np.all(first - lo < 1.5)
                  and np.all(hi - last < 1.5) and np.all(depths > 0),
                  f"image {image.image_id} gt {gt}: the model projects to {lo}..{hi}, mask pixel centres "
                  f"{first}..{last}")
            check(image.mask_visib(gt).sum() == instance["px_count_visib"], f"px_count_visib of gt {gt}")


def check_flow(data):
    frames = list(data)
    for frame in frames:
        forward, backward, motion = frame.forward_flow(), frame.backward_flow(), frame.motion_vectors()
        check(forward.shape == (72, 96, 2) and backward.shape == (72, 96, 2) and motion.shape == (72, 96, 4),
              f"flow shapes {forward.shape} {backward.shape} {motion.shape}")
        check(not motion[..., 2:].any(), "motion_vectors' z and w are not 0")
        # Isaac's x (left) and y (up) are the backward flow's column and row (docs/writers.md).
        check(np.array_equal(motion[..., 0], backward[..., 1]) and np.array_equal(motion[..., 1], backward[..., 0]),
              f"frame {frame.number}: motion_vectors are not (backward column, backward row)")
    check(not frames[0].backward_flow().any() and not frames[0].motion_vectors().any(),
          "the first frame has backward motion")
    check(not frames[-1].forward_flow().any(), "the last frame has forward flow")
    check(frames[0].forward_flow().any() and frames[-1].backward_flow().any(), "the turning crate does not move")


def check_bop_shards(binary, scene, work):
    """Two iterations run whole and as two merged shards read as the same BOP scenes and images."""
    whole, sharded = os.path.join(work, "whole"), os.path.join(work, "sharded")
    plan = ["--iterations", "2", "--frames", "2", "--quiet"]
    subprocess.run([binary, "run", scene, "--out", whole, *plan], check=True, capture_output=True)
    for shard in ("1/2", "0/2"):
        subprocess.run([binary, "run", scene, "--out", sharded, "--shard", shard, *plan], check=True,
                       capture_output=True)
    subprocess.run([binary, "merge", sharded, "--quiet"], check=True, capture_output=True)
    a, b = Dataset(whole).bop(), Dataset(sharded).bop()
    check(a.scene_ids("train_pbr") == b.scene_ids("train_pbr") == [0, 1], f"scenes {b.scene_ids('train_pbr')}")
    for x, y in zip((i for s in a.scenes("train_pbr") for i in s), (i for s in b.scenes("train_pbr") for i in s)):
        check(x.image_id == y.image_id and np.array_equal(x.rgb(), y.rgb()) and np.array_equal(x.depth(), y.depth())
              and [o["obj_id"] for o in x.objects] == [o["obj_id"] for o in y.objects],
              f"{y}: the sharded run's image differs from the whole run's")


def main():
    binary, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    scene = os.path.join(source, "tests/data/data_package/bop_flow.yaml")
    probe = subprocess.run([binary, "validate", scene], capture_output=True, text=True)
    if probe.returncode == 2 and any(w in probe.stderr for w in ("'BopWriter'", "'forward_flow'", "'motion_vectors'")):
        print("skipped: this sdgbehave has no BopWriter or flow annotators yet:\n" + probe.stderr)
        return 77
    with tempfile.TemporaryDirectory(prefix="sdg_bop_flow_") as work:
        out = os.path.join(work, "data")
        result = subprocess.run([binary, "run", scene, "--out", out, "--quiet"], capture_output=True, text=True)
        if result.returncode != 0:
            print(f"FAIL: sdgbehave run exited {result.returncode}:\n{result.stderr}")
            return 1
        data = Dataset(out)
        check(len(data) == 3, f"{len(data)} frames")
        check_bop(data)
        check_flow(data)
        check_bop_shards(binary, scene, work)
    return finish("ok: BOP scenes and flow read, consistent with the BasicWriter's files")


if __name__ == "__main__":
    sys.exit(main())
