#!/usr/bin/python3
"""The example behavior scripts (scenes/examples/scripts/camera_orbit.py,
material_randomizer.py, distractor_scatter.py, dome_randomizer.py) run from
their example scenes, reproducibly, and do what their docstrings say.

For each scene:
- a run with --threads 1 and one with --threads 2 (same seed) write
  byte-identical files (all but run_summary.json and .sdgbehave/run.json,
  which hold timings and the scene's hash);
- the scene --save-stage wrote, run again, writes those files too;
- another seed changes every rgb image;
- a --no-render --record run is read back: each frame's stage is rebuilt
  from the scene as `sdgbehave inspect` prints it plus the recorded changes,
  the behavior's promise is checked on it (camera distance, elevation,
  azimuth and aim; material colours and ranges; distractor count, volume,
  scale), the run changes no prim it has no business with, and the stop
  line puts back exactly the stage from before play.

usage: check_script_examples.py SDGBEHAVE SOURCE_DIR    (stdlib and numpy only)"""
import ast
import filecmp
import glob
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

FRAMES, RECORD_FRAMES = 6, 4
NOT_COMPARED = {"run_summary.json", os.path.join(".sdgbehave", "run.json")}
GEOMETRY = {"Mesh", "Cube", "Sphere", "Cylinder", "Cone", "Capsule", "Plane"}
TOLERANCE = 1e-6

failures = []


def fail(scene, message):
    failures.append(f"{scene}: {message}")


# --- running the binary ----------------------------------------------------

def run(binary, *args):
    cmd = [binary, *args]
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    if result.returncode != 0:
        raise RuntimeError(f"`{' '.join(cmd)}` exited {result.returncode}:\n{result.stderr.strip()}")
    return result.stdout


def dataset_files(root):
    found = []
    for folder, _, names in os.walk(root):
        for name in names:
            relative = os.path.relpath(os.path.join(folder, name), root)
            if relative not in NOT_COMPARED:
                found.append(relative)
    return sorted(found)


def compare_datasets(scene, a, b, what):
    names = dataset_files(a)
    if not names:
        fail(scene, f"{a} holds no files")
        return 0
    other = dataset_files(b)
    if names != other:
        fail(scene, f"{what}: different files: {sorted(set(names) ^ set(other))[:10]}")
        return 0
    different = [n for n in names if not filecmp.cmp(os.path.join(a, n), os.path.join(b, n), shallow=False)]
    if different:
        fail(scene, f"{what}: {len(different)} files differ, e.g. {different[:5]}")
    return len(names)


# --- the stage as `sdgbehave inspect` prints it ----------------------------

def parse_value(text):
    if text in ("true", "false"):
        return text == "true"
    try:
        return ast.literal_eval(text)
    except (ValueError, SyntaxError):
        return text


class Prim:
    def __init__(self, path, type_name):
        self.path, self.type = path, type_name
        self.values = {}       # xform ops and authored attributes (exposed variables aside)
        self.behaviors = {}    # namespace -> {variable: value}
        self.world = None      # world position
        self.material = None   # bound material path


def inspect_stage(binary, scene):
    """{path: Prim} from `sdgbehave inspect`, in stage order."""
    prims, current, behavior, detail = {}, None, None, 0
    listing = False
    for line in run(binary, "inspect", scene).splitlines():
        if line.startswith("prims ("):
            listing = True
            continue
        if not listing or not line.strip():
            continue
        indent, text = len(line) - len(line.lstrip(" ")), line.strip().split("  # ", 1)[0]
        if text.startswith("/"):
            path, type_name = text.split()[:2]
            current, behavior, detail = Prim(path, type_name), None, indent + 4
            prims[path] = current
            continue
        if behavior is not None and indent == detail + 2:
            name, _, value = text.partition(" ")
            current.behaviors[behavior][name] = parse_value(value)
            continue
        behavior = None
        if text.startswith("world position "):
            current.world = parse_value(text[len("world position "):])
        elif text.startswith("behavior "):
            behavior = text[len("behavior "):]
            current.behaviors[behavior] = {}
        elif text.startswith("material "):
            current.material = text.split()[1]
        elif text.startswith(("semantics ", "metadata ")):
            pass
        else:
            name, _, value = text.partition(" ")
            if value.endswith("  (custom)"):
                value = value[:-len("  (custom)")]
            current.values[name] = parse_value(value)
    return prims


def original_state(prims):
    """{(prim, attribute): value} in the record's terms ("prim" is the type)."""
    state = {}
    for p in prims.values():
        state[(p.path, "prim")] = p.type
        for name, value in p.values.items():
            state[(p.path, name)] = value
        if p.material:
            state[(p.path, "material:binding")] = p.material
    return state


# --- the record --------------------------------------------------------------

def value_of(state, key):
    """A key's value; None when absent or when its prim is gone."""
    prim, attribute = key
    if attribute != "prim" and (prim, "prim") in state and state[(prim, "prim")] is None:
        return None
    return state.get(key)


def same(a, b):
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return abs(a - b) <= TOLERANCE * max(1.0, abs(a), abs(b))
    return a == b


class Record:
    """The record of a --no-render run, replayed over the inspected stage."""

    def __init__(self, scene, path, original):
        with open(path, encoding="utf-8") as f:
            self.lines = [json.loads(line) for line in f]
        head, self.frames, stop = self.lines[0], self.lines[1:-1], self.lines[-1]
        if head.get("event") != "preroll" or stop.get("event") != "stop":
            raise RuntimeError(f"{path}: expected a pre-roll line first and a stop line last")
        if [line.get("frame") for line in self.frames] != list(range(RECORD_FRAMES)):
            raise RuntimeError(f"{path}: expected frames 0..{RECORD_FRAMES - 1}, found "
                               f"{[line.get('frame') for line in self.frames]}")
        state = dict(original)
        self.apply(state, head)
        self.before_play = dict(state)
        self.states, self.touched = [], set()
        for line in self.frames:
            self.apply(state, line)
            self.states.append(dict(state))
        self.after_stop = dict(state)
        self.apply(self.after_stop, stop)
        self.stop = stop

    def apply(self, state, line):
        for change in line["changes"]:
            key = (change["prim"], change["attribute"])
            state[key] = change["value"]
            if line is not self.lines[0]:
                self.touched.add(key)

    def changed_prims(self):
        return sorted({prim for prim, _ in self.touched})


def check_restored(scene, record):
    """The stop line leaves every key the run touched as it was before play."""
    wrong = []
    for key in sorted(record.touched):
        before, after = value_of(record.before_play, key), value_of(record.after_stop, key)
        if not same(before, after):
            wrong.append(f"{key[0]}.{key[1]}: {after!r} after stop, {before!r} before play")
    if wrong:
        fail(scene, f"the stop does not restore the stage ({len(wrong)} keys), e.g. " + "; ".join(wrong[:4]))
    if not record.stop["changes"]:
        fail(scene, "the stop line restores nothing although the frames changed the stage")


def check_only_under(scene, record, allowed):
    stray = [p for p in record.changed_prims() if not any(p == a or p.startswith(a + "/") for a in allowed)]
    if stray:
        fail(scene, f"the run changed prims outside {allowed}: {stray[:5]}")


# --- vector helpers ------------------------------------------------------------

def unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def quat_matrix(q):
    w, x, y, z = unit(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def within(value, low, high, slack=TOLERANCE):
    return low - slack <= value <= high + slack


def only_translated_parents(scene, prims, path):
    """The prim's parents carry no transform (so its translate is its world position)."""
    parent = path.rsplit("/", 1)[0]
    while parent:
        if any(k.startswith("xformOp:") for k in prims[parent].values):
            fail(scene, f"this check expects {parent} to have no transform")
        parent = parent.rsplit("/", 1)[0]


# --- the behaviors' promises -------------------------------------------------

def check_camera_orbit(scene, prims, record, dataset):
    cameras = [p for p in prims.values() if "cameraOrbit" in p.behaviors]
    if len(cameras) != 1:
        fail(scene, f"expected one prim with cameraOrbit, found {len(cameras)}")
        return "no camera"
    camera, v = cameras[0], cameras[0].behaviors["cameraOrbit"]
    only_translated_parents(scene, prims, camera.path)
    target_path = v["targetPrimPath"]
    target = np.array(prims[target_path].world if target_path else v["targetLocation"], dtype=float)
    up = unit(v["upAxis"])
    reference = np.array([1.0, 0, 0]) if abs(up[0]) < 0.9 else np.array([0, 1.0, 0])
    e1 = unit(reference - reference.dot(up) * up)
    e2 = np.cross(up, e1)
    check_only_under(scene, record, [camera.path])
    eyes = []
    for frame, state in enumerate(record.states):
        eye = np.array(value_of(state, (camera.path, "xformOp:translate")), dtype=float)
        orient = value_of(state, (camera.path, "xformOp:orient"))
        offset = eye - target
        distance = float(np.linalg.norm(offset))
        elevation = math.degrees(math.asin(max(-1.0, min(1.0, offset.dot(up) / distance))))
        azimuth = math.degrees(math.atan2(offset.dot(e2), offset.dot(e1))) % 360
        where = f"frame {frame}"
        if not within(distance, *v["distanceRange"]):
            fail(scene, f"{where}: the camera is {distance:.4f} from the target, outside {v['distanceRange']}")
        if not within(elevation, *v["elevationRange"], slack=1e-4):
            fail(scene, f"{where}: elevation {elevation:.4f} outside {v['elevationRange']}")
        low, high = v["azimuthRange"]
        if high - low < 360 and not (azimuth - low) % 360 <= (high - low) + 1e-4:
            fail(scene, f"{where}: azimuth {azimuth:.4f} outside {v['azimuthRange']}")
        if orient is None:
            fail(scene, f"{where}: the camera has no xformOp:orient")
            continue
        r = quat_matrix(orient)
        forward, camera_up, right = -r[:, 2], r[:, 1], r[:, 0]
        if forward.dot(-offset / distance) < 1 - 1e-9:
            fail(scene, f"{where}: the camera looks along {forward.round(4)}, not at the target")
        if camera_up.dot(up) <= 0 or abs(right.dot(up)) > 1e-6:
            fail(scene, f"{where}: the camera is not upright (its +Y {camera_up.round(4)}, +X {right.round(4)})")
        eyes.append(eye)
    if any(np.allclose(a, b) for a, b in zip(eyes, eyes[1:])):
        fail(scene, "the camera did not move between two frames")
    return f"camera {len(eyes)} frames within distance {v['distanceRange']} and aimed at {target_path or 'the point'}"


def check_material_randomizer(scene, prims, record, dataset):
    owners = [p for p in prims.values() if "materialRandomizer" in p.behaviors]
    if len(owners) != 1:
        fail(scene, f"expected one prim with materialRandomizer, found {len(owners)}")
        return "no owner"
    owner, v = owners[0], owners[0].behaviors["materialRandomizer"]
    below = [p for p in prims.values() if p.path == owner.path or p.path.startswith(owner.path + "/")]
    if not v["includeChildren"]:
        below = [owner]
    geometry = [p.path for p in below if p.type in GEOMETRY]
    if not geometry:
        fail(scene, "no geometry prim below the behavior's prim")
        return "no geometry"
    check_only_under(scene, record, geometry + ["/Behaviors"])
    stray = [p for p in record.changed_prims() if p.startswith("/Behaviors/") and p != "/Behaviors"
             and not p.startswith("/Behaviors/materialRandomizer")]
    if stray:
        fail(scene, f"prims created outside /Behaviors/materialRandomizer: {stray}")
    colour_low, colour_high = v["range:minColor"], v["range:maxColor"]
    previous = None
    for frame, state in enumerate(record.states):
        where = f"frame {frame}"
        bound = [value_of(state, (g, "material:binding")) for g in geometry]
        if len(set(bound)) != len(bound) or None in bound:
            fail(scene, f"{where}: the geometry prims do not each have a material of their own: {bound}")
            continue
        values = []
        for g, m in zip(geometry, bound):
            if not m.startswith("/Behaviors/materialRandomizer/") or value_of(state, (m, "prim")) != "Material":
                fail(scene, f"{where}: {g} is bound to {m}, not to a Material the behavior created")
                continue
            colour = value_of(state, (m, "inputs:diffuse_color_constant"))
            roughness = value_of(state, (m, "inputs:reflection_roughness_constant"))
            metallic = value_of(state, (m, "inputs:metallic_constant"))
            if colour is None or roughness is None or metallic is None:
                fail(scene, f"{where}: {m} lacks its colour, roughness or metalness")
                continue
            if not all(within(c, lo, hi) for c, lo, hi in zip(colour, colour_low, colour_high)):
                fail(scene, f"{where}: {m} colour {colour} outside {colour_low} .. {colour_high}")
            if not within(roughness, *v["roughnessRange"]):
                fail(scene, f"{where}: {m} roughness {roughness} outside {v['roughnessRange']}")
            if not within(metallic, *v["metallicRange"]):
                fail(scene, f"{where}: {m} metalness {metallic} outside {v['metallicRange']}")
            values.append((tuple(colour), roughness, metallic))
        if previous is not None and any(a == b for a, b in zip(values, previous)):
            fail(scene, f"{where}: a material kept last frame's values")
        previous = values
    return f"{len(geometry)} prims, each with its own material within range, {len(record.states)} frames"


def check_distractor_scatter(scene, prims, record, dataset):
    owners = [p for p in prims.values() if "distractorScatter" in p.behaviors]
    if len(owners) != 1:
        fail(scene, f"expected one prim with distractorScatter, found {len(owners)}")
        return "no owner"
    owner, v = owners[0], owners[0].behaviors["distractorScatter"]
    anchor = np.array(owner.world if owner.world is not None else (0, 0, 0), dtype=float)
    check_only_under(scene, record, ["/Behaviors"])
    shapes = [s.strip() for s in v["shapes:csv"].split(",") if s.strip()] if v["shapes:csv"] else v["shapes"]
    files = [a.rsplit("#", 1)[0] for a in v["assets"]]
    first = record.states[0]
    created = [p for (p, a), t in first.items()
               if a == "prim" and p.startswith("/Behaviors/distractorScatter/") and t not in (None, "Scope")]
    if len(created) != v["count"]:
        fail(scene, f"expected {v['count']} distractors, found {len(created)}: {created}")
    for p in created:
        kind = first[(p, "prim")]
        if kind == "Mesh" and value_of(first, (p, "asset")) not in files:
            fail(scene, f"{p}: mesh {value_of(first, (p, 'asset'))!r} is not one of {files}")
        elif kind != "Mesh" and kind not in shapes:
            fail(scene, f"{p}: a {kind}, not one of {shapes}")
    low, high = anchor + np.array(v["range:minPosition"]), anchor + np.array(v["range:maxPosition"])
    previous = None
    for frame, state in enumerate(record.states):
        where = f"frame {frame}"
        positions = []
        for p in created:
            position = value_of(state, (p, "xformOp:translate"))
            scale = value_of(state, (p, "xformOp:scale"))
            orient = value_of(state, (p, "xformOp:orient"))
            if position is None or scale is None or orient is None:
                fail(scene, f"{where}: {p} lacks its translate, orient or scale")
                continue
            if not all(within(x, lo, hi) for x, lo, hi in zip(position, low, high)):
                fail(scene, f"{where}: {p} at {position}, outside the volume {low.tolist()} .. {high.tolist()}")
            factor = v["assetScale"] if state[(p, "prim")] == "Mesh" else 1.0
            s_low, s_high = (x * factor for x in v["scaleRange"])
            if not (same(scale[0], scale[1]) and same(scale[1], scale[2]) and within(scale[0], s_low, s_high)):
                fail(scene, f"{where}: {p} scale {scale}, not uniform within {s_low} .. {s_high}")
            if abs(np.linalg.norm(orient) - 1) > 1e-6:
                fail(scene, f"{where}: {p} orient {orient} is not a unit quaternion")
            positions.append(tuple(position))
        if previous is not None and any(a == b for a, b in zip(positions, previous)):
            fail(scene, f"{where}: a distractor stayed where it was")
        previous = positions
    # The labels, from the rendered dataset: every distractor box says "distractor".
    label = v["semanticClass"]
    boxes = 0
    for paths_file in sorted(glob.glob(os.path.join(dataset, "bounding_box_2d_tight_prim_paths_*.json"))):
        number = paths_file[-9:-5]
        paths = json.load(open(paths_file))
        labels = json.load(open(os.path.join(dataset, f"bounding_box_2d_tight_labels_{number}.json")))
        table = np.load(os.path.join(dataset, f"bounding_box_2d_tight_{number}.npy"))
        ours = [(path, row) for path, row in zip(paths, table) if path.startswith("/Behaviors/distractorScatter/")]
        if not ours:
            fail(scene, f"frame {number}: no distractor in view")
        for path, row in ours:
            if labels.get(str(int(row["semanticId"])), {}).get("class") != label:
                fail(scene, f"frame {number}: {path} is labelled {labels.get(str(int(row['semanticId'])))}")
        boxes += len(ours)
    return f"{len(created)} distractors inside the volume in {len(record.states)} frames, {boxes} labelled boxes"


def check_dome_randomizer(scene, prims, record, dataset):
    owners = [p for p in prims.values() if "domeRandomizer" in p.behaviors]
    if len(owners) != 1:
        fail(scene, f"expected one prim with domeRandomizer, found {len(owners)}")
        return "no owner"
    owner, v = owners[0], owners[0].behaviors["domeRandomizer"]
    check_only_under(scene, record, [owner.path])
    maps = set(v["textures:assets"])
    low, high = v["intensityRange"]
    seen, turns = set(), set()
    for frame, state in enumerate(record.states):
        where = f"frame {frame}"
        texture = value_of(state, (owner.path, "inputs:texture:file"))
        if texture not in maps:
            fail(scene, f"{where}: texture {texture!r} is not one of {sorted(maps)}")
        seen.add(texture)
        intensity = value_of(state, (owner.path, "inputs:intensity"))
        if intensity is None or not within(intensity, low, high):
            fail(scene, f"{where}: intensity {intensity} outside {low} .. {high}")
        orient = value_of(state, (owner.path, "xformOp:orient"))
        # A turn about the stage's up axis (Z): a quaternion (w, 0, 0, z).
        if orient is None or abs(orient[1]) > 1e-6 or abs(orient[2]) > 1e-6:
            fail(scene, f"{where}: orient {orient} is not a turn about Z")
        else:
            turns.add(round(math.degrees(2 * math.atan2(orient[3], orient[0])) % 360, 3))
    if len(seen) < 2 or len(turns) < len(record.states):
        fail(scene, f"the sky hardly changed: maps {sorted(seen)}, turns {sorted(turns)}")
    pictures = [open(f, "rb").read() for f in sorted(glob.glob(os.path.join(dataset, "rgb_*.png")))]
    if len(set(pictures)) != len(pictures):
        fail(scene, "two frames rendered the same picture")
    return f"{len(seen)} maps, {len(turns)} turns, intensities within range in {len(record.states)} frames"


SCENES = {
    "camera_orbit.yaml": check_camera_orbit,
    "dome_randomizer.yaml": check_dome_randomizer,
    "material_randomizer.yaml": check_material_randomizer,
    "distractor_scatter.yaml": check_distractor_scatter,
}


def check_scene(binary, scene_path, check, tmp):
    scene = os.path.basename(scene_path)
    stem = os.path.join(tmp, os.path.splitext(scene)[0])
    one, two, other, again = stem + "_threads1", stem + "_threads2", stem + "_seed2", stem + "_saved"
    saved = stem + "_saved.yaml"
    common = ["--frames", str(FRAMES), "--quiet"]
    run(binary, "run", scene_path, *common, "--seed", "1", "--threads", "1", "--out", one)
    run(binary, "run", scene_path, *common, "--seed", "1", "--threads", "2", "--out", two, "--save-stage", saved)
    files = compare_datasets(scene, one, two, "--threads 1 and --threads 2")
    run(binary, "run", saved, *common, "--seed", "1", "--out", again)
    compare_datasets(scene, one, again, "the --save-stage scene")
    run(binary, "run", scene_path, *common, "--seed", "2", "--out", other)
    rgb = sorted(os.path.basename(p) for p in glob.glob(os.path.join(one, "rgb_*.png")))
    if len(rgb) != FRAMES:
        fail(scene, f"expected {FRAMES} rgb images, found {len(rgb)}")
    same_images = [n for n in rgb if filecmp.cmp(os.path.join(one, n), os.path.join(other, n), shallow=False)]
    if same_images:
        fail(scene, f"seeds 1 and 2 gave the same {same_images}")

    record_path = stem + ".jsonl"
    run(binary, "run", scene_path, "--no-render", "--record", record_path, "--frames", str(RECORD_FRAMES),
        "--seed", "1", "--quiet")
    prims = inspect_stage(binary, scene_path)
    record = Record(scene, record_path, original_state(prims))
    check_restored(scene, record)
    what = check(scene, prims, record, one)
    return f"{scene}: {files} files identical across threads and --save-stage; other seed differs; {what}; " \
           f"stop restores {len(record.touched)} keys"


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    binary, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    with tempfile.TemporaryDirectory() as tmp:
        for scene, check in SCENES.items():
            before = len(failures)
            try:
                summary = check_scene(binary, os.path.join(source, "scenes", "examples", scene), check, tmp)
            except (RuntimeError, OSError, KeyError, ValueError, subprocess.TimeoutExpired) as e:
                fail(scene, f"{type(e).__name__}: {e}")
                summary = None
            print(summary if summary and len(failures) == before else f"{scene}: FAILED")
    if failures:
        print("\n".join(failures[:60]))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
