#!/usr/bin/python3
"""`make bench` rows for Isaac Sim's location_randomizer.py (read in place from <repo>/../shared/isaac-behaviors)
moving 1,000 prims, through sdgbehave's Isaac layer, next to the built-in locationRandomizer on the same scene:
the behaviors' milliseconds per frame (run_summary's behaviors seconds / frames, 300 frames, median of 5 runs),
and the whole process's CPU milliseconds per frame (user + system time of a 300-frame run minus a 30-frame
run, / 270; steadier than wall time on a loaded machine). Prints one JSON row per figure; prints nothing
when the Isaac files are not there.

usage: bench_isaac_scripts.py SDGBEHAVE [RUNS]"""
import json
import os
import resource
import subprocess
import sys
import tempfile

binary = sys.argv[1]
runs = int(sys.argv[2]) if len(sys.argv) > 2 else 5
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
script = os.path.join(os.path.dirname(root), "shared", "isaac-behaviors", "isaacsim", "replicator", "behavior",
                      "behaviors", "location_randomizer.py")
if not os.path.isfile(script):
    sys.exit(0)
tmp = tempfile.mkdtemp()
frames = 300


def grid(scripts, frames=frames):
    lines = ["version: 1", f"scripts: [{scripts}]", "render: {resolution: [16, 16]}",
             f"capture: {{cameras: [/World/Cam], frames: {frames}, seed: 1}}", "writer: {type: BasicWriter, rgb: true}",
             "prims:", "  /World: {}", "  /World/Cam: {type: Camera, translate: [0, 0, 60]}",
             "  /World/Grid: {behaviors: {locationRandomizer: {range:minPosition: [-0.2, -0.2, 0], "
             "range:maxPosition: [0.2, 0.2, 0.2]}}}"]
    lines += [f"  /World/Grid/C{i}: {{type: Cube, size: 0.5, translate: [{i % 40}, {i // 40}, 0]}}" for i in range(1000)]
    return "\n".join(lines) + "\n"


def per_frame(scene):
    costs = []
    for _ in range(runs):
        subprocess.run([binary, "run", scene, "--out", f"{tmp}/o", "--overwrite"], check=True,
                       capture_output=True)
        costs.append(1000 * json.load(open(f"{tmp}/o/run_summary.json"))["seconds"]["behaviors"] / frames)
    return sorted(costs)


def cpu_seconds(scene):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([binary, "run", scene, "--out", f"{tmp}/c", "--overwrite"], check=True, capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime


def cpu_per_frame(scripts):
    short, long_ = f"{tmp}/short.yaml", f"{tmp}/long.yaml"
    with open(short, "w") as f:
        f.write(grid(scripts, 30))
    with open(long_, "w") as f:
        f.write(grid(scripts, frames))
    return sorted(1000 * (cpu_seconds(long_) - cpu_seconds(short)) / (frames - 30) for _ in range(runs))


for name, scripts in (("Isaac's location_randomizer.py through the layer", script),
                      ("the built-in locationRandomizer", "")):
    path = f"{tmp}/{'isaac' if scripts else 'builtin'}.yaml"
    with open(path, "w") as f:
        f.write(grid(scripts))
    costs = per_frame(path)
    print(json.dumps({"name": f"{name}, 1,000 prims, behaviors per frame", "unit": "ms",
                      "median": round(costs[len(costs) // 2], 3), "min": round(costs[0], 3),
                      "max": round(costs[-1], 3)}))
    costs = cpu_per_frame(scripts)
    print(json.dumps({"name": f"{name}, 1,000 prims, whole-process CPU per frame", "unit": "ms",
                      "median": round(costs[len(costs) // 2], 3), "min": round(costs[0], 3),
                      "max": round(costs[-1], 3)}))
