#!/usr/bin/python3
"""One of Isaac Sim's behavior scripts (read in place from <repo>/../shared/isaac-behaviors), run unchanged
through sdgbehave's Isaac layer, against the built-in behavior of the same name on the same scene: the same
exposed variables (describe --json), and per-attribute statistics of what each writes over FRAMES frames
that agree within sampling error (means within 4 standard errors, deviations within 15%, category
frequencies within 4 standard errors). The scene lists the script under `scripts:`; dropping that line
gives the built-in.

With --exact=ATTR the values of ATTR must also agree frame by frame (within 1e-4): for a deterministic
behavior such as the look-at, whose input the same built-in moves in both runs.

With --rendered, 3 rendered frames of the Isaac run must all differ (what the script writes reaches the
renderer: the scene has nothing else that changes) and be byte-identical with --threads 2 and as 2 shards.

usage: check_isaac_fidelity.py SDGBEHAVE SCENE SHARED_DIR BEHAVIOR FRAMES [--exact=ATTR] [--rendered]
                               [run flags...]"""
import json
import math
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
    return p


def recorded(binary, scene, tmp, frames, flags):
    """attribute -> every value written (prim paths dropped: created materials have random names)."""
    record = os.path.join(tmp, os.path.basename(scene) + ".jsonl")
    run(binary, scene, os.path.join(tmp, "norender"), "--no-render", "--frames", str(frames), "--record", record,
        *flags)
    values = {}
    with open(record) as f:
        for line in f:
            entry = json.loads(line)
            if "frame" in entry:
                for c in entry["changes"]:
                    values.setdefault(c["attribute"], []).append(c["value"])
    return values


def variables(binary, behavior, scripts):
    p = subprocess.run([binary, "describe", behavior, "--format", "json", *scripts], capture_output=True, text=True, timeout=60)
    check(p.returncode == 0, f"describe {behavior}: {p.stderr.strip()[-400:]}")
    spec = json.loads(p.stdout)["behaviors"][0]
    return {v["name"]: (v["type"], json.dumps(v.get("default"))) for v in spec["variables"]}


def columns(values):
    """Numeric columns of a list of values (numbers or equal-length lists), or None."""
    first = values[0]
    if isinstance(first, bool) or isinstance(first, str):
        return None
    if isinstance(first, (int, float)):
        return [[float(v) for v in values]]
    if isinstance(first, list) and all(isinstance(x, (int, float)) for x in first):
        return [[float(v[i]) for v in values] for i in range(len(first))]
    return None


def compare(name, a, b):
    # The record lists changes only: a value drawn equal to the last is not written, so the counts of
    # rarely changing values (booleans, a choice among few) are themselves random.
    check(len(a) > 0 and abs(len(a) - len(b)) <= 4 * math.sqrt(max(len(a), len(b))) + 0.02 * max(len(a), len(b)),
          f"{name}: {len(a)} values written through the layer, {len(b)} by the built-in")
    ca, cb = columns(a), columns(b)
    if ca is None:  # categories: each value's frequency within 4 standard errors
        n, m = len(a), len(b)
        for v in sorted({json.dumps(x) for x in a + b}):
            p, q = sum(json.dumps(x) == v for x in a) / n, sum(json.dumps(x) == v for x in b) / m
            pooled = (p * n + q * m) / (n + m)
            se = math.sqrt(max(pooled * (1 - pooled), 1e-12) * (1 / n + 1 / m))
            check(abs(p - q) <= 4 * se + 1e-9, f"{name} = {v}: frequency {p:.3f} (Isaac) vs {q:.3f} (built-in)")
        return
    for i, (x, y) in enumerate(zip(ca, cb)):
        sx, sy = statistics.pstdev(x), statistics.pstdev(y)
        se = math.sqrt(sx * sx / len(x) + sy * sy / len(y))
        mx, my = statistics.mean(x), statistics.mean(y)
        check(abs(mx - my) <= 4 * se + 1e-9 * max(1.0, abs(my)),
              f"{name}[{i}]: mean {mx:.5g} (Isaac) vs {my:.5g} (built-in), standard error {se:.3g}")
        if sy > 1e-9 or sx > 1e-9:
            check(abs(sx / max(sy, 1e-12) - 1) < 0.15, f"{name}[{i}]: stdev {sx:.5g} (Isaac) vs {sy:.5g} (built-in)")


def main():
    binary, scene, shared, behavior, frames = sys.argv[1:6]
    exact = [a.split("=", 1)[1] for a in sys.argv[6:] if a.startswith("--exact=")]
    rendered = "--rendered" in sys.argv[6:]
    flags = [a for a in sys.argv[6:] if not a.startswith("--exact=") and a != "--rendered"]
    if not os.path.isdir(os.path.join(shared, "isaacsim", "replicator", "behavior")):
        print(f"skipped: Isaac Sim's behavior scripts are not at {shared}")
        return 77
    frames = int(frames)
    with open(scene) as f:
        text = f.read()
    script_line = next(line for line in text.splitlines() if line.startswith("scripts:"))
    script = os.path.normpath(os.path.join(os.path.dirname(scene), script_line.split("[", 1)[1].rstrip("]").strip()))
    with tempfile.TemporaryDirectory() as tmp:
        isaac_vars = variables(binary, behavior, ["--script", script])
        builtin_vars = variables(binary, behavior, [])
        check(isaac_vars == builtin_vars, f"{behavior}: exposed variables differ:\n  Isaac    {isaac_vars}\n"
                                          f"  built-in {builtin_vars}")
        builtin_scene = os.path.join(os.path.dirname(scene), "." + os.path.basename(scene) + ".builtin.yaml")
        try:
            with open(builtin_scene, "w") as f:
                f.write("\n".join(line for line in text.splitlines() if not line.startswith("scripts:")) + "\n")
            builtin = recorded(binary, builtin_scene, tmp, frames, flags)
        finally:
            os.remove(builtin_scene)
        isaac = recorded(binary, scene, tmp, frames, flags)
        check(sorted(isaac) == sorted(builtin), f"attributes written: {sorted(isaac)} (Isaac) vs {sorted(builtin)} "
                                                f"(built-in)")
        for name in sorted(set(isaac) & set(builtin)):
            compare(name, isaac[name], builtin[name])
        for name in exact:
            a, b = isaac.get(name, []), builtin.get(name, [])
            worst = max((abs(x - y) for u, v in zip(a, b) for x, y in zip(u, v)), default=float("inf"))
            check(len(a) == len(b) and worst < 1e-4, f"{name}: {len(a)} vs {len(b)} values, frame by frame "
                                                     f"differing by up to {worst:.3g}")
        if rendered:
            out = os.path.join(tmp, "rendered")
            run(binary, scene, out, "--frames", "3", *flags)
            hashes = dataset_hashes(out)
            frames_rgb = [h for name, h in hashes.items() if os.path.basename(name).startswith("rgb_")]
            check(len(frames_rgb) == 3 and len(set(frames_rgb)) == 3,
                  f"3 rendered frames: {len(set(frames_rgb))} distinct rgb images of {len(frames_rgb)}")
            # Determinism: byte-identical across --threads and a 2-shard split.
            again = os.path.join(tmp, "threads")
            run(binary, scene, again, "--frames", "3", "--threads", "2", *flags)
            check(dataset_hashes(again) == hashes, "--threads 2 differs from the default")
            shards = os.path.join(tmp, "shards")
            for i in range(2):
                run(binary, scene, shards, "--frames", "3", "--shard", f"{i}/2", *flags)
            p = subprocess.run([binary, "merge", shards], capture_output=True, text=True)
            check(p.returncode == 0 and dataset_hashes(shards) == hashes, "2 shards merged differ from the whole run")
        counts = ", ".join(f"{k}: {len(v)}" for k, v in sorted(isaac.items()))
    return finish(f"{behavior}: Isaac's script and the built-in agree over {frames} frames ({counts})")


if __name__ == "__main__":
    sys.exit(main())
