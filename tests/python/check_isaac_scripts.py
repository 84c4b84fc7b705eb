#!/usr/bin/python3
"""Isaac Sim's own behavior scripts (read in place from <repo>/../shared/isaac-behaviors) run through
sdgbehave's Isaac layer: byte-identical datasets across reruns, --threads and shards; the locations
written stay within the exposed range; over many frames their statistics match the built-in
locationRandomizer's (uniform offsets).

usage: check_isaac_scripts.py SDGBEHAVE SCENE_DIR SHARED_DIR"""
import json
import os
import statistics
import subprocess
import sys
import tempfile

from checklib import check, dataset_hashes, finish


def run(binary, scene, out, *flags):
    p = subprocess.run([binary, "run", scene, "--out", out, "--quiet", *flags], capture_output=True, text=True,
                       timeout=300)
    check(p.returncode == 0, f"run {os.path.basename(scene)} {flags} exited {p.returncode}: {p.stderr.strip()[-800:]}")


def recorded_locations(binary, scene, tmp, frames):
    record = os.path.join(tmp, os.path.basename(scene) + ".jsonl")
    run(binary, scene, os.path.join(tmp, "norender"), "--no-render", "--frames", str(frames), "--record", record)
    xs = []
    with open(record) as f:
        for line in f:
            entry = json.loads(line)
            if "frame" in entry:
                xs += [c["value"] for c in entry["changes"] if c["attribute"] == "xformOp:translate"]
    return xs


def main():
    binary, scenes, shared = sys.argv[1:4]
    if not os.path.isdir(os.path.join(shared, "isaacsim", "replicator", "behavior")):
        print(f"skipped: Isaac Sim's behavior scripts are not at {shared}")
        return 77
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(scenes, "rotation_location.yaml")
        whole = os.path.join(tmp, "whole")
        run(binary, scene, whole, "--threads", "1")
        reference = dataset_hashes(whole)
        check(len(reference) > 5, f"the run wrote only {len(reference)} files")
        again = os.path.join(tmp, "again")
        run(binary, scene, again, "--threads", "2")
        check(dataset_hashes(again) == reference, "--threads 2 differs from --threads 1")
        sharded = os.path.join(tmp, "shards")
        for i in range(2):
            run(binary, scene, sharded, "--shard", f"{i}/2")
        p = subprocess.run([binary, "merge", sharded], capture_output=True, text=True)
        check(p.returncode == 0, f"merge: {p.stderr.strip()[-300:]}")
        check(dataset_hashes(sharded) == reference, "2 shards merged differ from the whole run")

        # Within range, and the same distribution as the built-in of the same name.
        isaac_scene = os.path.join(scenes, "location_one.yaml")
        isaac = recorded_locations(binary, isaac_scene, tmp, 400)
        check(len(isaac) == 400, f"expected 400 recorded locations, found {len(isaac)}")
        lo, hi = (0.5, 1.5, 3.0), (1.5, 2.5, 3.2)  # translate [1, 2, 3] + the exposed range
        for v in isaac:
            check(all(lo[i] <= v[i] <= hi[i] for i in range(3)), f"location {v} outside {lo}..{hi}")
        with open(isaac_scene) as f:
            text = f.read()
        builtin_scene = os.path.join(tmp, "builtin.yaml")
        with open(builtin_scene, "w") as f:
            f.write("\n".join(line for line in text.splitlines() if not line.startswith("scripts:")))
        builtin = recorded_locations(binary, builtin_scene, tmp, 400)
        check(len(builtin) == 400, f"the built-in recorded {len(builtin)} locations")
        for axis, width in ((0, 1.0), (1, 1.0), (2, 0.2)):
            a, b = [v[axis] for v in isaac], [v[axis] for v in builtin]
            # Uniform: the mean within 4 standard errors, the deviation within 15% of each other.
            se = width / (12 ** 0.5) / (len(a) ** 0.5)
            check(abs(statistics.mean(a) - statistics.mean(b)) < 4 * 1.42 * se,
                  f"axis {axis}: mean {statistics.mean(a):.4f} (Isaac) vs {statistics.mean(b):.4f} (built-in)")
            check(abs(statistics.pstdev(a) / statistics.pstdev(b) - 1) < 0.15,
                  f"axis {axis}: stdev {statistics.pstdev(a):.4f} (Isaac) vs {statistics.pstdev(b):.4f} (built-in)")
    return finish("Isaac location/rotation randomizers: threads and shards identical; in range; built-in statistics")


if __name__ == "__main__":
    sys.exit(main())
