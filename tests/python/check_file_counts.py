#!/usr/bin/python3
"""One count of a dataset's files: the run's last log line ("N files in
DIR"), `files_written` in run_summary.json and `sdgbehave verify`'s "N
files" agree with each other and with the files in the folder outside
.sdgbehave/, for a whole run and for two shards merged; and verify's
manifest counts add up to the manifest's lines.

usage: check_file_counts.py SDGBEHAVE SCENE"""
import json
import os
import re
import subprocess
import sys
import tempfile

from checklib import check, finish


def files_outside_parts(folder):
    count = 0
    for root, dirs, files in os.walk(folder):
        if root == folder and ".sdgbehave" in dirs:
            dirs.remove(".sdgbehave")
        count += len(files)
    return count


def manifest_files(folder):
    listed = hidden = 0
    with open(os.path.join(folder, "manifest.jsonl")) as f:
        for line in f:
            for entry in json.loads(line)["files"]:
                listed += 1
                hidden += entry["path"].startswith(".sdgbehave/")
    return listed, hidden


def run(binary, *args):
    result = subprocess.run([binary, *args], capture_output=True, text=True, timeout=300)
    if result.returncode != 0:
        print(f"sdgbehave {' '.join(args)} exited {result.returncode}:\n{result.stderr}")
        sys.exit(1)
    return result


def check_folder(binary, folder, logged, what):
    on_disk = files_outside_parts(folder)
    summary = json.load(open(os.path.join(folder, "run_summary.json")))
    verify = run(binary, "verify", folder).stdout
    counts = re.search(r": (\d+) files, (\d+) frame outputs; the manifest's (\d+) files and (\d+) hidden parts checked, "
                       r"0 problems$", verify, re.M)
    check(counts is not None, f"{what}: verify's summary line not found in:\n{verify}")
    if not counts:
        return
    verified, _, listed, hidden = (int(g) for g in counts.groups())
    check(summary.get("files_written") == on_disk,
          f"{what}: files_written {summary.get('files_written')}, {on_disk} files outside .sdgbehave/")
    check(verified == on_disk, f"{what}: verify says {verified} files, {on_disk} are in the folder")
    if logged is not None:
        check(logged == on_disk, f"{what}: the log line says {logged} files, {on_disk} are in the folder")
    check((listed + hidden, hidden) == manifest_files(folder),
          f"{what}: verify checked {listed} + {hidden} hidden, the manifest lists {manifest_files(folder)}")
    print(f"{what}: {on_disk} files; log, files_written and verify agree ({listed} + {hidden} hidden in the manifest)")


def main():
    binary, scene = sys.argv[1:3]
    small = ["--resolution", "96x72", "--seed", "3"]
    with tempfile.TemporaryDirectory(prefix="sdg_counts_") as tmp:
        whole = os.path.join(tmp, "whole")
        log = run(binary, "run", scene, "--frames", "3", "--out", whole, *small).stderr
        logged = re.search(r"(\d+) files in " + re.escape(whole), log)
        check(logged is not None, f"no 'N files in {whole}' in the log:\n{log}")
        check_folder(binary, whole, int(logged.group(1)) if logged else None, "a whole run")

        sharded = os.path.join(tmp, "sharded")
        for shard in ("0/2", "1/2"):
            run(binary, "run", scene, "--iterations", "2", "--frames", "2", "--shard", shard, "--out", sharded, *small)
        run(binary, "merge", sharded)
        check_folder(binary, sharded, None, "two shards merged")
    return finish("ok: one count of files")


if __name__ == "__main__":
    sys.exit(main())
