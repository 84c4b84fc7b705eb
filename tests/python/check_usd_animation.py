#!/usr/bin/python3
"""A USD stage's own animation plays (docs/usd.md, "Values and time"), read the way users read datasets.

  check_usd_animation.py BIN REPO stage    tests/data/usd/animated.usda (4 time codes a second; frame f
                                           shows time code f + 1): the time-sampled translate moves the
                                           box's 2D box to the right frame by frame, time-sampled
                                           visibility leaves no box and no pixels on frames 3 and 4, the
                                           flag's time-sampled points rise, the sun's sampled intensity
                                           brightens the box; the dataset is byte-identical with
                                           --threads 1 and 2 and as two shards merged; a behavior on top
                                           (a YAML scene mounting the stage, locationRandomizer every
                                           second update) pins the box on the updates it writes; a run
                                           without pixels restores the stage on stop.
  check_usd_animation.py BIN REPO corpus   ../shared/usd-corpus/arnold-usd/test_1726 (animated orient,
                                           24 tps) runs and its frames differ over time. Exit 77 when
                                           the corpus is absent.
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


def sdg(binary, *args, timeout=300):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=timeout)


def boxes_of(out, frame, label):
    """The tight 2D boxes labelled `label` in a BasicWriter frame."""
    boxes = np.load(os.path.join(out, f"bounding_box_2d_tight_{frame:04d}.npy"))
    labels = json.load(open(os.path.join(out, f"bounding_box_2d_tight_labels_{frame:04d}.json")))
    ids = {int(k) for k, v in labels.items() if v.get("class") == label}
    return [b for b in boxes if int(b["semanticId"]) in ids]


def label_pixels(out, frame, label):
    seg = np.asarray(Image.open(os.path.join(out, f"semantic_segmentation_{frame:04d}.png")).convert("RGBA"))
    labels = json.load(open(os.path.join(out, f"semantic_segmentation_labels_{frame:04d}.json")))
    count = 0
    for key, value in labels.items():
        if value.get("class") == label:
            colour = np.array([int(c) for c in key.strip("()").split(",")])
            count += int((seg == colour).all(axis=2).sum())
    return count


def run(binary, scene, out, *flags):
    result = sdg(binary, "run", scene, "--frames", "8", "--resolution", "96x96", "--out", out, *flags)
    check(result.returncode == 0, f"run {os.path.basename(scene)} {flags}: exit {result.returncode}: "
                                  f"{result.stderr[-600:]}")
    return result.returncode == 0


def check_stage(binary, repo, tmp):
    data = os.path.join(repo, "tests", "data", "usd")
    stage = os.path.join(data, "animated.usda")
    whole = os.path.join(tmp, "whole")
    if not run(binary, stage, whole, "--threads", "1"):
        return
    invisible = {3, 4}  # time codes 4 and 5
    centres, tops, brightness = [], [], []
    for frame in range(8):
        box = boxes_of(whole, frame, "box")
        pixels = label_pixels(whole, frame, "box")
        if frame in invisible:
            check(not box and pixels == 0, f"frame {frame}: the box is invisible (time code {frame + 1}) "
                                           f"but has {len(box)} boxes and {pixels} pixels")
            continue
        check(len(box) == 1 and pixels > 20, f"frame {frame}: expected the box, found {len(box)} boxes, "
                                             f"{pixels} pixels")
        if len(box) != 1:
            continue
        b = box[0]
        centres.append((frame, (int(b["x_min"]) + int(b["x_max"])) / 2))
        rgb = np.asarray(Image.open(os.path.join(whole, f"rgb_{frame:04d}.png")).convert("RGB")).astype(float)
        inner = rgb[int(b["y_min"]) + 2:int(b["y_max"]) - 1, int(b["x_min"]) + 2:int(b["x_max"]) - 1]
        brightness.append(inner.mean())
        flag = boxes_of(whole, frame, "flag")
        check(len(flag) == 1, f"frame {frame}: expected the flag's box, found {len(flag)}")
        if flag:
            tops.append(int(flag[0]["y_min"]))
    # Time code f + 1: x = -1.6 + 0.4 (f + 1), to the right every frame.
    xs = [x for _, x in centres]
    check(len(xs) == 6 and all(b > a + 2 for a, b in zip(xs, xs[1:])),
          f"the box's centre should move right frame by frame: {centres}")
    check(len(tops) == 6 and all(b < a for a, b in zip(tops, tops[1:])),
          f"the flag's points rise: its box's top row should fall frame by frame: {tops}")
    check(len(brightness) == 6 and brightness[-1] > brightness[0] * 1.3,
          f"the sun's intensity rises from 750 to 2500: the box's mean brightness {brightness}")

    # Determinism: --threads 2, and two shards merged, give the same bytes.
    reference = dataset_hashes(whole)
    threads = os.path.join(tmp, "threads2")
    if run(binary, stage, threads, "--threads", "2"):
        diff = sorted(n for n in set(reference) | set(dataset_hashes(threads))
                      if reference.get(n) != dataset_hashes(threads).get(n))
        check(not diff, f"--threads 2 differs from --threads 1: {diff[:6]}")
    shards = os.path.join(tmp, "shards")
    if run(binary, stage, shards, "--threads", "1", "--shard", "0/2") and \
            run(binary, stage, shards, "--threads", "2", "--shard", "1/2"):
        merged = sdg(binary, "merge", shards)
        check(merged.returncode == 0, f"merge: {merged.returncode} {merged.stderr[-300:]}")
        got = dataset_hashes(shards)
        diff = sorted(n for n in set(reference) | set(got) if reference.get(n) != got.get(n))
        check(not diff, f"two shards merged differ from the whole run: {diff[:6]}")

    # A behavior on top: locationRandomizer (a fixed absolute position, every second update) writes the
    # box's translate on updates 2, 4, 6, 8 (frames 1, 3, 5, 7; and once at play); the samples show on the rest.
    scene = os.path.join(tmp, "on_top.yaml")
    with open(scene, "w") as f:
        f.write(f"""version: 1
stage: {{timeCodesPerSecond: 4}}
capture: {{cameras: [/World/Cam]}}
writer: {{type: BasicWriter, rgb: true, bounding_box_2d_tight: true, semantic_segmentation: true}}
prims:
  /World:
    reference: {stage}
  /World/Box:
    behaviors:
      locationRandomizer:
        interval: 2
        frame:useRelativeFrame: false
        includeChildren: false
        range:minPosition: [0.0, 0.0, -5.0]
        range:maxPosition: [0.0, 0.0, -5.0]
""")
    on_top = os.path.join(tmp, "on_top")
    if run(binary, scene, on_top, "--threads", "1"):
        for frame in range(8):
            box = boxes_of(on_top, frame, "box")
            if frame % 2 == 1:  # pinned below the camera's view by the behavior
                check(not box, f"behavior on top, frame {frame}: the behavior moved the box out of view, "
                               f"found {len(box)} boxes")
            elif frame not in invisible:
                expected = dict(centres).get(frame)
                got = (int(box[0]["x_min"]) + int(box[0]["x_max"])) / 2 if len(box) == 1 else None
                check(got is not None and expected is not None and abs(got - expected) <= 1,
                      f"behavior on top, frame {frame}: the samples should show (centre {expected}), found {got}")

    # A run without pixels: the stage after stop equals the stage before play.
    result = sdg(binary, "run", stage, "--frames", "8", "--no-render", "--record", os.path.join(tmp, "rec.jsonl"))
    check(result.returncode == 0 and "differs from the stage before play" not in result.stderr,
          f"--no-render: exit {result.returncode}: {result.stderr[-400:]}")


def check_corpus(binary, repo, tmp):
    corpus = os.path.join(repo, "..", "shared", "usd-corpus", "arnold-usd")
    # test_1442's samples are a PointInstancer's arrays (expanded once, at the
    # start time code: not played) on a frame that is black: not a check of play.
    files = [os.path.join(corpus, "test_1726", "test.usdz")]
    files = [f for f in files if os.path.isfile(f)]
    if not files:
        print(f"skipped: no corpus files under {corpus}")
        sys.exit(77)
    for path in files[:2]:
        out = os.path.join(tmp, os.path.basename(os.path.dirname(path)))
        result = sdg(binary, "run", path, "--frames", "12", "--resolution", "64x64", "--out", out)
        check(result.returncode == 0, f"run {path}: exit {result.returncode}: {result.stderr[-400:]}")
        if result.returncode != 0:
            continue
        images = sorted(glob.glob(os.path.join(out, "rgb_*.png")))
        first = np.asarray(Image.open(images[0]).convert("RGB")).astype(int)
        last = np.asarray(Image.open(images[-1]).convert("RGB")).astype(int)
        check(np.abs(first - last).max() > 0, f"{path}: the first and last frames are the same: nothing played")


def main():
    binary, repo, mode = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2]), sys.argv[3]
    with tempfile.TemporaryDirectory() as tmp:
        if mode == "stage":
            check_stage(binary, repo, tmp)
        else:
            check_corpus(binary, repo, tmp)
    return finish(f"usd animation ({mode}): ok")


if __name__ == "__main__":
    sys.exit(main())
