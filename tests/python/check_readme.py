#!/usr/bin/python3
"""Every command in README.md's ```sh (```bash, ```shell) blocks runs and
exits 0, as a new user would type it, so the quick start cannot rot.

usage: check_readme.py SDGBEHAVE_BINARY SOURCE_DIR

Lines ending in a backslash are joined with the next; blank lines and
comments are skipped, and so are `make ...` lines (CI runs those itself) and
`export PATH=...` lines: the binary's folder is put first on PATH instead.
Each command runs in bash in a scratch folder holding copies of scenes/,
tests/data/ and schemas/, so what the commands write never lands in the
source tree. Commands that are meant to fail belong in ```console or ```text
blocks, which are not run. Standard library only."""
import os
import re
import shutil
import subprocess
import sys
import tempfile

RUN_LANGUAGES = {"sh", "bash", "shell"}
COPIED = ("scenes", "tests/data", "schemas")
FENCE = re.compile(r"^ {0,3}(`{3,}|~{3,})\s*([^\s`]*)")


def shell_blocks(text):
    """(first line number, lines) of every fenced block tagged sh/bash/shell."""
    return [(start, body) for start, language, body in fenced_blocks(text) if language in RUN_LANGUAGES]


def fenced_blocks(text):
    """(first line number, language, lines) of every fenced block, in order."""
    blocks, lines = [], text.splitlines()
    i = 0
    while i < len(lines):
        opening = FENCE.match(lines[i])
        if not opening:
            i += 1
            continue
        fence, language = opening.group(1), opening.group(2).lower()
        start, body = i + 2, []
        i += 1
        while i < len(lines):
            closing = re.match(r"^ {0,3}(`{3,}|~{3,})\s*$", lines[i])
            if closing and closing.group(1)[0] == fence[0] and len(closing.group(1)) >= len(fence):
                break
            body.append(lines[i])
            i += 1
        i += 1
        blocks.append((start, language, body))
    return blocks


def commands(blocks):
    """(README line number, command) for every line to run."""
    out = []
    for start, body in blocks:
        pending, pending_line = "", None
        for offset, raw in enumerate(body):
            line = raw.strip() if pending else raw.rstrip()
            if pending_line is None:
                pending_line = start + offset
            if line.endswith("\\"):
                pending += line[:-1].strip() + " "
                continue
            command = (pending + line).strip()
            number = pending_line
            pending, pending_line = "", None
            if not command or command.startswith("#"):
                continue
            if command.startswith("make ") or command == "make":
                continue
            if re.match(r"^export\s+PATH=", command):
                continue
            out.append((number, command))
        if pending.strip():
            out.append((pending_line, pending.strip()))
    return out


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    binary, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    readme = os.path.join(source, "README.md")
    with open(readme, encoding="utf-8") as f:
        to_run = commands(shell_blocks(f.read()))
    if not to_run:
        print(f"{readme}: no commands found in ```sh, ```bash or ```shell blocks")
        return 1

    env = dict(os.environ)
    env["PATH"] = os.path.dirname(binary) + os.pathsep + env.get("PATH", "")
    env.pop("SDGBEHAVE_ISAAC_ASSETS", None)  # the README's commands must work without one
    passed, failed = 0, []
    with tempfile.TemporaryDirectory(prefix="sdg_readme_") as work:
        for part in COPIED:
            if os.path.isdir(os.path.join(source, part)):
                shutil.copytree(os.path.join(source, part), os.path.join(work, part), symlinks=True)
        for number, command in to_run:
            try:
                result = subprocess.run(["/bin/bash", "-o", "pipefail", "-c", command], cwd=work, env=env,
                                        capture_output=True, text=True, timeout=300)
                code, stderr = result.returncode, result.stderr
            except subprocess.TimeoutExpired as e:
                code = "timeout after 300 s"
                stderr = e.stderr.decode(errors="replace") if isinstance(e.stderr, bytes) else (e.stderr or "")
            if code == 0:
                passed += 1
                print(f"ok    README.md:{number}: {command}")
            else:
                failed.append((number, command, code, stderr))
                print(f"FAIL  README.md:{number}: {command}")

    for number, command, code, stderr in failed:
        print(f"\nREADME.md:{number}: `{command}` exited {code}")
        print("--- stderr\n" + (stderr.rstrip() or "(empty)"))
    print(f"\n{passed} passed, {len(failed)} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
