#!/usr/bin/python3
"""`run --no-render --record`: a pre-roll line with the settle reports, then
every line is JSON with frame, time and changes; the same seed twice gives
byte-identical files; another seed differs."""
import json
import os
import subprocess
import sys
import tempfile

from checklib import failures, finish


def record(binary, scene, seed, path):
    subprocess.run([binary, "run", scene, "--no-render", "--frames", "6", "--seed", str(seed), "--record", path],
                   check=True, capture_output=True)
    with open(path, "rb") as f:
        return f.read()


def main():
    binary, scene = sys.argv[1:3]
    with tempfile.TemporaryDirectory() as tmp:
        a = record(binary, scene, 10, os.path.join(tmp, "a.jsonl"))
        b = record(binary, scene, 10, os.path.join(tmp, "b.jsonl"))
        c = record(binary, scene, 11, os.path.join(tmp, "c.jsonl"))
    lines = [json.loads(line) for line in a.decode().splitlines()]
    if not lines or lines[0].get("event") != "preroll" or not isinstance(lines[0].get("settle"), list):
        failures.append(f"the first line is not the pre-roll line: {lines[:1]}")
    lines = lines[1:]
    if len(lines) != 7:
        failures.append(f"expected 6 frame lines and a stop line after the pre-roll, found {len(lines)}")
    for i, line in enumerate(lines[:6]):
        if line.get("frame") != i or "time" not in line or not isinstance(line.get("changes"), list):
            failures.append(f"line {i + 1} malformed: {line}")
        for change in line.get("changes", []):
            if set(change) != {"prim", "attribute", "value"}:
                failures.append(f"line {i + 1}: change keys {sorted(change)}")
    if lines and lines[-1].get("event") != "stop":
        failures.append("the last line is not the stop")
    if a != b:
        failures.append("the same seed gave different records")
    if a == c:
        failures.append("another seed gave the same record")
    if not lines[0]["changes"]:
        failures.append("frame 0 recorded no changes")
    return finish(f"ok: {len(lines)} lines, deterministic")


if __name__ == "__main__":
    sys.exit(main())
