#!/usr/bin/python3
"""A docs page's examples run as a reader pastes them: every ```sh (bash,
shell) command and every ```python block, in page order, in one scratch
folder holding a copy of scenes/, with sdgbehave first on PATH and the
source tree's python/ on PYTHONPATH (so `sdgbehave.data` imports as from a
checkout). Blocks tagged otherwise (```console, ```text) are not run.

Exits 77 (skipped) when a Python block imports a module this machine lacks
(torch: Debian python3-torch).

usage: check_doc_examples.py SDGBEHAVE_BINARY SOURCE_DIR PAGE"""
import importlib.util
import os
import re
import shutil
import subprocess
import sys
import tempfile

from check_readme import RUN_LANGUAGES, commands, fenced_blocks

PYTHON = "/usr/bin/python3"


def missing_module(code):
    """The first top-level module a block imports that is not installed, or None."""
    for name in re.findall(r"^\s*(?:import|from)\s+([A-Za-z_][A-Za-z0-9_]*)", code, re.M):
        if name != "sdgbehave" and importlib.util.find_spec(name) is None:
            return name
    return None


def main():
    binary, source, page = (os.path.abspath(a) for a in sys.argv[1:4])
    with open(page, encoding="utf-8") as f:
        blocks = fenced_blocks(f.read())
    runnable = [b for b in blocks if b[1] in RUN_LANGUAGES or b[1] == "python"]
    if not runnable:
        print(f"{page}: no ```sh or ```python blocks")
        return 1
    for _, language, body in runnable:
        if language == "python" and missing_module("\n".join(body)):
            print(f"skipped: {page} imports {missing_module(chr(10).join(body))}, which is not installed")
            return 77

    env = dict(os.environ)
    env["PATH"] = os.path.dirname(binary) + os.pathsep + env.get("PATH", "")
    env["PYTHONPATH"] = os.path.join(source, "python")
    name = os.path.relpath(page, source)
    with tempfile.TemporaryDirectory(prefix="sdg_doc_") as work:
        shutil.copytree(os.path.join(source, "scenes"), os.path.join(work, "scenes"), symlinks=True)
        for start, language, body in runnable:
            steps = [(start, "\n".join(body))] if language == "python" else commands([(start, body)])
            for line, text in steps:
                argv = [PYTHON, "-c", text] if language == "python" else ["/bin/bash", "-o", "pipefail", "-c", text]
                result = subprocess.run(argv, cwd=work, env=env, capture_output=True, text=True, timeout=120)
                shown = text.splitlines()[0] + (" ..." if "\n" in text else "")
                if result.returncode != 0:
                    print(f"FAIL  {name}:{line}: {shown}\n--- stdout\n{result.stdout}--- stderr\n{result.stderr}")
                    return 1
                print(f"ok    {name}:{line}: {shown}\n{result.stdout}", end="")
    print(f"ok: every example of {name} runs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
