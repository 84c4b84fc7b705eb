#!/usr/bin/python3
"""`sdgbehave studio`'s JSON API, without a browser: the access token, the
Host and Origin checks and '..' paths are enforced; bad requests get 4xx
and never kill the server; an edit updates the tree, the record and the
preview; save writes the value into the YAML keeping comments and layout,
inserts new keys in the mapping's style, turns an edit of a referenced
asset's value into a local override and leaves the asset file alone; an
edit made on disk is picked up, and one that clashes with unsaved edits is
a conflict that save refuses.

usage: check_studio_api.py SDGBEHAVE SOURCE_DIR"""
import os
import shutil
import subprocess
import sys
import tempfile
import time

from checklib import check, finish
from studio_server import Studio


def main():
    binary, root = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "scene.yaml")
        shutil.copy(os.path.join(root, "scenes/examples/location_randomizer.yaml"), scene)
        original = open(scene).read()
        studio = Studio(binary, scene)
        try:
            # Safety: token, Host, Origin, '..'.
            status, _ = studio.request("/api/state", token=False)
            check(status == 403, f"no token: {status}")
            status, _ = studio.request("/api/state", headers={"Origin": "http://evil.example"})
            check(status == 403, f"foreign Origin: {status}")
            status, _ = studio.request("/api/state", headers={"Host": "evil.example:80"})
            check(status == 421, f"foreign Host: {status}")
            status, _ = studio.request("/api/../../etc/passwd")
            check(status in (400, 404), f"'..' path: {status}")
            status, page = studio.request("/")
            check(status == 200 and "sdgbehave studio" in page, "the page")
            # Bad requests: 4xx, the server lives on.
            for path, body in (("/api/edit", b"{not json"), ("/api/edit", {"prim": "/Nope", "keys": ["size"], "value": 1}),
                               ("/api/edit", {"prim": "/World/Box", "keys": ["size"], "value": -1}),
                               ("/api/edit", {"prim": "/World/Box", "keys": ["size"], "value": "big"}),
                               ("/api/edit", {"prim": "/World/Box"}), ("/api/seed", {"seed": "x"}),
                               ("/api/preview?pass=xray", None), ("/api/preview?frame=-1", None),
                               ("/api/record?frame=1e9", None), ("/api/nothing", None),
                               # Only values: no YAML smuggled in through names, no new references.
                               ("/api/edit", {"prim": "/World/Box", "keys": ["size: 1\nscripts: [evil.py]\nx"], "value": 1}),
                               ("/api/edit", {"prim": "/World/Box", "keys": ["reference"], "value": "other.yaml"}),
                               ("/api/edit", {"prim": "/World/Box", "keys": ["behaviors", "locationRandomizer"],
                                              "value": {"interval": 1}}),
                               ("/api/edit", {"prim": "/World/Box", "keys": ["attributes"],
                                              "value": {"a}\nscripts: [evil.py]\n#": 1}})):
                status, answer = studio.request(path, body)
                check(400 <= status < 500 and "error" in answer, f"{path} {body}: {status} {answer}")
            check(studio.alive(), "the server died of a bad request")
            status, diff = studio.request("/api/diff")
            check("+" not in diff.split("\n", 2)[-1], f"refused edits changed the text:\n{diff}")

            # An edit: tree, record and preview follow.
            _, before = studio.request("/api/preview?frame=1", raw=True)
            status, answer = studio.request("/api/edit", {"prim": "/World/Box",
                                                          "keys": ["behaviors", "locationRandomizer", "range:maxPosition"],
                                                          "value": [3, 3, 0]})
            check(status == 200 and not answer["preroll_stale"], f"edit: {status} {answer}")
            _, tree = studio.request("/api/tree")
            box = next(p for p in tree["prims"] if p["path"] == "/World/Box")
            var = next(v for v in box["behaviors"][0]["variables"] if v["name"] == "range:maxPosition")
            check(var["value"] == [3.0, 3.0, 0.0] and "scene.yaml" in var["origin"], f"tree after edit: {var}")
            _, after = studio.request("/api/preview?frame=1", raw=True)
            check(after[:8] == b"\x89PNG\r\n\x1a\n" and after != before, "the preview did not change")
            _, record = studio.request("/api/record?frame=1")
            check(any(c["prim"] == "/World/Box" for c in record["changes"]), f"record: {record}")
            # Frame 0 includes what behaviors do on play (interval 2 applies once there).
            _, record = studio.request("/api/record?frame=0")
            check(any(c["prim"] == "/World/Box" for c in record["changes"]), f"frame 0's record: {record}")
            # A label edit reaches the preview's stage without a new pre-roll.
            status, answer = studio.request("/api/edit", {"prim": "/World/Box", "keys": ["semantics", "class"],
                                                          "value": "crate"})
            check(status == 200 and {"prim": "/World/Box", "attribute": "semantics"} in answer["changed"],
                  f"label edit: {status} {answer}")
            # A variable the file does not set goes into its flow mapping.
            status, _ = studio.request("/api/edit", {"prim": "/World/Box", "keys": ["behaviors", "locationRandomizer", "seed"],
                                                     "value": 7})
            check(status == 200, f"new key: {status}")
            status, answer = studio.request("/api/save", {})
            check(status == 200, f"save: {status} {answer}")
            saved = open(scene).read()
            check("range:maxPosition: [3, 3, 0]" in saved and "seed: 7}" in saved, f"saved text:\n{saved}")
            kept = [l for l in original.splitlines() if "locationRandomizer: {interval: 2" not in l]
            check(all(l in saved.splitlines() for l in kept), "save changed lines it did not edit (comments, order)")
            check(subprocess.run([binary, "validate", scene], capture_output=True).returncode == 0, "saved file invalid")

            # Render frames of the scene as edited, in a child process.
            status, _ = studio.request("/api/render", {"frames": 2, "name": "../escape"})
            check(status == 400, f"render into '../escape': {status}")
            status, job = studio.request("/api/render", {"frames": 2, "name": "quick"})
            check(status == 200 and job["running"], f"render: {status} {job}")
            deadline = time.time() + 120
            while job["running"] and time.time() < deadline:
                time.sleep(0.2)
                _, job = studio.request("/api/render")
            check(job["exit_code"] == 0 and job["frames_written"] == 2 and job["contact_sheet"], f"render: {job}")
            status, sheet = studio.request("/api/render/contact_sheet", raw=True)
            check(status == 200 and sheet[:4] == b"\x89PNG", "the render's contact sheet")
            check(os.path.isfile(os.path.join(tmp, "studio_out", "quick", "rgb_0001.png")), "render output folder")
            check(not [f for f in os.listdir(tmp) if f.startswith(".")], "the render's scene file was left behind")

            # Edited on disk while nothing is unsaved: picked up.
            time.sleep(0.05)
            open(scene, "w").write(saved.replace("radius: 0.2", "radius: 0.3"))
            _, state = studio.request("/api/state")
            _, tree = studio.request("/api/tree")
            ball = next(p for p in tree["prims"] if p["path"] == "/World/Ball")
            check(any(a["name"] == "radius" and a["value"] == 0.3 for a in ball["attributes"]), "disk edit not picked up")
            # Unsaved edit here + edit on disk: a conflict, and save refuses.
            studio.request("/api/edit", {"prim": "/World/Ball", "keys": ["radius"], "value": 0.25})
            time.sleep(0.05)
            open(scene, "a").write("# edited in an editor\n")
            _, state = studio.request("/api/state")
            check(state["conflict"], f"no conflict reported: {state}")
            status, _ = studio.request("/api/save", {})
            check(status == 409, f"save during a conflict: {status}")
            check(open(scene).read().endswith("# edited in an editor\n"), "the file on disk was overwritten")
            status, _ = studio.request("/api/reload", {})
            _, state = studio.request("/api/state")
            check(status == 200 and not state["conflict"] and not state["unsaved"], f"reload: {status} {state}")
        finally:
            check(studio.stop() == 0, "the server did not stop cleanly on SIGTERM")

        # Attach and detach: written into the file, the pre-roll runs again.
        plain = os.path.join(tmp, "attach.yaml")
        shutil.copy(os.path.join(root, "scenes/examples/location_randomizer.yaml"), plain)
        studio = Studio(binary, plain)
        try:
            status, answer = studio.request("/api/behavior", {"prim": "/World/Box", "behavior": "rotationRandomizer",
                                                              "action": "attach"})
            check(status == 200, f"attach: {status} {answer}")
            status, answer = studio.request("/api/behavior", {"prim": "/World/Box", "behavior": "rotationRandomizer",
                                                              "action": "attach"})
            check(status == 400, f"attaching twice: {status}")
            status, answer = studio.request("/api/behavior", {"prim": "/World/Box", "behavior": "locationRandomizer",
                                                              "action": "detach"})
            check(status == 200, f"detach: {status} {answer}")
            status, _ = studio.request("/api/behavior", {"prim": "/World/Box", "behavior": "nope", "action": "attach"})
            check(status == 400, f"unknown behavior: {status}")
            _, tree = studio.request("/api/tree")
            box = next(p for p in tree["prims"] if p["path"] == "/World/Box")
            check([b["name"] for b in box["behaviors"]] == ["rotationRandomizer"], f"behaviors: {box['behaviors']}")
            studio.request("/api/save", {})
            text = open(plain).read()
            check("rotationRandomizer: {}" in text and "interval: 2, range:minPosition: [-1, -1, 0]" not in text,
                  f"attach/detach written:\n{text}")
        finally:
            studio.stop()

        # A behavior script saved in an editor is reloaded; a broken one keeps
        # the last good version running and says where it broke.
        script = os.path.join(tmp, "wobble.py")
        source = ("import sdgbehave\n\n\nclass Wobble(sdgbehave.IntervalBehavior):\n"
                  "    BEHAVIOR_NS = \"wobble\"\n    VARIABLES_TO_EXPOSE = [\n"
                  "        {\"attr_name\": \"amount\", \"attr_type\": \"double\", \"default_value\": 0.1, \"doc\": \"How far.\"},\n"
                  "    ]\n\n    def apply(self):\n"
                  "        self.prim.set_location((0.0, 0.0, self.rng.uniform(0, self.get_exposed_variable(\"amount\"))))\n")
        open(script, "w").write(source)
        scripted = os.path.join(tmp, "scripted.yaml")
        text = open(os.path.join(root, "scenes/examples/location_randomizer.yaml")).read()
        text = text.replace("version: 1", "version: 1\nscripts: [wobble.py]").replace(
            "locationRandomizer: {interval: 2,", "wobble: {}\n      locationRandomizer: {interval: 2,")
        open(scripted, "w").write(text)
        studio = Studio(binary, scripted)
        try:
            def wobble_variables():
                _, tree = studio.request("/api/tree")
                box = next(p for p in tree["prims"] if p["path"] == "/World/Box")
                return [v["name"] for b in box["behaviors"] if b["name"] == "wobble" for v in b["variables"]]
            check(wobble_variables() == ["amount", "interval"], f"script variables: {wobble_variables()}")
            time.sleep(0.05)
            open(script, "w").write(source.replace("    ]\n", "        {\"attr_name\": \"extra\", \"attr_type\": "
                                                   "\"double\", \"default_value\": 2.0, \"doc\": \"More.\"},\n    ]\n"))
            _, state = studio.request("/api/state")
            check("a behavior script changed" in state["note"], f"script reload note: {state}")
            check(wobble_variables() == ["amount", "extra", "interval"], f"after reload: {wobble_variables()}")
            time.sleep(0.05)
            open(script, "w").write(source.replace("def apply(self):", "def apply(self)"))
            _, state = studio.request("/api/state")
            check("no longer loads" in state["note"] and "wobble.py:10:20: error" in state["note"], f"broken script: {state}")
            status, png = studio.request("/api/preview?frame=1", raw=True)
            check(status == 200 and png[:4] == b"\x89PNG", "the last good version stopped working")
        finally:
            studio.stop()

        # A referenced asset's values: edits become local overrides.
        shutil.copytree(os.path.join(root, "tests/data/references/lib"), os.path.join(tmp, "lib"))
        refscene = os.path.join(tmp, "ref.yaml")
        open(refscene, "w").write("# A scene with a smart asset.\nversion: 1\nprims:\n  /World: {}\n"
                                  "  /World/Plain: {reference: lib/box.yaml}\n")
        asset_before = open(os.path.join(tmp, "lib/box.yaml")).read()
        studio = Studio(binary, refscene)
        try:
            for prim, keys, value in (("/World/Plain", ["behaviors", "bob", "amplitude"], 0.4),
                                      ("/World/Plain/Marker", ["radius"], 0.09)):
                status, answer = studio.request("/api/edit", {"prim": prim, "keys": keys, "value": value})
                check(status == 200, f"override {prim}: {status} {answer}")
            # Detaching what the asset attaches switches it off locally.
            status, answer = studio.request("/api/behavior", {"prim": "/World/Plain/Marker",
                                                              "behavior": "locationRandomizer", "action": "detach"})
            check(status == 200, f"detach an asset's behavior: {status} {answer}")
            status, _ = studio.request("/api/save", {})
            text = open(refscene).read()
            check("/World/Plain: {reference: lib/box.yaml, behaviors: {bob: {amplitude: 0.4}}}" in text
                  and "/World/Plain/Marker: {radius: 0.09, behaviors: {locationRandomizer: {enabled: false}}}" in text,
                  f"overrides written:\n{text}")
            check(open(os.path.join(tmp, "lib/box.yaml")).read() == asset_before, "the asset file was written")
            # Editing the asset itself, when asked: the asset file changes, not the scene.
            status, answer = studio.request("/api/edit", {"prim": "/World/Plain", "keys": ["size"], "value": 0.6,
                                                          "in": "asset"})
            check(status == 200 and answer.get("asset", "").endswith("lib/box.yaml"), f"edit in the asset: {answer}")
            status, _ = studio.request("/api/edit", {"prim": "/World", "keys": ["visibility"], "value": "invisible",
                                                     "in": "asset"})
            check(status == 400, f"'in the asset' for a prim of the scene: {status}")
            status, diff = studio.request("/api/diff")
            check("lib/box.yaml" in diff and "+    size: 0.6" in diff, f"asset diff: {diff}")
            scene_before = open(refscene).read()
            studio.request("/api/save", {})
            check("size: 0.6" in open(os.path.join(tmp, "lib/box.yaml")).read(), "the asset edit was not saved")
            check(open(refscene).read() == scene_before, "an edit in the asset changed the scene file")
            status, files = studio.request("/api/files?kind=image")
            check(status == 200 and "lib/tex/red.png" in files["files"], f"files: {files}")
            status, _ = studio.request("/api/files?kind=../../etc")
            check(status == 400, f"files of a bad kind: {status}")
            check(subprocess.run([binary, "validate", refscene], capture_output=True).returncode == 0, "override invalid")
        finally:
            studio.stop()
    return finish("token, Host, Origin, '..'; 4xx without dying; edit -> tree, record, preview; save keeps the file; "
                  "disk edits and conflicts; asset overrides")


if __name__ == "__main__":
    sys.exit(main())
