"""A finished dataset folder: its run record, its manifest and the checks
`sdgbehave verify` makes, and the files of each (frame, render product).

A folder is a finished dataset when `manifest.jsonl` lists every frame of
every render product that `.sdgbehave/run.json` plans, every listed file is
there with its size and SHA-256, and every shard ran with the same inputs.
An unmerged sharded run (only `manifest.shard-*.jsonl`) is not finished yet:
`sdgbehave merge` writes its manifest."""
import concurrent.futures
import hashlib
import json
import os
import re


class DatasetError(Exception):
    """The folder is not a finished sdgbehave dataset, or a file in it is not what the manifest says."""


PARTS_FOLDER = ".sdgbehave"
# <kind>_<frame digits>.<ext>, as the BasicWriter names every per-frame file (kinds and camera names
# start with a letter or _, which keeps BOP's <im_id>_<gt_id>.png masks out).
_FRAME_FILE = re.compile(r"^(?P<stem>[A-Za-z_].*)_(?P<digits>[0-9]+)\.(?P<ext>png|npy|json|bin)$")


def read_json(path, what):
    """The JSON value of a file, or a DatasetError naming the file and `what` it is."""
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except FileNotFoundError:
        raise DatasetError(f"{path}: missing ({what})") from None
    except (OSError, ValueError) as e:
        raise DatasetError(f"{path}: cannot read {what}: {e}") from None


def read_manifest(root):
    """Every complete line of root/manifest.jsonl as {(frame, product): [file, ...]}, each file a
    {"path", "bytes", "sha256"} dict; a later line for the same frame and product wins, as in
    `sdgbehave verify`."""
    path = os.path.join(root, "manifest.jsonl")
    if not os.path.isfile(path):
        shards = sorted(name for name in os.listdir(root) if name.startswith("manifest.") and name.endswith(".jsonl"))
        hint = (f"; it holds the per-shard manifests {', '.join(shards)}: run `sdgbehave merge {root}` once every "
                f"shard has finished") if shards else "; is it the --out folder of a finished `sdgbehave run`?"
        raise DatasetError(f"{root}: not a finished sdgbehave dataset: no manifest.jsonl{hint}")
    entries = {}
    with open(path, encoding="utf-8") as f:
        for line in f:
            try:
                record = json.loads(line)
                key = (int(record["frame"]), int(record.get("product", 0)))
                files = [{"path": str(e["path"]), "bytes": int(e["bytes"]), "sha256": str(e["sha256"])}
                         for e in record["files"]]
            except (ValueError, KeyError, TypeError):
                continue  # a torn or foreign line: `sdgbehave verify` skips it too
            entries[key] = files
    if not entries:
        raise DatasetError(f"{path}: no frame listed; nothing to read")
    return entries


def _sha256(path):
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def verify_files(root, entries, hashes=True):
    """Problems ("path: missing", ...) of the manifest's files: present, of the listed size and,
    with `hashes`, of the listed SHA-256 (hashed on a few threads: hashlib releases the GIL)."""
    listed = [f for files in entries.values() for f in files]
    problems, to_hash = [], []
    for f in listed:
        path = os.path.join(root, f["path"])
        try:
            size = os.path.getsize(path)
        except OSError:
            problems.append(f"{f['path']}: missing")
            continue
        if size != f["bytes"]:
            problems.append(f"{f['path']}: {size} bytes, the manifest says {f['bytes']}")
        elif hashes:
            to_hash.append(f)
    if to_hash:
        with concurrent.futures.ThreadPoolExecutor(max_workers=min(8, os.cpu_count() or 1)) as pool:
            digests = pool.map(lambda f: _sha256(os.path.join(root, f["path"])), to_hash)
            for f, digest in zip(to_hash, digests):
                if digest != f["sha256"]:
                    problems.append(f"{f['path']}: sha256 differs from the manifest")
    return problems


def _shard_input_problems(root, run):
    """Shards whose recorded inputs differ from run.json's, as `sdgbehave verify` reports them."""
    parts = os.path.join(root, PARTS_FOLDER)
    recorded = {f["path"]: f["sha256"] for f in run.get("inputs", {}).get("files", [])}
    problems = []
    for name in sorted(os.listdir(parts)) if os.path.isdir(parts) else []:
        if not (name.startswith("inputs.") and name.endswith(".json")):
            continue
        shard = name[len("inputs."):-len(".json")]
        inputs = read_json(os.path.join(parts, name), f"the inputs of shard {shard}")
        now = {f.get("path"): f.get("sha256") for f in inputs.get("files", [])}
        if now != recorded or inputs.get("sdgbehave") != run.get("inputs", {}).get("sdgbehave"):
            changed = sorted(p for p in set(now) | set(recorded) if now.get(p) != recorded.get(p))
            problems.append(f"shard {shard} ran with other inputs ({', '.join(changed) or 'another sdgbehave'})")
    return problems


def read_run(root, verify=True):
    """(run.json's record, manifest entries) of a finished dataset, after the checks of
    `sdgbehave verify` (`verify=True`) or the cheap ones only (`verify=False`: every listed file
    present with its listed size, no hashing); DatasetError naming every problem otherwise."""
    if not os.path.isdir(root):
        raise DatasetError(f"{root}: not a folder")
    entries = read_manifest(root)
    run = read_json(os.path.join(root, PARTS_FOLDER, "run.json"), "the run record `sdgbehave run` writes")
    try:
        frames = int(run["iterations"]) * int(run["frames_per_iteration"])
        products = [str(p) for p in run["products"]]
    except (KeyError, TypeError, ValueError) as e:
        raise DatasetError(f"{root}/{PARTS_FOLDER}/run.json: corrupt ({e})") from None
    problems = [f"{root}/{p}" for p in verify_files(root, entries, hashes=verify)]
    problems += [f"{root}: {p}" for p in _shard_input_problems(root, run)]
    expected = {(frame, product) for frame in range(frames) for product in range(len(products))}
    missing = sorted(expected - set(entries))
    if missing:
        shown = ", ".join(f"frame {f} of {products[p] if p < len(products) else p}" for f, p in missing[:5])
        more = f" and {len(missing) - 5} more" if len(missing) > 5 else ""
        problems.append(f"{root}: the run is incomplete ({len(entries)} of {len(expected)} frame outputs; "
                        f"missing {shown}{more}); resume it with `sdgbehave run ... --resume`")
    if problems:
        raise DatasetError(f"{root}: not a finished sdgbehave dataset ({len(problems)} problems):\n  "
                           + "\n  ".join(problems[:20]) + ("\n  ..." if len(problems) > 20 else ""))
    return run, entries


def frame_files(files, frame, product_name, several_products):
    """{kind: {ext: relative path}} of one (frame, product)'s BasicWriter files, kind being the
    file name's stem without the frame number (and without `<camera>_` in a common output folder):
    `rgb`, `semantic_segmentation_labels`, `bounding_box_2d_tight`, ..."""
    kinds = {}
    for f in files:
        path = f["path"]
        if path.startswith(PARTS_FOLDER + "/"):
            continue  # COCO fragments and contact-sheet tiles
        match = _FRAME_FILE.match(os.path.basename(path))
        if not match or int(match["digits"]) != frame:
            continue
        stem = match["stem"]
        # With several cameras: <camera>/<annotator>/<kind>_X, or with use_common_output_dir
        # <annotator>/<camera>_<kind>_X, whose camera prefix is not part of the kind.
        in_common_folder = path.count("/") == 1
        if several_products and in_common_folder and stem.startswith(product_name + "_"):
            stem = stem[len(product_name) + 1:]
        kinds.setdefault(stem, {})[match["ext"]] = path
    return kinds
