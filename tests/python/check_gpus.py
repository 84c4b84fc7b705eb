#!/usr/bin/python3
"""`run --gpus`. Always: a malformed or impossible --gpus, or one beside --shard, --gpu or --no-render, exits 2
naming the flag; `--gpus all` on a machine with one GPU or none runs as a plain run (byte-identical files).
With MODE=workers the workers' path: on a machine with two or more GPUs, `--gpus 2` writes the files one
process writes (shards merged), verify passes and the workers' logs are kept; skipped (77) with fewer GPUs.

usage: check_gpus.py SDGBEHAVE SCENE flags|workers"""
import os
import subprocess
import sys
import tempfile

from checklib import check, dataset_hashes, finish

binary, scene, mode = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2]), sys.argv[3]
tmp = tempfile.mkdtemp()
base = ["run", scene, "--frames", "4", "--resolution", "64x64"]


def run(*extra, out):
    return subprocess.run([binary, *base, "--out", os.path.join(tmp, out), *extra], capture_output=True, text=True)


def gpu_count():
    """How many GPUs the process sees, from --gpus's own message (it names the count it sees)."""
    text = run("--gpus", "4096", out="probe").stderr
    marker = "this process sees "
    return int(text[text.index(marker) + len(marker):].split()[0]) if marker in text else None


if mode == "flags":
    for spec, words in (("x", "expected all, a number"), ("0,0", None), ("4096", "asked for")):
        r = run("--gpus", spec, out="bad_" + spec.replace(",", "_"))
        check(r.returncode == 2 and "--gpus" in r.stderr and (words is None or words in r.stderr),
              f"--gpus {spec}: exit 2 naming the flag, got {r.returncode}: {r.stderr.strip()[-300:]}")
    for extra in (["--shard", "0/2"], ["--gpu", "0"], ["--no-render"]):
        r = run("--gpus", "all", *extra, out="bad_" + extra[0].strip("-"))
        check(r.returncode == 2 and "--gpus" in r.stderr, f"--gpus with {extra[0]}: exit 2, got {r.returncode}: "
                                                          f"{r.stderr.strip()[-300:]}")
    n = gpu_count()
    if n is not None and n < 2:
        plain, gpus = run(out="plain"), run("--gpus", "all", out="all")
        check(plain.returncode == 0 and gpus.returncode == 0, f"runs exit 0: {plain.stderr[-300:]} {gpus.stderr[-300:]}")
        check(dataset_hashes(os.path.join(tmp, "plain")) == dataset_hashes(os.path.join(tmp, "all")),
              f"--gpus all with {n} GPU(s) writes what a plain run writes")
    sys.exit(finish())

n = gpu_count()
if n is None or n < 2:
    print(f"skipped: --gpus workers need two GPUs; this machine has {n}")
    sys.exit(77)
plain, gpus = run(out="plain"), run("--gpus", "2", out="two")
check(plain.returncode == 0 and gpus.returncode == 0, f"runs exit 0: {plain.stderr[-300:]} {gpus.stderr[-300:]}")
hashes = [{k: v for k, v in dataset_hashes(os.path.join(tmp, d)).items() if not k.startswith(".sdgbehave")}
          for d in ("plain", "two")]
check(hashes[0] == hashes[1], "--gpus 2 writes the files one process writes")
v = subprocess.run([binary, "verify", os.path.join(tmp, "two")], capture_output=True, text=True)
check(v.returncode == 0, f"verify passes: {v.stdout[-300:]} {v.stderr[-300:]}")
parts = os.listdir(os.path.join(tmp, "two", ".sdgbehave"))
check(all(f"worker.shard-{i}-of-2.log" in parts for i in range(2)), f"the workers' logs are kept: {parts}")
sys.exit(finish())
