#!/usr/bin/python3
"""USD stages end to end, read the way users read datasets (numpy, PIL, json).

  check_usd_stage.py BIN REPO stage     tests/data/usd: cube_camera.usda runs to a dataset whose rgb
                                        shows the red cube where its box says, labelled `box` from the
                                        layer's Isaac semantics; --camera picks a camera or exits 2
                                        naming the flag; a broken layer fails validate with exit 2 at
                                        its file:line:col; flatten writes a YAML scene that inspects and
                                        runs the same; studio opens the stage (tree and preview) and
                                        refuses edits (it edits YAML only).
  check_usd_stage.py BIN REPO samples   every .usd/.usda/.usdz under <repo>/../shared/usd-samples:
                                        validate exits 0 or a clean 2; Teapot and one .usdz run to a
                                        dataset whose rgb is not empty. Exit 77 when the samples are absent.
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
from studio_server import Studio


def sdg(binary, *args, timeout=300):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=timeout)


def rgb_is_not_empty(folder, what):
    """The first rgb image exists and is more than one flat colour."""
    images = sorted(glob.glob(os.path.join(folder, "rgb_*.png")))
    check(images, f"{what}: no rgb image in {folder}")
    if not images:
        return
    rgb = np.asarray(Image.open(images[0]).convert("RGB")).astype(int)
    spread = rgb.reshape(-1, 3).max(axis=0) - rgb.reshape(-1, 3).min(axis=0)
    check(spread.max() > 30, f"{what}: {images[0]} is flat (channel ranges {spread.tolist()})")


def check_stage(binary, repo, tmp):
    data = os.path.join(repo, "tests", "data", "usd")
    out = os.path.join(tmp, "cube")
    result = sdg(binary, "run", os.path.join(data, "cube_camera.usda"), "--frames", "1", "--out", out)
    check(result.returncode == 0, f"run cube_camera.usda: exit {result.returncode}: {result.stderr}")
    if result.returncode != 0:
        return
    rgb = np.asarray(Image.open(os.path.join(out, "rgb_0000.png")).convert("RGB")).astype(int)
    boxes = np.load(os.path.join(out, "bounding_box_2d_tight_0000.npy"))
    labels = json.load(open(os.path.join(out, "bounding_box_2d_tight_labels_0000.json")))
    names = {int(k): v.get("class") for k, v in labels.items()}
    check(list(names.values()) == ["box"], f"box labels {labels}, expected one 'box' (USD semantics)")
    check(len(boxes) == 1, f"{len(boxes)} boxes, expected the cube's")
    if len(boxes) == 1:
        b = boxes[0]
        check(names.get(int(b["semanticId"])) == "box", f"box {b} is not labelled box")
        x0, y0, x1, y1 = int(b["x_min"]), int(b["y_min"]), int(b["x_max"]), int(b["y_max"])
        check(x1 - x0 > 20 and y1 - y0 > 20, f"the cube's box {b} is too small to be the cube")
        inside = rgb[y0:y1 + 1, x0:x1 + 1].reshape(-1, 3)
        red = (inside[:, 0] > inside[:, 1] + 30) & (inside[:, 0] > inside[:, 2] + 30)
        check(red.mean() > 0.5, f"the cube's box holds {red.mean():.0%} red pixels, expected most (displayColor)")
    seg = np.asarray(Image.open(os.path.join(out, "semantic_segmentation_0000.png")).convert("RGBA"))
    seg_labels = json.load(open(os.path.join(out, "semantic_segmentation_labels_0000.json")))
    box_colours = [k for k, v in seg_labels.items() if v.get("class") == "box"]
    check(len(box_colours) == 1, f"semantic labels {seg_labels}: expected one colour for box")
    if box_colours:
        colour = np.array([int(c) for c in box_colours[0].strip("()").split(",")])
        check((seg == colour).all(axis=2).sum() > 400, "the semantic image has few box pixels")

    # --camera: the stage's camera works; anything else is exit 2 naming the flag.
    result = sdg(binary, "run", os.path.join(data, "cube_camera.usda"), "--frames", "1", "--out",
                 os.path.join(tmp, "cam"), "--camera", "/World/Cam")
    check(result.returncode == 0, f"--camera /World/Cam: exit {result.returncode}: {result.stderr}")
    result = sdg(binary, "run", os.path.join(data, "cube_camera.usda"), "--frames", "1", "--out",
                 os.path.join(tmp, "nocam"), "--camera", "/World/Box")
    check(result.returncode == 2 and "--camera" in result.stderr and "/World/Box" in result.stderr,
          f"--camera /World/Box: exit {result.returncode}, expected 2 naming --camera: {result.stderr}")
    check(not os.path.exists(os.path.join(tmp, "nocam", "rgb_0000.png")), "--camera /World/Box wrote images")

    # A stage without camera or light is framed by the defaults: the cube fills a good part of the image.
    out = os.path.join(tmp, "framed")
    result = sdg(binary, "run", os.path.join(data, "no_camera.usda"), "--frames", "1", "--out", out)
    check(result.returncode == 0, f"run no_camera.usda: exit {result.returncode}: {result.stderr}")
    if result.returncode == 0:
        rgb_is_not_empty(out, "no_camera.usda")

    # A broken layer: exit 2, the message at file:line:col.
    result = subprocess.run([binary, "validate", "bad_syntax.usda"], cwd=data, capture_output=True, text=True,
                            timeout=60)
    check(result.returncode == 2, f"validate bad_syntax.usda: exit {result.returncode}, expected 2")
    expected = "bad_syntax.usda:12:5: error: expected ')' after 3 numbers in a float3 value, found '}'"
    check(expected in result.stderr, f"validate bad_syntax.usda said {result.stderr!r}, expected {expected!r}")


def check_flatten_and_studio(binary, repo, tmp):
    """flatten of a usda stage writes a YAML scene that reloads to the same stage (inspect, less the
    lines naming the source) and runs to the same dataset, byte for byte; studio opens the stage and
    shows its prim tree and a preview."""
    stage = os.path.join(repo, "tests", "data", "usd", "cube_camera.usda")
    flat = os.path.join(tmp, "cube_flat.yaml")
    result = sdg(binary, "flatten", stage, "-o", flat)
    check(result.returncode == 0, f"flatten cube_camera.usda: exit {result.returncode}: {result.stderr}")
    if result.returncode != 0:
        return

    def inspected(path):
        r = sdg(binary, "inspect", path)
        check(r.returncode == 0, f"inspect {path}: exit {r.returncode}: {r.stderr}")
        return [line.split("  # ")[0] for line in r.stdout.splitlines()
                if not line.startswith("scene ") and not line.startswith("asset_roots: ")]

    a, b = inspected(stage), inspected(flat)
    diff = [f"  usda: {x}\n  yaml: {y}" for x, y in zip(a, b) if x != y]
    check(len(a) == len(b) and not diff, f"flatten: inspect differs ({len(a)}, {len(b)} lines):\n" + "\n".join(diff[:6]))
    hashes = []
    for name, source in (("usda", stage), ("flat", flat)):
        out = os.path.join(tmp, "flat_" + name)
        r = sdg(binary, "run", source, "--frames", "1", "--resolution", "64x48", "--out", out)
        check(r.returncode == 0, f"run {source}: exit {r.returncode}: {r.stderr[-400:]}")
        # .sdgbehave/run.json hashes the input files, which differ.
        hashes.append({f: h for f, h in dataset_hashes(out).items() if f != os.path.join(".sdgbehave", "run.json")})
    check(hashes[0] and hashes[0] == hashes[1], "flatten: the flattened scene's dataset differs from the stage's")

    studio = Studio(binary, stage)
    try:
        status, tree = studio.request("/api/tree")
        check(status == 200 and "/World/Box" in json.dumps(tree), f"studio /api/tree: {status} {str(tree)[:200]}")
        status, png = studio.request("/api/preview?frame=0", raw=True)
        check(status == 200 and png[:4] == b"\x89PNG", f"studio /api/preview of a USD stage: {status}")
        status, answer = studio.request("/api/edit", {"prim": "/World/Box", "keys": ["size"], "value": 2})
        check(status == 400 and "is a USD stage" in json.dumps(answer),
              f"studio /api/edit of a USD stage: {status} {answer}, expected 400 (edits YAML only)")
    finally:
        studio.stop()


def check_samples(binary, repo, tmp):
    samples = os.path.normpath(os.path.join(repo, "..", "shared", "usd-samples"))
    if not os.path.isdir(samples):
        print(f"skipped: no USD samples at {samples}")
        sys.exit(77)
    files = sorted(p for ext in ("usd", "usda", "usdz")
                   for p in glob.glob(os.path.join(samples, "**", f"*.{ext}"), recursive=True))
    check(files, f"no .usd/.usda/.usdz under {samples}")
    for path in files:
        result = sdg(binary, "validate", path, timeout=120)
        clean = result.returncode == 0 or (result.returncode == 2 and "error:" in result.stderr)
        check(clean and "internal error" not in result.stderr,
              f"validate {path}: exit {result.returncode}: {result.stderr[-400:]}")
    teapot = os.path.join(samples, "full_assets", "Teapot", "Teapot.usd")
    usdz = [p for p in files if p.endswith(".usdz") and sdg(binary, "validate", p).returncode == 0]
    runs = ([teapot] if os.path.exists(teapot) else []) + usdz[:1]
    check(len(runs) == 2, f"expected Teapot.usd and a valid .usdz to run, found {runs}")
    for i, path in enumerate(runs):
        out = os.path.join(tmp, f"sample{i}")
        result = sdg(binary, "run", path, "--frames", "1", "--out", out)
        check(result.returncode == 0, f"run {path}: exit {result.returncode}: {result.stderr[-400:]}")
        if result.returncode == 0:
            rgb_is_not_empty(out, path)


def main():
    binary, repo, part = sys.argv[1:4]
    binary = os.path.abspath(binary)
    with tempfile.TemporaryDirectory() as tmp:
        if part == "stage":
            check_stage(binary, repo, tmp)
            check_flatten_and_studio(binary, repo, tmp)
        else:
            check_samples(binary, repo, tmp)
    return finish(f"usd {part}: ok")


if __name__ == "__main__":
    sys.exit(main())
