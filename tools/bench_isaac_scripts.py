#!/usr/bin/python3
"""`make bench` rows for Isaac Sim's six behavior scripts (read in place from <repo>/../shared/isaac-behaviors)
through sdgbehave's Isaac layer, each next to the built-in of the same namespace on the same scene (the
scene without its `scripts:` line):

- location_randomizer.py, rotation_randomizer.py, look_at_behavior.py and texture_randomizer.py on 1,000
  prims, light_randomizer.py on 100 lights: the behaviors' milliseconds per frame (run_summary's behaviors
  seconds / frames, FRAMES frames, median of RUNS runs), and the whole process's CPU milliseconds per frame
  (user + system time of a FRAMES-frame run minus a 30-frame run, / (FRAMES - 30); steadier than wall time
  on a loaded machine). The rotation grid's prims have a translate only (the script adds an orient op);
  the look-at's have a rotateXYZ op (the script decomposes each rotation into Euler angles).
- volume_stack_randomizer.py is event-driven: it does nothing per frame (its on_update is empty); its work
  is the pre-roll's setup (crates referenced, walls sized) and run (the drop and settling, one physics step
  per update). Its row is run_summary's preroll seconds for 12 crates, median of RUNS runs.

Prints one JSON row per figure; prints nothing when the Isaac files are not there.

usage: bench_isaac_scripts.py SDGBEHAVE [RUNS [FRAMES [NAME...]]]   (NAME: location rotation look_at light
texture volume_stack; all when none is given)"""
import json
import os
import resource
import subprocess
import sys
import tempfile

binary = sys.argv[1]
runs = int(sys.argv[2]) if len(sys.argv) > 2 else 5
frames = int(sys.argv[3]) if len(sys.argv) > 3 else 300
only = set(sys.argv[4:])
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
behaviors = os.path.join(os.path.dirname(root), "shared", "isaac-behaviors", "isaacsim", "replicator", "behavior",
                         "behaviors")
if not os.path.isdir(behaviors):
    sys.exit(0)
tmp = tempfile.mkdtemp()
HEAD = ["version: 1", "render: {resolution: [16, 16]}", "writer: {type: BasicWriter, rgb: true}", "prims:",
        "  /World: {}", "  /World/Cam: {type: Camera, translate: [0, 0, 60]}"]


def cubes(parent, extra=""):
    return [f"  {parent}/C{i}: {{type: Cube, size: 0.5, translate: [{i % 40}, {i // 40}, 0]{extra}}}"
            for i in range(1000)]


def location():
    return (["  /World/Grid: {behaviors: {locationRandomizer: {range:minPosition: [-0.2, -0.2, 0], "
             "range:maxPosition: [0.2, 0.2, 0.2]}}}"] + cubes("/World/Grid"))


def rotation():
    return (["  /World/Grid: {behaviors: {rotationRandomizer: {range:minRotation: [0, 0, 0], "
             "range:maxRotation: [90, 90, 90]}}}"] + cubes("/World/Grid"))


def look_at():
    return (["  /World/Target: {type: Sphere, radius: 0.2, translate: [20, 12, 5]}",
             "  /World/Grid: {behaviors: {lookAtBehavior: {targetPrimPath: /World/Target}}}"]
            + cubes("/World/Grid", ", rotateXYZ: [0, 0, 0]"))


def light():
    return (["  /World/Lights: {behaviors: {lightRandomizer: {range:minColor: [0.2, 0.3, 0.4], "
             "range:maxColor: [0.8, 0.9, 1.0], range:intensity: [500, 1500]}}}"]
            + [f"  /World/Lights/L{i}: {{type: SphereLight, translate: [{i % 10}, {i // 10}, 3], "
               f"inputs:intensity: 800}}" for i in range(100)])


def texture():
    return (["  /World/Grid: {behaviors: {textureRandomizer: {projectUvwProbability: 0.7, "
             "textureScaleRange: [0.2, 0.8], textureRotateRange: [0, 30]}}}"] + cubes("/World/Grid"))


def volume_stack():
    return ["  /World/Pallet:", "    type: Cube", "    translate: [0, 0, 0.07]", "    scale: [1.2, 1.0, 0.07]",
            "    behaviors:",
            "      volumeStackRandomizer: {assets:assets: [meshes/crate.glb], assets:csv: \"\", "
            "assets:numRange: [12, 12], dropHeight: 1.5, seed: 3}",
            "events:",
            "  - publish: isaacsim.replicator.behavior.volumeStackRandomizer.in",
            "    payload: {action: setup}",
            "    wait_event: isaacsim.replicator.behavior.volumeStackRandomizer.out",
            "    wait_for: {state_name: SETUP}",
            "  - publish: isaacsim.replicator.behavior.volumeStackRandomizer.in",
            "    payload: {action: run}",
            "    wait_event: isaacsim.replicator.behavior.volumeStackRandomizer.out",
            "    wait_for: {state_name: FINISHED}",
            "    max_updates: 1000"]


# (key, Isaac file, built-in namespace, what is counted, the prims)
CASES = [("location", "location_randomizer.py", "locationRandomizer", "1,000 prims", location),
         ("rotation", "rotation_randomizer.py", "rotationRandomizer", "1,000 prims", rotation),
         ("look_at", "look_at_behavior.py", "lookAtBehavior", "1,000 prims", look_at),
         ("light", "light_randomizer.py", "lightRandomizer", "100 lights", light),
         ("texture", "texture_randomizer.py", "textureRandomizer", "1,000 prims", texture),
         ("volume_stack", "volume_stack_randomizer.py", "volumeStackRandomizer", "12 crates", volume_stack)]


def scene(path, script, body, n_frames):
    lines = list(HEAD)
    if script:
        lines.insert(1, f"scripts: [{script}]")
    lines.insert(1, f"asset_roots: [{root}/tests/data]")
    lines.insert(1, f"isaac_assets: {root}/tests/data/isaac/pack")
    lines.insert(1, f"capture: {{cameras: [/World/Cam], frames: {n_frames}, seed: 1}}")
    with open(path, "w") as f:
        f.write("\n".join(lines + body()) + "\n")
    return path


def summary(path):
    subprocess.run([binary, "run", path, "--out", f"{tmp}/o", "--overwrite"], check=True, capture_output=True)
    return json.load(open(f"{tmp}/o/run_summary.json"))["seconds"]


def cpu_seconds(path):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([binary, "run", path, "--out", f"{tmp}/c", "--overwrite"], check=True, capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime


def row(name, unit, costs):
    costs = sorted(costs)
    print(json.dumps({"name": name, "unit": unit, "median": round(costs[len(costs) // 2], 3),
                      "min": round(costs[0], 3), "max": round(costs[-1], 3)}), flush=True)


for key, file, ns, count, body in CASES:
    if only and key not in only:
        continue
    for name, script in ((f"Isaac's {file} through the layer", os.path.join(behaviors, file)),
                         (f"the built-in {ns}", "")):
        if key == "volume_stack":
            path = scene(f"{tmp}/{key}.yaml", script, body, 2)
            row(f"{name}, {count}, pre-roll (setup and stacking)", "ms",
                [1000 * summary(path)["preroll"] for _ in range(runs)])
            continue
        path = scene(f"{tmp}/{key}.yaml", script, body, frames)
        row(f"{name}, {count}, behaviors per frame", "ms",
            [1000 * summary(path)["behaviors"] / frames for _ in range(runs)])
        short = scene(f"{tmp}/{key}_short.yaml", script, body, 30)
        row(f"{name}, {count}, whole-process CPU per frame", "ms",
            [1000 * (cpu_seconds(path) - cpu_seconds(short)) / (frames - 30) for _ in range(runs)])
