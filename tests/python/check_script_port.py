#!/usr/bin/python3
"""The ported scripts reproduce the built-ins byte for byte.

scenes/examples/scripts/location_randomizer.py and look_at.py re-implement
locationRandomizer and lookAtBehavior with the documented script API. For
each scene below, a copy with the scripted behaviors swapped in for the
built-ins must write the same dataset files (every file but the run summary
and run.json, which hold timings and the scene's hash) and the same change
record (what changed at each frame, and what the stop put back).

usage: check_script_port.py SDGBEHAVE SOURCE_DIR"""
import filecmp
import os
import re
import subprocess
import sys
import tempfile

# The demo as one flat file (scenes/warehouse.yaml keeps these behaviors in
# its smart assets), and two examples.
SCENES = ["tests/data/references/warehouse_flat.yaml", "scenes/examples/location_randomizer.yaml",
          "scenes/examples/look_at.yaml"]
SWAPS = {"locationRandomizer": "scriptedLocationRandomizer", "lookAtBehavior": "scriptedLookAtBehavior"}
NOT_COMPARED = {"run_summary.json", "run.json"}


def scripted_copy(source_dir, scene, folder):
    """The scene with the scripted behaviors swapped in, written to `folder`;
    its asset roots and scripts point back into the source tree."""
    path = os.path.join(source_dir, scene)
    with open(path, encoding="utf-8") as f:
        text = f.read()
    scene_dir = os.path.dirname(path)
    roots = [scene_dir]
    declared = re.search(r"^asset_roots: \[(.*)\]$", text, flags=re.M)
    if declared:
        roots += [os.path.normpath(os.path.join(scene_dir, r.strip())) for r in declared.group(1).split(",")]
    for builtin, scripted in SWAPS.items():
        text, n = re.subn(rf"(^\s+){builtin}:", rf"\g<1>{scripted}:", text, flags=re.M)
    scripts = os.path.join(source_dir, "scenes", "examples", "scripts")
    text = re.sub(r"^asset_roots:.*$", "", text, flags=re.M)
    header = (f"asset_roots: [{', '.join(roots)}]\n"
              f"scripts: [{scripts}/location_randomizer.py, {scripts}/look_at.py]\n")
    text = re.sub(r"^version: 1$", "version: 1\n" + header, text, count=1, flags=re.M)
    out = os.path.join(folder, "scripted_" + os.path.basename(scene))
    with open(out, "w", encoding="utf-8") as f:
        f.write(text)
    return out


def run(binary, scene, out, record):
    cmd = [binary, "run", scene, "--frames", "4", "--seed", "7", "--resolution", "96x96", "--out", out,
           "--record", record, "--quiet"]
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    if result.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} exited {result.returncode}:\n{result.stderr}")


def files_under(root):
    found = []
    for folder, _, names in os.walk(root):
        for name in names:
            if name not in NOT_COMPARED:
                found.append(os.path.relpath(os.path.join(folder, name), root))
    return sorted(found)


def main():
    binary, source_dir = sys.argv[1], os.path.abspath(sys.argv[2])
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in SCENES:
            scripted = scripted_copy(source_dir, scene, tmp)
            stem = os.path.splitext(os.path.basename(scene))[0]
            a, b = os.path.join(tmp, stem + "_builtin"), os.path.join(tmp, stem + "_scripted")
            run(binary, os.path.join(source_dir, scene), a, a + ".jsonl")
            run(binary, scripted, b, b + ".jsonl")
            names = files_under(a)
            if names != files_under(b):
                failures.append(f"{scene}: different files: {sorted(set(names) ^ set(files_under(b)))}")
                continue
            for name in names:
                if not filecmp.cmp(os.path.join(a, name), os.path.join(b, name), shallow=False):
                    failures.append(f"{scene}: {name} differs")
            if not filecmp.cmp(a + ".jsonl", b + ".jsonl", shallow=False):
                failures.append(f"{scene}: the change records differ")
            print(f"{scene}: {len(names)} files and the change record identical")
    if failures:
        print("\n".join(failures))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
