#!/usr/bin/python3
"""`sdgbehave exec` on Isaac Sim 6.0's version of the tutorial's SDG program (per-behavior seeds,
isaacsim.core.experimental.utils.semantics.add_labels, timeline.pause/commit, depth), as Isaac's own
extension carries it: the body of test_behavior_sdg_pipeline_warehouse in
isaacsim/replicator/behavior/tests/test_behaviors_sdg_scenario.py, read in place from a copy of Isaac's
extension (../shared/isaac-behaviors: skipped with 77 when absent) and written, with the call the
tutorial's page makes (6 captures, seeded), into a temporary program; nothing of Isaac's is kept. The
program writes 6 rgb and 6 depth frames into ./_out_behaviors_sdg, the drill labelled, frames differing,
byte-identical across two runs.

usage: check_exec_isaac6.py SDGBEHAVE ISAAC_EXTENSION_DIR"""
import ast
import os
import subprocess
import sys
import tempfile
import textwrap

import numpy as np
from PIL import Image

from checklib import check, dataset_hashes, finish

binary, extension = (os.path.abspath(a) for a in sys.argv[1:3])
source_file = os.path.join(extension, "isaacsim", "replicator", "behavior", "tests", "test_behaviors_sdg_scenario.py")
if not os.path.isfile(source_file):
    print(f"skipped: Isaac's SDG scenario test is not at {source_file}")
    sys.exit(77)
source = open(source_file).read()
function = next(n for n in ast.walk(ast.parse(source))
                if isinstance(n, ast.AsyncFunctionDef) and n.name == "test_behavior_sdg_pipeline_warehouse")
lines = source.splitlines()
body = []
for statement in function.body:
    if isinstance(statement, ast.Assign) and any(getattr(t, "id", "") == "test_num_captures" for t in statement.targets):
        break  # from here on the test checks its own golden images
    body.append("\n".join(lines[statement.lineno - 1:statement.end_lineno]))
program = "from __future__ import annotations\n\nimport asyncio\nfrom typing import Any\n" + textwrap.dedent("\n".join(body)) + \
    "\n\nasyncio.ensure_future(run_example_async(num_captures=6, seed=63))\n"
tmp = tempfile.mkdtemp()
path = os.path.join(tmp, "behaviors_sdg_isaac6.py")
with open(path, "w") as f:
    f.write(program)

hashes = []
for name in ("one", "two"):
    cwd = os.path.join(tmp, name)
    os.makedirs(cwd)
    r = subprocess.run([binary, "exec", path], cwd=cwd, capture_output=True, text=True)
    check(r.returncode == 0, f"the 6.0 program exits 0 ({name}): {r.stderr[-3000:]}")
    out = os.path.join(cwd, "_out_behaviors_sdg")
    files = sorted(os.listdir(out)) if os.path.isdir(out) else []
    rgb = [f for f in files if f.startswith("rgb_")]
    depth = [f for f in files if f.startswith("distance_to_image_plane_") and f.endswith(".npy")]
    check(len(rgb) == 6 and len(depth) == 6, f"6 rgb and 6 depth frames in ./_out_behaviors_sdg: {files}")
    hashes.append(dataset_hashes(out))
    if name == "one" and len(rgb) == 6:
        images = [np.asarray(Image.open(os.path.join(out, f)), dtype=float) for f in rgb]
        changes = [np.abs(images[i + 1] - images[i]).mean() for i in range(5)]
        check(sum(c > 0.05 for c in changes) >= 3, f"frames differ as the behaviors randomize: {changes}")
check(hashes[0] == hashes[1], "two runs of the 6.0 program write byte-identical files")
sys.exit(finish())
