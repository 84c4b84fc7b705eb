#!/usr/bin/python3
"""Scripts publish and subscribe on the same event bus as the built-ins:
the scene's pre-roll waits for a script's reply; a ping published in one
update reaches the listening script in the next; what the listener wrote
while playing is undone on stop, what the responder wrote in the pre-roll
stays until the end of the run. A long run: the ping of the last update is
delivered when the timeline stops, and current_time at frame 9999 is
exactly 10000 / 60 (counted, not summed).

usage: check_script_events.py SDGBEHAVE SCENE"""
import json
import os
import subprocess
import sys
import tempfile


def main():
    binary, scene = sys.argv[1:3]
    with tempfile.TemporaryDirectory() as tmp:
        record = os.path.join(tmp, "record.jsonl")
        result = subprocess.run([binary, "run", scene, "--no-render", "--record", record, "--quiet"],
                                capture_output=True, text=True, timeout=120)
        if result.returncode != 0:
            print(f"exit {result.returncode}:\n{result.stderr}")
            return 1
        with open(record, encoding="utf-8") as f:
            lines = [json.loads(line) for line in f]
    changes = [[(c["prim"], c["attribute"], c["value"]) for c in line["changes"]] for line in lines]
    expected = [
        [("/World/Answer", "user:requests", 1)],          # the pre-roll's request, answered
        [],                                                # frame 0: the first ping is in flight
        [("/World/Ear", "user:lastPing", 1)],
        [("/World/Ear", "user:lastPing", 2)],
        [("/World/Ear", "user:lastPing", 3)],
        [("/World/Ear", "user:lastPing", None)],           # stop: the listener's attribute removed
    ]
    if changes != expected:
        print("record:\n" + "\n".join(map(str, changes)) + "\nexpected:\n" + "\n".join(map(str, expected)))
        return 1
    result = subprocess.run([binary, "run", scene, "--no-render", "--frames", "10000", "-v"],
                            capture_output=True, text=True, timeout=300)
    if result.returncode != 0:
        print(f"exit {result.returncode}:\n{result.stderr}")
        return 1
    expected_lines = ["/World/Ear: listener: heard 10000 pings, the last 10000",
                      f"/World/Talker: pinger: sent 10000 pings; the last current_time was {10000 / 60!r}"]
    missing = [line for line in expected_lines if line not in result.stderr]
    if missing:
        print("stderr lacks:\n" + "\n".join(missing) + "\n--- stderr\n" + result.stderr)
        return 1
    print("pre-roll reply, one-update delivery, delivery at stop, restore on stop and the time as expected")
    return 0


if __name__ == "__main__":
    sys.exit(main())
