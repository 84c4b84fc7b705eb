#!/usr/bin/python3
"""Export then import reproduces the scene: `export-usd scenes/warehouse.yaml -o x.usda`, then
`inspect` of x.usda prints what `inspect` of the YAML scene prints (less the lines and comments
that name the source file; the layer's absolute file paths read relative to the scene's folder), and `run` of x.usda writes the
same dataset, byte for byte (every file but run_summary.json, which holds timings, and
.sdgbehave/run.json, which hashes the input files), as `run` of the
YAML scene with the same seed, frames and flags — the pre-roll stacking, the drill's own materials
and every behavior included; also every_type.yaml (custom attributes) and camera_orbit.yaml (a
behavior script the layer lists). Small frames keep it fast.

  check_usd_roundtrip.py BIN REPO
"""
import os
import subprocess
import sys
import tempfile

from checklib import check, dataset_hashes, finish

FLAGS = ["--frames", "2", "--resolution", "96x96", "--seed", "7"]


def asset_folders(inspect_text, scene):
    """The folders the YAML scene's relative file paths are relative to: its asset roots (from
    inspect's `asset_roots:` line) and its own folder, absolute, longest first."""
    base = os.path.dirname(os.path.abspath(scene))
    folders = {os.path.realpath(base)}
    for line in inspect_text.splitlines():
        if line.startswith("asset_roots: "):
            folders |= {os.path.realpath(os.path.join(base, r.strip())) for r in line[13:].split(",")}
    return sorted(folders, key=len, reverse=True)


def comparable(inspect_text, strip_prefixes=()):
    """inspect's lines less what names the source: the `scene` and `asset_roots` lines and each
    value's origin comment (`# file:line:col`). The exported layer holds file paths absolute where
    the YAML scene writes them relative to an asset root: `strip_prefixes` are taken off."""
    out = []
    for line in inspect_text.splitlines():
        if line.startswith("scene ") or line.startswith("asset_roots: "):
            continue
        line = line.split("  # ")[0]
        for prefix in strip_prefixes:
            for before in ("'", ",", " "):
                line = line.replace(before + prefix + "/", before)
        out.append(line)
    return out


def same_line(a, b):
    """Equal, or both long strings inspect cut short ('...') that agree as far as both go."""
    if a == b:
        return True
    # A cut string may end inside an absolute path whose prefix could not be
    # stripped ('...,/wor...'): compare up to the last whole list item.
    cut = [x[:-4] for x in (a, b) if x.endswith("...'")]
    cut = [x[: x.rfind(",") + 1] if "," in x else x for x in cut]
    if not cut:
        return False
    n = min(len(x) for x in cut)
    return a[:n] == b[:n]


def sdg(binary, *args):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=300)


def roundtrip(binary, scene, tmp):
    """The number of dataset files compared; failures are collected by check()."""
    name = os.path.splitext(os.path.basename(scene))[0]
    stage = os.path.join(tmp, name + ".usda")
    r = sdg(binary, "export-usd", scene, "-o", stage)
    check(r.returncode == 0, f"export-usd {scene}: exit {r.returncode}: {r.stderr}")
    if r.returncode != 0:
        return 0
    yaml_inspect, usd_inspect = sdg(binary, "inspect", scene), sdg(binary, "inspect", stage)
    check(yaml_inspect.returncode == 0 and usd_inspect.returncode == 0,
          f"inspect {name}: exits {yaml_inspect.returncode}, {usd_inspect.returncode}: {usd_inspect.stderr}")
    a = comparable(yaml_inspect.stdout)
    b = comparable(usd_inspect.stdout, asset_folders(yaml_inspect.stdout, scene))
    diff = [f"  yaml: {x}\n  usda: {y}" for x, y in zip(a, b) if not same_line(x, y)]
    check(len(a) == len(b) and not diff,
          f"{name}: inspect differs ({len(a)} and {len(b)} lines); first differences:\n" + "\n".join(diff[:8]))
    outs = {}
    for kind, source in (("yaml", scene), ("usda", stage)):
        out = os.path.join(tmp, f"{name}_{kind}")
        r = sdg(binary, "run", source, *FLAGS, "--out", out)
        check(r.returncode == 0, f"run {source}: exit {r.returncode}: {r.stderr[-2000:]}")
        # .sdgbehave/run.json is the run's identity: the hashes of its input files, which differ.
        outs[kind] = {f: h for f, h in dataset_hashes(out).items() if f != os.path.join(".sdgbehave", "run.json")}
    yaml_files, usd_files = outs["yaml"], outs["usda"]
    check(yaml_files, f"{name}: the YAML run wrote no files")
    check(sorted(yaml_files) == sorted(usd_files),
          f"{name}: different files: only yaml {sorted(set(yaml_files) - set(usd_files))}, "
          f"only usda {sorted(set(usd_files) - set(yaml_files))}")
    differing = [f for f in sorted(yaml_files) if f in usd_files and yaml_files[f] != usd_files[f]]
    check(not differing, f"{name}: {len(differing)} files differ: {differing[:10]}")
    return len(yaml_files)


def main():
    binary, repo = sys.argv[1], sys.argv[2]
    # The demo (pre-roll stacking, smart assets, mesh files with their own materials), every prim
    # type with custom attributes, and a scene whose behavior is a script the layer lists.
    scenes = [os.path.join(repo, "scenes", p) for p in ("warehouse.yaml", "every_type.yaml",
                                                        os.path.join("examples", "camera_orbit.yaml"))]
    with tempfile.TemporaryDirectory() as tmp:
        files = sum(roundtrip(binary, scene, tmp) for scene in scenes)
    return finish(f"export -> import: inspect and {files} dataset files identical ({len(scenes)} scenes)")


if __name__ == "__main__":
    sys.exit(main())
