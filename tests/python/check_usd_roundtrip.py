#!/usr/bin/python3
"""Export then import reproduces the scene: `export-usd scenes/warehouse.yaml -o x.usda`, then
`inspect` of x.usda prints what `inspect` of the YAML scene prints (less the lines and comments
that name the source file; the layer's absolute file paths read relative to the scene's folder), and `run` of x.usda writes the
same dataset, byte for byte (every file but run_summary.json, which holds timings, and
.sdgbehave/run.json, which hashes the input files), as `run` of the
YAML scene with the same seed, frames and flags — the pre-roll stacking, the drill's own materials
and every behavior included. Small frames keep it fast.

  check_usd_roundtrip.py BIN REPO
"""
import os
import subprocess
import sys
import tempfile

from checklib import check, dataset_hashes, finish

FLAGS = ["--frames", "2", "--resolution", "96x96", "--seed", "7"]


def comparable(inspect_text, strip_prefix=None):
    """inspect's lines less what names the source: the `scene` and `asset_roots` lines and each
    value's origin comment (`# file:line:col`). The exported layer holds file paths absolute where
    the YAML scene writes them relative to its folder: `strip_prefix` (that folder) is taken off."""
    out = []
    for line in inspect_text.splitlines():
        if line.startswith("scene ") or line.startswith("asset_roots: "):
            continue
        line = line.split("  # ")[0]
        if strip_prefix:
            for before in ("'", ","):
                line = line.replace(before + strip_prefix + "/", before)
        out.append(line)
    return out


def same_line(a, b):
    """Equal, or both long strings inspect cut short ('...') that agree as far as both go."""
    if a == b:
        return True
    cut = [x[:-4] for x in (a, b) if x.endswith("...'")]
    if not cut:
        return False
    n = min(len(x) for x in cut)
    return a[:n] == b[:n]


def sdg(binary, *args):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=300)


def main():
    binary, repo = sys.argv[1], sys.argv[2]
    scene = os.path.join(repo, "scenes", "warehouse.yaml")
    with tempfile.TemporaryDirectory() as tmp:
        stage = os.path.join(tmp, "warehouse.usda")
        r = sdg(binary, "export-usd", scene, "-o", stage)
        check(r.returncode == 0, f"export-usd: exit {r.returncode}: {r.stderr}")
        if r.returncode != 0:
            return finish()
        yaml_inspect, usd_inspect = sdg(binary, "inspect", scene), sdg(binary, "inspect", stage)
        check(yaml_inspect.returncode == 0 and usd_inspect.returncode == 0,
              f"inspect: exits {yaml_inspect.returncode}, {usd_inspect.returncode}: {usd_inspect.stderr}")
        a = comparable(yaml_inspect.stdout)
        b = comparable(usd_inspect.stdout, os.path.realpath(os.path.dirname(scene)))
        diff = [f"  yaml: {x}\n  usda: {y}" for x, y in zip(a, b) if not same_line(x, y)]
        check(len(a) == len(b) and not diff,
              f"inspect differs ({len(a)} and {len(b)} lines); first differences:\n" + "\n".join(diff[:8]))
        outs = {}
        for name, source in (("yaml", scene), ("usda", stage)):
            out = os.path.join(tmp, name)
            r = sdg(binary, "run", source, *FLAGS, "--out", out)
            check(r.returncode == 0, f"run {source}: exit {r.returncode}: {r.stderr[-2000:]}")
            # .sdgbehave/run.json is the run's identity: the hashes of its input files, which differ.
            outs[name] = {f: h for f, h in dataset_hashes(out).items() if f != os.path.join(".sdgbehave", "run.json")}
        yaml_files, usd_files = outs["yaml"], outs["usda"]
        check(yaml_files, "the YAML run wrote no files")
        check(sorted(yaml_files) == sorted(usd_files),
              f"different files: only yaml {sorted(set(yaml_files) - set(usd_files))}, "
              f"only usda {sorted(set(usd_files) - set(yaml_files))}")
        differing = [f for f in sorted(yaml_files) if f in usd_files and yaml_files[f] != usd_files[f]]
        check(not differing, f"{len(differing)} files differ: {differing[:10]}")
    return finish(f"export -> import: inspect and {len(yaml_files)} dataset files identical")


if __name__ == "__main__":
    sys.exit(main())
