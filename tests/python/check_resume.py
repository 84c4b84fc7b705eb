#!/usr/bin/python3
"""Crash safety: a run killed with SIGKILL at several moments (during the
first pre-roll, after a few frames, in the second iteration, near the end)
and then resumed with --resume gives a folder identical to an uninterrupted
run. While killed, no file under its final name is half written. A full
disk (a small tmpfs, when this user may mount one) exits 1 naming the file
and leaves no temporary file behind."""
import glob
import os
import signal
import subprocess
import sys
import tempfile
import time

from PIL import Image

from checklib import check, dataset_hashes, failures, finish

FLAGS = ["--frames", "12", "--iterations", "2", "--resolution", "128x128", "--threads", "2"]


def manifest_lines(folder):
    try:
        return open(f"{folder}/manifest.jsonl", "rb").read().count(b"\n")
    except FileNotFoundError:
        return 0


def kill_after(binary, scene, out, lines, delay):
    p = subprocess.Popen([binary, "run", scene, "--out", out, *FLAGS], stdout=subprocess.DEVNULL,
                         stderr=subprocess.DEVNULL)
    start = time.time()
    while p.poll() is None and manifest_lines(out) < lines and time.time() - start < 60:
        time.sleep(0.002)
    time.sleep(delay)
    if p.poll() is None:
        p.send_signal(signal.SIGKILL)
    p.wait()
    return p.returncode


def main():
    binary, scene = (os.path.abspath(a) for a in sys.argv[1:3])
    with tempfile.TemporaryDirectory() as tmp:
        reference_dir = f"{tmp}/whole"
        subprocess.run([binary, "run", scene, "--out", reference_dir, *FLAGS], check=True, capture_output=True)
        reference = dataset_hashes(reference_dir)
        killed_mid_run = 0
        for n, (lines, delay) in enumerate([(0, 0.02), (2, 0.0), (13, 0.0), (21, 0.003)]):
            out = f"{tmp}/run{n}"
            rc = kill_after(binary, scene, out, lines, delay)
            killed_mid_run += rc == -signal.SIGKILL
            for png in glob.glob(f"{out}/*.png"):
                try:
                    Image.open(png).load()
                except Exception as e:  # noqa: BLE001 - any decode error is the failure
                    failures.append(f"kill {n}: {os.path.basename(png)} is half written: {e}")
            p = subprocess.run([binary, "run", scene, "--out", out, *FLAGS, "--resume"], capture_output=True, text=True)
            check(p.returncode == 0, f"resume {n}: exit {p.returncode}: {p.stderr.strip()[-300:]}")
            got = dataset_hashes(out)
            diff = sorted(k for k in set(got) | set(reference) if got.get(k) != reference.get(k))
            check(not diff, f"kill after {lines} frames, then resume: {len(diff)} files differ: {diff[:6]}")
            v = subprocess.run([binary, "verify", out], capture_output=True, text=True)
            check(v.returncode == 0, f"verify after resume {n}: {v.stdout.strip()}")
        check(killed_mid_run >= 3, f"only {killed_mid_run} of 4 runs were killed before they finished")

        # Resuming a folder that holds a different run is refused.
        p = subprocess.run([binary, "run", scene, "--out", reference_dir, *FLAGS, "--seed", "99", "--resume"],
                           capture_output=True, text=True)
        check(p.returncode == 2 and "holds a different run" in p.stderr, f"resume with another seed: {p.stderr.strip()}")

        tiny = f"{tmp}/tiny"
        os.makedirs(tiny)
        if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=300k", "tmpfs", tiny], capture_output=True).returncode == 0:
            try:
                p = subprocess.run([binary, "run", scene, "--out", f"{tiny}/out", *FLAGS], capture_output=True, text=True)
                check(p.returncode == 1 and "No space left on device" in p.stderr, f"full disk: {p.returncode} {p.stderr}")
                check(not glob.glob(f"{tiny}/**/*.tmp-*", recursive=True), "full disk left temporary files")
            finally:
                subprocess.run(["umount", tiny], capture_output=True)
        else:
            print("note: cannot mount a tmpfs here; the full-disk case was not run")
    return finish("ok")


if __name__ == "__main__":
    sys.exit(main())
