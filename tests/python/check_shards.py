#!/usr/bin/python3
"""Shards add up to the whole run: for k = 1, 2, 3, 4 and 12 (more shards
than frames) the shards' union, after `sdgbehave merge`, is byte-identical
to a single run (COCO file, contact sheet and manifest included); two shards
running at the same time into one folder too. Shard numbers come from Slurm
array and Kubernetes Indexed Job variables; bad ones exit 2. `verify`
passes on the result and fails (exit 1) on a changed file."""
import os
import subprocess
import sys
import tempfile

from checklib import check, dataset_hashes, failures, finish



def run(binary, scene, out, *flags, env=None, check_rc=True):
    p = subprocess.run([binary, "run", scene, "--out", out, *flags], capture_output=True, text=True,
                       env={**os.environ, **(env or {})})
    if check_rc and p.returncode != 0:
        failures.append(f"run {flags} exited {p.returncode}: {p.stderr.strip()[-400:]}")
    return p


def merge(binary, out):
    p = subprocess.run([binary, "merge", out], capture_output=True, text=True)
    check(p.returncode == 0, f"merge {out}: {p.returncode} {p.stderr.strip()[-300:]}")


def main():
    binary, scene = (os.path.abspath(a) for a in sys.argv[1:3])
    with tempfile.TemporaryDirectory() as tmp:
        whole = f"{tmp}/whole"
        run(binary, scene, whole)
        reference = dataset_hashes(whole)
        check("coco_annotations.json" in reference or any(k.endswith(".json") and "coco" in k for k in reference),
              f"no COCO file in the whole run: {sorted(reference)[:5]}")
        check("contact_sheet.png" in reference and "manifest.jsonl" in reference, "whole run lacks sheet or manifest")
        for k in (1, 2, 3, 4, 12):
            out = f"{tmp}/k{k}"
            for i in range(k):
                run(binary, scene, out, "--shard", f"{i}/{k}")
            merge(binary, out)
            got = dataset_hashes(out)
            diff = sorted(n for n in set(got) | set(reference) if got.get(n) != reference.get(n))
            check(not diff, f"k={k}: {len(diff)} files differ from the whole run: {diff[:6]}")
        # Two shards at the same time, numbered by Slurm's variables (array 4-6:2 -> tasks 4 and 6).
        out = f"{tmp}/slurm"
        slurm = {"SLURM_ARRAY_TASK_MIN": "4", "SLURM_ARRAY_TASK_MAX": "6", "SLURM_ARRAY_TASK_STEP": "2",
                 "SLURM_ARRAY_TASK_COUNT": "2"}
        procs = [subprocess.Popen([binary, "run", scene, "--out", out], env={**os.environ, **slurm,
                                                                            "SLURM_ARRAY_TASK_ID": task},
                                  stdout=subprocess.DEVNULL, stderr=subprocess.PIPE) for task in ("4", "6")]
        for p in procs:
            check(p.wait() == 0, f"concurrent Slurm shard exited {p.returncode}: {p.stderr.read().decode()[-300:]}")
        merge(binary, out)
        check(dataset_hashes(out) == reference, "two concurrent Slurm-numbered shards differ from the whole run")
        # A Kubernetes Indexed Job: the index from the environment, the count from the flag.
        out = f"{tmp}/k8s"
        for index in ("0", "1", "2"):
            run(binary, scene, out, "--shard-count", "3", env={"JOB_COMPLETION_INDEX": index})
        merge(binary, out)
        check(dataset_hashes(out) == reference, "Kubernetes-indexed shards differ from the whole run")

        uneven = run(binary, scene, f"{tmp}/bad", env={**slurm, "SLURM_ARRAY_TASK_MAX": "7", "SLURM_ARRAY_TASK_ID": "4"},
                     check_rc=False)
        check(uneven.returncode == 2 and "not evenly spaced" in uneven.stderr, f"uneven array: {uneven.returncode} "
              f"{uneven.stderr.strip()}")
        k8s = run(binary, scene, f"{tmp}/bad2", env={"JOB_COMPLETION_INDEX": "1"}, check_rc=False)
        check(k8s.returncode == 2 and "--shard-count" in k8s.stderr, f"k8s without count: {k8s.stderr.strip()}")
        big = run(binary, scene, f"{tmp}/bad3", "--shard", "4/4", check_rc=False)
        check(big.returncode == 2 and "not below the shard count" in big.stderr, f"4/4: {big.stderr.strip()}")
        incomplete = f"{tmp}/incomplete"
        run(binary, scene, incomplete, "--shard", "0/2")
        p = subprocess.run([binary, "merge", incomplete], capture_output=True, text=True)
        check(p.returncode == 1 and "is not in the manifest" in p.stderr, f"merge of half a run: {p.stderr.strip()}")

        p = subprocess.run([binary, "verify", whole], capture_output=True, text=True)
        check(p.returncode == 0 and "0 problems" in p.stdout, f"verify: {p.returncode} {p.stdout.strip()}")
        with open(f"{whole}/rgb_0003.png", "r+b") as f:
            f.seek(60)
            f.write(b"\x00\x01")
        p = subprocess.run([binary, "verify", whole], capture_output=True, text=True)
        check(p.returncode == 1 and "rgb_0003.png: sha256 differs" in p.stdout, f"verify after a change: {p.stdout}")
    return finish("ok")


if __name__ == "__main__":
    sys.exit(main())
