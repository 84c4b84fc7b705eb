"""Shared by the Python checks: collecting failures and the exit code, and
the SHA-256 of every file of a dataset folder (hidden parts included)
except the summaries, which hold timings and per-shard facts and are the
only files allowed to differ between a whole run and its shards."""
import glob
import hashlib
import os

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


def finish(ok_message="ok", limit=40):
    """Prints the failures (exit 1) or `ok_message` (exit 0)."""
    if failures:
        print("\n".join(failures[:limit]))
        return 1
    print(ok_message)
    return 0


def dataset_hashes(folder):
    out = {}
    paths = glob.glob(f"{folder}/**/*", recursive=True) + glob.glob(f"{folder}/.sdgbehave/**/*", recursive=True)
    for path in sorted(paths):
        name = os.path.relpath(path, folder)
        if os.path.isfile(path) and name != "run_summary.json" and not os.path.basename(name).startswith("summary."):
            out[name] = hashlib.sha256(open(path, "rb").read()).hexdigest()
    return out
