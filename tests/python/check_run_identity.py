#!/usr/bin/python3
"""A run's identity covers every input, and a failed run keeps its work.

Identity: a run is resumed, or a second shard started, after one input
changed (the script, a module it imports, a texture, the scene): each is
refused with exit 2 naming the changed file. Two shards that ran with other
inputs into one folder (as if they had started at the same moment) are
refused by `merge` (exit 2) and reported by `verify`.

Kept frames: a run whose script raises at update 3 exits 1 with frames 0-2
on disk and in the manifest (the last one was still in read-back when it
failed); one that raises in on_stop exits 1 with every frame and a contact
sheet. Resuming each (the failure was transient) gives the same bytes as a
run that never failed."""
import json
import os
import shutil
import subprocess
import sys
import tempfile

from checklib import check, dataset_hashes, failures, finish


def run(binary, *args, env=None):
    full = dict(os.environ)
    full.pop("SDG_TEST_FAIL", None)
    full.update(env or {})
    return subprocess.run([binary, *args], capture_output=True, text=True, env=full)


def manifest_frames(folder):
    frames = set()
    for name in os.listdir(folder):
        if name.startswith("manifest") and name.endswith(".jsonl"):
            for line in open(os.path.join(folder, name)):
                frames.add(json.loads(line)["frame"])
    return frames


def fresh_copy(source, texture, tmp, name):
    folder = os.path.join(tmp, name)
    shutil.copytree(source, folder)
    shutil.copy(texture, os.path.join(folder, "wood.png"))
    return folder


def main():
    binary = os.path.abspath(sys.argv[1])
    source, texture = sys.argv[2], sys.argv[3]
    flags = ["--threads", "2"]
    with tempfile.TemporaryDirectory() as tmp:
        base = fresh_copy(source, texture, tmp, "base")
        whole = f"{tmp}/whole"
        p = run(binary, "run", f"{base}/scene.yaml", "--out", whole, *flags)
        check(p.returncode == 0, f"whole run: exit {p.returncode}: {p.stderr[-400:]}")
        reference = dataset_hashes(whole)
        recorded = json.load(open(f"{whole}/.sdgbehave/run.json"))["inputs"]
        roles = {f["path"]: f["role"] for f in recorded["files"]}
        for path, role in [("scene.yaml", "scene"), ("mover.py", "script"), ("step_size.py", "python"),
                           ("wood.png", "file")]:
            check(roles.get(path) == role, f"run.json inputs: {path} should be a {role} input; have {roles}")

        # --resume after each kind of change is refused, naming the file.
        edits = {
            "mover.py": lambda t: t.replace("x + step", "x + 0.5 * step"),
            "step_size.py": lambda t: t.replace("-0.2, 0.2", "-0.3, 0.3"),
            "scene.yaml": lambda t: t.replace("size: 0.6", "size: 0.7"),
        }
        for n, (name, edit) in enumerate(edits.items()):
            folder = fresh_copy(source, texture, tmp, f"edit{n}")
            out = f"{tmp}/out{n}"
            p = run(binary, "run", f"{folder}/scene.yaml", "--out", out, "--frames", "6", *flags,
                    env={"SDG_TEST_FAIL": "3"})
            check(p.returncode == 1, f"{name}: the failing run should exit 1, got {p.returncode}: {p.stderr[-300:]}")
            path = os.path.join(folder, name)
            text = open(path).read()
            open(path, "w").write(edit(text))
            p = run(binary, "run", f"{folder}/scene.yaml", "--out", out, *flags, "--resume")
            check(p.returncode == 2 and f"{name}: changed" in p.stderr,
                  f"resume after editing {name}: want exit 2 naming it, got {p.returncode}: {p.stderr[-400:]}")
        folder = fresh_copy(source, texture, tmp, "texture")
        out = f"{tmp}/out_texture"
        run(binary, "run", f"{folder}/scene.yaml", "--out", out, *flags, env={"SDG_TEST_FAIL": "3"})
        shutil.copy(os.path.join(os.path.dirname(texture), "boards.png"), f"{folder}/wood.png")
        p = run(binary, "run", f"{folder}/scene.yaml", "--out", out, *flags, "--resume")
        check(p.returncode == 2 and "wood.png: changed" in p.stderr, f"resume after a new texture: {p.stderr[-400:]}")

        # A failure at update 3 keeps frames 0-2; resuming completes the same dataset.
        out = f"{tmp}/fails_at_3"
        p = run(binary, "run", f"{base}/scene.yaml", "--out", out, *flags, env={"SDG_TEST_FAIL": "3"})
        check(p.returncode == 1 and "failing at update 3" in p.stderr, f"failure at 3: {p.returncode} {p.stderr[-300:]}")
        check(manifest_frames(out) == {0, 1, 2}, f"failure at 3 kept frames {sorted(manifest_frames(out))}, want 0-2")
        check(os.path.exists(f"{out}/contact_sheet.png"), "failure at 3 wrote no contact sheet of frames 0-2")
        p = run(binary, "run", f"{base}/scene.yaml", "--out", out, *flags, "--resume")
        check(p.returncode == 0 and "3 kept from before" in p.stderr + p.stdout,
              f"resume after failure at 3: {p.returncode} {p.stderr[-300:]}")
        got = dataset_hashes(out)
        diff = sorted(k for k in set(got) | set(reference) if got.get(k) != reference.get(k))
        check(not diff, f"failure at 3, then resume: {len(diff)} files differ from a whole run: {diff[:6]}")

        # A failure in on_stop comes after every frame is written.
        out = f"{tmp}/fails_in_stop"
        p = run(binary, "run", f"{base}/scene.yaml", "--out", out, *flags, env={"SDG_TEST_FAIL": "stop"})
        check(p.returncode == 1 and "on_stop" in p.stderr, f"failure in on_stop: {p.returncode} {p.stderr[-300:]}")
        check(manifest_frames(out) == set(range(6)), f"failure in on_stop kept {sorted(manifest_frames(out))}")
        check(os.path.exists(f"{out}/contact_sheet.png"), "failure in on_stop wrote no contact sheet")

        # Shards of one folder with other inputs: the second is refused at its start...
        folder = fresh_copy(source, texture, tmp, "shards")
        out = f"{tmp}/sharded"
        p = run(binary, "run", f"{folder}/scene.yaml", "--out", out, "--shard", "0/2", *flags)
        check(p.returncode == 0, f"shard 0/2: {p.stderr[-300:]}")
        script = f"{folder}/step_size.py"
        original = open(script).read()
        open(script, "w").write(original.replace("-0.2, 0.2", "-0.25, 0.25"))
        p = run(binary, "run", f"{folder}/scene.yaml", "--out", out, "--shard", "1/2", *flags)
        check(p.returncode == 2 and "step_size.py: changed" in p.stderr, f"shard 1/2 with another module: {p.stderr[-300:]}")
        # ... and when both started before either wrote run.json, merge and verify catch it.
        other = f"{tmp}/sharded_other"
        p = run(binary, "run", f"{folder}/scene.yaml", "--out", other, "--shard", "1/2", *flags)
        check(p.returncode == 0, f"shard 1/2 alone: {p.stderr[-300:]}")
        for root, _, files in os.walk(other):
            for name in files:
                if name == "run.json":
                    continue
                rel = os.path.relpath(os.path.join(root, name), other)
                os.makedirs(os.path.dirname(os.path.join(out, rel)), exist_ok=True)
                shutil.copy(os.path.join(root, name), os.path.join(out, rel))
        v = run(binary, "verify", out)
        check(v.returncode == 1 and "step_size.py: changed" in v.stdout, f"verify of mixed shards: {v.stdout[-400:]}")
        m = run(binary, "merge", out)
        check(m.returncode == 2 and "step_size.py: changed" in m.stderr, f"merge of mixed shards: {m.stderr[-400:]}")
        # Restored, the second shard resumes and the merge gives the whole run's bytes.
        open(script, "w").write(original)
        shutil.rmtree(out)
        for shard in ("0/2", "1/2"):
            p = run(binary, "run", f"{folder}/scene.yaml", "--out", out, "--shard", shard, *flags)
            check(p.returncode == 0, f"shard {shard}: {p.stderr[-300:]}")
        m = run(binary, "merge", out)
        check(m.returncode == 0, f"merge: {m.stderr[-300:]}")
        got = dataset_hashes(out)
        diff = sorted(k for k in set(got) | set(reference) if got.get(k) != reference.get(k))
        check(not diff, f"merged shards differ from a whole run: {diff[:6]}")
    return finish("ok")


if __name__ == "__main__":
    sys.exit(main())
