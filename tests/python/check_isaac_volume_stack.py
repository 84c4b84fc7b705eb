#!/usr/bin/python3
"""Isaac's volume_stack_randomizer.py (read in place from <repo>/../shared/isaac-behaviors) runs unchanged
through the layer (tests/data/isaac_scripts/volume_stack.yaml): its pre-roll sets up and stacks 4 to 6
crates on a pallet on sdgbehave's ODE world. Checked from --save-stage: every crate inside the walled
volume, on or above the pallet, no two interpenetrating, the walls gone; byte-identical reruns, --threads
and 2 shards; and comparable to the built-in volumeStackRandomizer on the same scene.

usage: check_isaac_volume_stack.py SDGBEHAVE SCENE_DIR SHARED_DIR"""
import os
import subprocess
import sys
import tempfile

import yaml

from checklib import check, dataset_hashes, finish

CRATE = ((-0.21, -0.16, 0.0), (0.21, 0.16, 0.32))  # tests/data/meshes/crate.glb's bounds, in its frame
PALLET_TOP, HALF_X, HALF_Y = 0.14, 0.6, 0.5       # volume_stack.yaml's pallet: the walled volume's floor and sides


def crate_boxes(saved):
    """{path: (centre, 3 axes, 3 half sizes)} of the stacked crates in a --save-stage file."""
    with open(saved) as f:
        prims = yaml.safe_load(f)["prims"]
    out = {}
    for path, p in prims.items():
        if not path.startswith("/Behaviors/volumeStackRandomizer/Assets/Pallet/Asset_"):
            continue
        w, x, y, z = p["orient"]
        rows = [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]
        mid = [(a + b) / 2 for a, b in zip(*CRATE)]
        centre = [p["translate"][r] + sum(rows[r][c] * mid[c] for c in range(3)) for r in range(3)]
        axes = [[rows[r][c] for r in range(3)] for c in range(3)]
        out[path] = (centre, axes, [(b - a) / 2 for a, b in zip(*CRATE)])
    return prims, out


def corners(box):
    c, axes, h = box
    return [[c[i] + sx * h[0] * axes[0][i] + sy * h[1] * axes[1][i] + sz * h[2] * axes[2][i] for i in range(3)]
            for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]


def overlap_depth(a, b):
    """The least overlap of two boxes over the separating axis candidates (<= 0: apart)."""
    def cross(u, v):
        return [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    candidates = a[1] + b[1] + [cross(u, v) for u in a[1] for v in b[1]]
    least = float("inf")
    for axis in candidates:
        n = sum(x * x for x in axis) ** 0.5
        if n < 1e-9:
            continue
        axis = [x / n for x in axis]
        pa = [sum(p[i] * axis[i] for i in range(3)) for p in corners(a)]
        pb = [sum(p[i] * axis[i] for i in range(3)) for p in corners(b)]
        least = min(least, min(max(pa), max(pb)) - max(min(pa), min(pb)))
    return least


def check_volume_stack(binary, scene, tmp):
    """volume_stack.yaml: Isaac's script stacks 4 to 6 crates on the pallet through the layer's ODE world.
    After the pre-roll they rest inside the walled volume, on or above the pallet, apart from each other;
    the walls are gone; the stage is byte-identical across runs and --threads; the built-in on the same
    scene stacks comparably (count inside the volume, mean height)."""
    def stack(name, extra=(), scene_path=scene):
        saved = os.path.join(tmp, name + ".yaml")
        p = subprocess.run([binary, "run", scene_path, "--out", os.path.join(tmp, name), "--no-render",
                            "--save-stage", saved, *extra], capture_output=True, text=True, timeout=120)
        check(p.returncode == 0, f"{os.path.basename(scene_path)} ({name}): exit {p.returncode}: {p.stderr[-800:]}")
        return saved

    saved = stack("stack")
    prims, boxes = crate_boxes(saved)
    check(4 <= len(boxes) <= 6, f"expected 4 to 6 crates (assets:numRange [4, 6]), found {sorted(boxes)}")
    check(not any("CollisionWalls" in p for p in prims), "the collision walls are still on the stage")
    for path, box in boxes.items():
        pts = corners(box)
        check(min(q[2] for q in pts) > PALLET_TOP - 0.01, f"{path} sinks into the pallet: {pts}")
        check(max(abs(q[0]) for q in pts) < HALF_X + 0.01 and max(abs(q[1]) for q in pts) < HALF_Y + 0.01,
              f"{path} is outside the walled volume: {pts}")
        check(max(q[2] for q in pts) < PALLET_TOP + 1.5, f"{path} is above the drop height: {pts}")
    paths = sorted(boxes)
    deepest = -float("inf")
    for i, a in enumerate(paths):
        for b in paths[i + 1:]:
            depth = overlap_depth(boxes[a], boxes[b])
            deepest = max(deepest, depth)
            check(depth < 0.01, f"{a} and {b} interpenetrate by {depth:.4f}")
    with open(saved, "rb") as f:
        first = f.read()
    for name, extra in (("again", ()), ("threads", ("--threads", "2"))):
        with open(stack(name, extra), "rb") as f:
            check(f.read() == first, f"the stacked stage differs on a rerun ({name})")
    # The rendered dataset: byte-identical across --threads and a 2-shard split (each shard stacks anew).
    whole, threads, shards = (os.path.join(tmp, n) for n in ("ds_whole", "ds_threads", "ds_shards"))
    for out, extra in ((whole, ()), (threads, ("--threads", "2")), (shards, ("--shard", "0/2")),
                       (shards, ("--shard", "1/2"))):
        p = subprocess.run([binary, "run", scene, "--out", out, *extra], capture_output=True, text=True, timeout=120)
        check(p.returncode == 0, f"volume_stack.yaml {' '.join(extra)}: exit {p.returncode}: {p.stderr[-600:]}")
    p = subprocess.run([binary, "merge", shards], capture_output=True, text=True, timeout=120)
    hashes = dataset_hashes(whole)
    check(any(os.path.basename(n).startswith("rgb_") for n in hashes), f"no rgb images in {sorted(hashes)}")
    check(dataset_hashes(threads) == hashes, "volume_stack.yaml: --threads 2 differs from the default")
    check(p.returncode == 0 and dataset_hashes(shards) == hashes, "volume_stack.yaml: 2 shards merged differ")
    # The built-in volumeStackRandomizer on the same scene (the scene without its script list).
    with open(scene) as f:
        text = f.read()
    builtin_scene = os.path.join(os.path.dirname(scene), ".volume_stack_builtin.yaml")
    try:
        with open(builtin_scene, "w") as f:
            f.write("\n".join(line for line in text.splitlines() if not line.startswith("scripts:")) + "\n")
        _, builtin = crate_boxes(stack("builtin", scene_path=builtin_scene))
    finally:
        os.remove(builtin_scene)
    check(4 <= len(builtin) <= 6, f"the built-in stacked {len(builtin)} crates")
    mean = sum(b[0][2] for b in boxes.values()) / len(boxes)
    mean_builtin = sum(b[0][2] for b in builtin.values()) / len(builtin)
    check(abs(mean - mean_builtin) < 0.15, f"mean crate height {mean:.3f} through the layer, {mean_builtin:.3f} "
          "with the built-in")
    print(f"volume stack: {len(boxes)} crates, mean centre height {mean:.3f} (built-in: {len(builtin)}, "
          f"{mean_builtin:.3f}); deepest overlap between crates {deepest:.4f}")


def main():
    binary, scenes, shared = sys.argv[1:4]
    if not os.path.isdir(os.path.join(shared, "isaacsim", "replicator", "behavior")):
        print(f"skipped: Isaac Sim's behavior scripts are not at {shared}")
        return 77
    with tempfile.TemporaryDirectory() as tmp:
        check_volume_stack(binary, os.path.join(scenes, "volume_stack.yaml"), tmp)
    return finish("Isaac's volume_stack_randomizer.py stacks through the layer")


if __name__ == "__main__":
    sys.exit(main())
