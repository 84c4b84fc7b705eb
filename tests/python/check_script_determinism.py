#!/usr/bin/python3
"""Scripts are deterministic: the same scene and seed write byte-identical
folders whatever --threads and however the run is split into shards
(merged afterwards), and another seed writes a different one. The scene's
script also uses Python's random, numpy's global generator and set order.

usage: check_script_determinism.py SDGBEHAVE SCENE"""
import os
import subprocess
import sys
import tempfile

from checklib import check, dataset_hashes, failures, finish


def run(binary, scene, out, *flags):
    p = subprocess.run([binary, "run", scene, "--out", out, "--quiet", *flags], capture_output=True, text=True,
                       timeout=300)
    check(p.returncode == 0, f"run {flags} exited {p.returncode}: {p.stderr.strip()[-600:]}")


def main():
    binary, scene = sys.argv[1:3]
    with tempfile.TemporaryDirectory() as tmp:
        whole = os.path.join(tmp, "whole")
        run(binary, scene, whole, "--threads", "1")
        reference = dataset_hashes(whole)
        check(len(reference) > 10, f"the run wrote only {len(reference)} files")
        threads = os.path.join(tmp, "threads")
        run(binary, scene, threads, "--threads", "2")
        check(dataset_hashes(threads) == reference, "--threads 2 differs from --threads 1")
        for k in (2, 4):
            sharded = os.path.join(tmp, f"shards{k}")
            for i in range(k):
                run(binary, scene, sharded, "--shard", f"{i}/{k}")
            p = subprocess.run([binary, "merge", sharded], capture_output=True, text=True)
            check(p.returncode == 0, f"merge: {p.stderr.strip()[-300:]}")
            check(dataset_hashes(sharded) == reference, f"{k} shards merged differ from the whole run")
        other = os.path.join(tmp, "other")
        run(binary, scene, other, "--seed", "6")
        changed = [n for n, h in dataset_hashes(other).items() if n.startswith("rgb_") and reference.get(n) != h]
        check(len(changed) >= 5, f"another seed changed only {len(changed)} rgb images")
    return finish("threads 1 and 2, 2 and 4 shards: byte-identical; another seed: different")


if __name__ == "__main__":
    sys.exit(main())
