#!/usr/bin/python3
"""docs/scripting.md's API reference against the module scripts get: every
public member of sdgbehave's Prim, Stage and Rng, as the embedded
interpreter of a real run lists them, has its heading (`#### name`, or
names joined by ", ") under the class's `### Class` section, and every
heading there names a member that exists.

usage: check_script_api_docs.py SDGBEHAVE DOCS_SCRIPTING_MD"""
import json
import os
import re
import subprocess
import sys
import tempfile

from checklib import check, finish

PROBE = '''import json, os
from sdgbehave import Behavior, Prim, Rng, Stage


class Probe(Behavior):
    BEHAVIOR_NS = "apiProbe"
    VARIABLES_TO_EXPOSE = []

    def on_init(self):
        members = {c.__name__: sorted(n for n in dir(c) if not n.startswith("_")) for c in (Prim, Stage, Rng)}
        with open(os.environ["SDG_API_PROBE_OUT"], "w") as out:
            json.dump(members, out)
'''

SCENE = '''version: 1
scripts: [probe.py]
writer: {type: BasicWriter, rgb: true}
render: {resolution: [16, 16]}
prims:
  /World: {type: Xform, behaviors: {apiProbe: {}}}
  /World/Cam: {type: Camera, translate: [0, -5, 1], rotateX: 90}
'''


def documented(markdown, cls):
    """The names in `#### ` headings between `### cls` and the next `### `."""
    section = re.search(rf"^### {cls}\n(.*?)(?=^### |\Z)", markdown, re.S | re.M)
    if not section:
        return set()
    names = set()
    for heading in re.findall(r"^#### (.+)$", section.group(1), re.M):
        names.update(n.strip() for n in heading.split(",") if re.fullmatch(r"[a-z_]+", n.strip()))
    return names


def main():
    binary, docs = sys.argv[1:3]
    markdown = open(docs, encoding="utf-8").read()
    with tempfile.TemporaryDirectory() as tmp:
        with open(f"{tmp}/probe.py", "w") as f:
            f.write(PROBE)
        with open(f"{tmp}/scene.yaml", "w") as f:
            f.write(SCENE)
        env = dict(os.environ, SDG_API_PROBE_OUT=f"{tmp}/members.json")
        run = subprocess.run([binary, "run", f"{tmp}/scene.yaml", "--frames", "1", "--out", f"{tmp}/out"],
                             capture_output=True, text=True, env=env)
        check(run.returncode == 0, f"the probe run failed ({run.returncode}): {run.stderr[-500:]}")
        if run.returncode != 0:
            return finish()
        members = json.load(open(f"{tmp}/members.json"))
    for cls, names in members.items():
        docs_names = documented(markdown, cls)
        check(docs_names, f"docs/scripting.md has no '### {cls}' section")
        for name in names:
            check(name in docs_names, f"{cls}.{name} is not in docs/scripting.md's '### {cls}' reference")
        for name in sorted(docs_names - set(names)):
            check(False, f"docs/scripting.md documents {cls}.{name}, which the module does not have")
    return finish(f"ok: {sum(len(v) for v in members.values())} members of Prim, Stage and Rng documented")


if __name__ == "__main__":
    sys.exit(main())
