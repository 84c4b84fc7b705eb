#!/usr/bin/python3
"""Smart assets (`reference:`), from the outside.

- The warehouse demo, rewritten to reference scenes/assets/, writes the same
  files as the flat demo it replaced (tests/data/references/warehouse_flat.yaml).
- `sdgbehave flatten` writes a file that reloads to the same stage (same
  inspect listing) and runs to the same files.
- Every override kind (tests/data/references/overrides.yaml): a transform,
  a label, one exposed variable, a new behavior, a behavior switched off, an
  attribute of a child, a new child under a mounted prim; prim paths inside
  an asset follow the mount; relative paths resolve from the asset's folder,
  nested folders included; an asset's script loads from its own folder, once,
  however many assets bring it.
- Twenty instances of one asset: the file is read once, each instance draws
  from its own stream.
- Errors inside an asset name the asset's file:line:col and where it was
  referenced from (exit 2): unknown key, bad value, unknown behavior and
  variable, missing mesh and texture, missing asset, a cycle, a name clash
  between two scripts.

usage: check_references.py SDGBEHAVE SOURCE_DIR"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

from checklib import check, dataset_hashes, finish

HERE = "tests/data/references"


def sdg(binary, *args, cwd):
    return subprocess.run([binary, *args], capture_output=True, text=True, cwd=cwd, timeout=300)


def without_timing(hashes):
    return {k: v for k, v in hashes.items() if not k.endswith("run.json")}


def listing(binary, scene, cwd):
    """inspect's listing without the origin comments (a flattened file has its own)."""
    p = sdg(binary, "inspect", scene, cwd=cwd)
    check(p.returncode == 0, f"inspect {scene}: {p.stderr}")
    lines = p.stdout.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("prims ("))
    return [line.split("  # ", 1)[0] for line in lines[start:]]


def demo_and_flatten(binary, root, tmp):
    flags = ["--frames", "3", "--seed", "10", "--resolution", "96x96", "--quiet"]
    a, b = os.path.join(tmp, "referencing"), os.path.join(tmp, "flat")
    for scene, out in (("scenes/warehouse.yaml", a), (f"{HERE}/warehouse_flat.yaml", b)):
        p = sdg(binary, "run", scene, "--out", out, *flags, cwd=root)
        check(p.returncode == 0, f"run {scene}: {p.stderr[-600:]}")
    check(without_timing(dataset_hashes(a)) == without_timing(dataset_hashes(b)),
          "the demo with smart assets differs from the flat demo")
    flat = os.path.join(tmp, "flattened.yaml")
    p = sdg(binary, "flatten", "scenes/warehouse.yaml", "-o", flat, cwd=root)
    check(p.returncode == 0, f"flatten: {p.stderr}")
    check("reference:" not in open(flat).read(), "the flattened file still has references")
    check(listing(binary, flat, tmp) == listing(binary, "scenes/warehouse.yaml", root),
          "the flattened scene's stage differs from the original's")
    c = os.path.join(tmp, "from_flattened")
    p = sdg(binary, "run", flat, "--out", c, *flags, cwd=tmp)
    check(p.returncode == 0, f"run flattened: {p.stderr[-600:]}")
    check(without_timing(dataset_hashes(c)) == without_timing(dataset_hashes(a)),
          "the flattened scene runs to different files")


def overrides(binary, root, tmp):
    folder = os.path.join(root, HERE)
    text = "\n".join(listing(binary, "overrides.yaml", folder))
    prims = {}
    current = None
    for line in text.splitlines()[1:]:
        if line.strip().startswith("/"):
            current = line.split()[0]
            prims[current] = []
        elif current:
            prims[current].append(line.strip())
    def has(path, entry):
        check(entry in prims.get(path, []), f"{path}: no '{entry}' in {prims.get(path)}")
    def lacks(path, prefix):
        check(not any(e.startswith(prefix) for e in prims.get(path, [])), f"{path}: unexpected '{prefix}'")
    has("/World/Plain", "semantics class: box")
    has("/World/Plain", "amplitude 0.1")
    has("/World/Moved", "xformOp:translate [2.0, 0.0, 0.0]")
    has("/World/Moved", "semantics class: crate")
    has("/World/Moved", "amplitude 0.5")
    has("/World/Moved", "behavior rotationRandomizer")
    has("/World/Moved", "material /World/Moved/Looks/Red (weakerThanDescendants)")
    has("/World/Moved/Marker", "frame:targetPrimPath '/World/Moved'")
    lacks("/World/Still", "behavior bob")
    has("/World/Still/Marker", "radius 0.2")
    has("/World/Plain/Marker", "radius 0.05")
    has("/World/Stack/High/Extra", "radius 0.1")
    has("/World/Stack/High", "xformOp:translate [0.0, 0.0, 1.0]")
    has("/World/Plain/Looks/Red", "inputs:diffuse_texture 'lib/tex/red.png'")
    check(text.count("behavior bob") == 4, f"bob attached {text.count('behavior bob')} times, expected 4")
    # Run it from another folder: paths still resolve; the script loaded once.
    p = sdg(binary, "run", os.path.join(folder, "overrides.yaml"), "--no-render", "--verbose", cwd=tmp)
    check(p.returncode == 0, f"run overrides.yaml from elsewhere: {p.stderr[-800:]}")


def instances(binary, tmp):
    lines = ["version: 1", "capture: {frames: 2, seed: 3}", "prims:", "  /Rack: {}"]
    lines += [f"  /Rack/Drill_{i:02d}: {{reference: assets/drill.yaml, translate: [{i}, 0, 0]}}" for i in range(20)]
    shutil.copytree(os.path.join(ROOT, "scenes", "assets"), os.path.join(tmp, "assets"))
    shutil.copytree(os.path.join(ROOT, "scenes", "props"), os.path.join(tmp, "props"))
    scene = os.path.join(tmp, "rack.yaml")
    open(scene, "w").write("\n".join(lines) + "\n")
    record = os.path.join(tmp, "rack.jsonl")
    p = sdg(binary, "run", scene, "--no-render", "--record", record, "--verbose", cwd=tmp)
    check(p.returncode == 0, f"rack: {p.stderr[-800:]}")
    check(p.stderr.count("reference: read ") == 1, f"the drill asset was read {p.stderr.count('reference: read ')} times")
    lines = open(record).readlines()
    first = json.loads(lines[1])  # frame 0 (line 0 is the pre-roll)
    moves = {c["prim"]: c["value"] for c in first["changes"] if c["attribute"] == "xformOp:translate"}
    offsets = {tuple(round(v - (i if k == 0 else 0), 9) for k, v in enumerate(moves[f"/Rack/Drill_{i:02d}"]))
               for i in range(20) if f"/Rack/Drill_{i:02d}" in moves}
    check(len(moves) == 20, f"{len(moves)} of 20 drills moved in the first frame")
    check(len(offsets) == 20, f"only {len(offsets)} distinct random offsets among 20 instances")


def errors(binary, tmp):
    lib = os.path.join(tmp, "errlib")
    os.makedirs(lib)
    cases = {
        "unknown_key": ("  /A: {type: Cube, colour: [1, 0, 0]}", "lib.yaml:3:20: error: /A: unknown key 'colour'"),
        "bad_value": ("  /A: {type: Cube, size: big}", "lib.yaml:3:26: error: /A.size: expected a number"),
        "unknown_behavior": ("  /A: {type: Cube, behaviors: {locationRandomiser: {}}}",
                             "lib.yaml:3:32: error: /A: unknown behavior 'locationRandomiser'"),
        "unknown_variable": ("  /A: {type: Cube, behaviors: {locationRandomizer: {intervall: 2}}}",
                             "lib.yaml:3:53: error: /A locationRandomizer: unknown key 'intervall'"),
        "missing_mesh": ("  /A: {type: Mesh, asset: nothing.glb}",
                         "lib.yaml:3:27: error: /S.asset: mesh 'errlib/nothing.glb' not found"),
        "missing_texture": ("  /A: {type: Material, inputs:diffuse_texture: nothing.png}",
                            "lib.yaml:3:48: error: /S.inputs:diffuse_texture: texture 'errlib/nothing.png' not found"),
    }
    for name, (prim, expected) in cases.items():
        open(os.path.join(lib, "lib.yaml"), "w").write(f"version: 1\nprims:\n{prim}\n")
        open(os.path.join(tmp, "scene.yaml"), "w").write("version: 1\nprims:\n  /S: {reference: errlib/lib.yaml}\n")
        p = sdg(binary, "validate", "scene.yaml", cwd=tmp)
        check(p.returncode == 2 and expected in p.stderr and "(referenced from scene.yaml:3:19)" in p.stderr,
              f"{name}: exit {p.returncode}, expected '{expected} ... (referenced from scene.yaml:3:19)':\n{p.stderr}")
    open(os.path.join(tmp, "scene.yaml"), "w").write("version: 1\nprims:\n  /S: {reference: errlib/none.yaml}\n")
    p = sdg(binary, "validate", "scene.yaml", cwd=tmp)
    check(p.returncode == 2 and "scene.yaml:3:19: error: reference: asset file not found" in p.stderr,
          f"missing asset: {p.returncode} {p.stderr}")
    open(os.path.join(lib, "a.yaml"), "w").write("version: 1\nprims:\n  /A: {reference: b.yaml}\n")
    open(os.path.join(lib, "b.yaml"), "w").write("version: 1\nprims:\n  /B: {reference: a.yaml}\n")
    open(os.path.join(tmp, "scene.yaml"), "w").write("version: 1\nprims:\n  /S: {reference: errlib/a.yaml}\n")
    p = sdg(binary, "validate", "scene.yaml", cwd=tmp)
    check(p.returncode == 2 and "a reference cycle: scene.yaml -> errlib/a.yaml -> errlib/b.yaml -> errlib/a.yaml"
          in p.stderr, f"cycle: {p.returncode} {p.stderr}")
    clash = os.path.join(ROOT, HERE)
    open(os.path.join(tmp, "clash.yaml"), "w").write(
        f"version: 1\nprims:\n  /X: {{reference: {clash}/lib/box.yaml}}\n  /Y: {{reference: {clash}/other/clash.yaml}}\n")
    p = sdg(binary, "validate", "clash.yaml", cwd=tmp)
    check(p.returncode == 2 and "other/bob.py:5:1: error: BEHAVIOR_NS 'bob' is already defined by" in p.stderr
          and "lib/bob.py" in p.stderr, f"script clash: {p.returncode} {p.stderr}")


ROOT = ""


def main():
    global ROOT
    binary, ROOT = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    with tempfile.TemporaryDirectory() as tmp:
        for part in (demo_and_flatten, overrides):
            folder = os.path.join(tmp, part.__name__)
            os.makedirs(folder)
            part(binary, ROOT, folder)
        for part in (instances, errors):
            folder = os.path.join(tmp, part.__name__)
            os.makedirs(folder)
            part(binary, folder)
    return finish("demo = flat demo, flatten round trip, overrides, 20 instances, errors located in both files")


if __name__ == "__main__":
    sys.exit(main())
