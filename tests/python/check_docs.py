#!/usr/bin/python3
"""The docs' examples, pasted in reading order into a fresh copy of the
checkout, as a new user would: README.md, then the pages in the order of
README's "Where to read on" table. Every ```sh, ```console and ```python
block runs (the conventions are in doc_blocks.py and docs/testing.md); a
block whose first line is `# needs: REASON` is listed as not run.

usage: check_docs.py SDGBEHAVE_BINARY SOURCE_DIR BUILD_DIR [PAGE ...]

The copy holds the files git lists (tracked, and untracked ones it does not
ignore), with build/release a link to BUILD_DIR; sdgbehave's folder is first
on PATH and the copy's python/ on PYTHONPATH (as docs/datasets-python.md says
for a checkout). Each page runs in one bash, so a variable or `cd` of one
block reaches the next, as in a terminal. The pages run in two lanes at once,
each in reading order in a copy of its own (SECOND_LANE below): pages of one
lane share their copy, so two of them writing the same folder collide as they
would for a reader. With PAGE arguments only those pages run. Exits 1 naming
each failing block's page:line, 0 when every block ran as shown."""
import glob
import importlib.util
import json
import os
import re
import select
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import doc_blocks
import doc_snippets

PYTHON = "/usr/bin/python3"
BLOCK_TIMEOUT = 120
# Pages that run beside the others, each lane in a copy of its own (two
# cores, and most blocks keep one busy): these share no file with the pages
# of the first lane and use none those make. Pages in one lane see each
# other's files, in reading order; a page not listed runs in the first lane.
SECOND_LANE = {"docs/behaviors.md", "docs/scripting.md", "docs/studio.md", "docs/writers.md",
               "docs/datasets-python.md"}
# The first command of a block that fails is recorded and ends the block, as
# a reader would stop there (`return` leaves the sourced block).
ERR_TRAP = ("trap '__rc=$?; [ -z \"$__sdg_fail\" ] && __sdg_fail=\"$LINENO: exit $__rc: $BASH_COMMAND\"; "
            "return $__rc 2>/dev/null' ERR")


def copy_checkout(source, build, work):
    """The files of the checkout into `work`, build/release linked to the real build."""
    try:
        listed = subprocess.run(["git", "-C", source, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                                capture_output=True, text=True)
    except FileNotFoundError:
        listed = None
    if listed is None or listed.returncode != 0:
        # Not a git checkout (an unpacked archive): its files, less what builds and runs make.
        shutil.copytree(source, work, symlinks=True, ignore=shutil.ignore_patterns(".git", "build", "out", "bench"))
        names = []
    else:
        names = sorted(set(filter(None, listed.stdout.split("\0"))))
    for name in names:
        src = os.path.join(source, name)
        if not os.path.lexists(src) or os.path.isdir(src) and not os.path.islink(src):
            continue  # deleted in the work tree, or a submodule
        dst = os.path.join(work, name)
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        if os.path.islink(src):
            os.symlink(os.readlink(src), dst)
        else:
            shutil.copy2(src, dst)
    os.makedirs(os.path.join(work, "build"), exist_ok=True)
    os.symlink(os.path.abspath(build), os.path.join(work, "build", "release"))


class PageShell:
    """One bash for a page's shell blocks: each block is sourced, so state
    carries over; an ERR trap records the first command that failed."""

    def __init__(self, work, scratch, env):
        self.scratch, self.count = scratch, 0
        self.bash = subprocess.Popen(["/bin/bash", "--noprofile", "--norc"], cwd=work, env=env, text=True,
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     start_new_session=True)
        self.send(f"set -o pipefail\n{ERR_TRAP}\n")

    def send(self, text):
        self.bash.stdin.write(text)
        self.bash.stdin.flush()

    def run(self, script, merge_output=False):
        """(exit code of the last command, first failure or '', stdout, stderr) of sourcing `script`."""
        self.count += 1
        base = os.path.join(self.scratch, f"step{self.count}")
        with open(base + ".sh", "w") as f:
            f.write(script)
        errors = f"{base}.out" if merge_output else f"{base}.err"
        to_errors = "2>&1" if merge_output else f"2> {errors}"
        marker = f"__SDG_DONE_{self.count}__"
        self.send(f"__sdg_fail=; source {base}.sh > {base}.out {to_errors} < /dev/null; __last=$?; trap - ERR; "
                  f"printf '%s\\n%s\\n' \"$__last\" \"$__sdg_fail\" > {base}.rc; {ERR_TRAP}; echo {marker}\n")
        deadline, seen = time.time() + BLOCK_TIMEOUT, ""
        while marker not in seen:
            left = deadline - time.time()
            if left <= 0 or self.bash.poll() is not None:
                what = "timed out" if left <= 0 else f"bash exited {self.bash.returncode}"
                return None, f"{what} (after {BLOCK_TIMEOUT} s at most)", read(base + ".out"), read(errors)
            ready, _, _ = select.select([self.bash.stdout], [], [], min(left, 1.0))
            if ready:
                seen += os.read(self.bash.stdout.fileno(), 65536).decode(errors="replace")
        last, failure = (read(base + ".rc").split("\n") + ["", ""])[:2]
        return int(last), failure, read(base + ".out"), "" if merge_output else read(errors)

    def close(self):
        """Ends the bash and whatever it left running (a server started with `&`)."""
        try:
            os.killpg(self.bash.pid, 9)
        except ProcessLookupError:
            pass
        self.bash.wait()


def read(path):
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            return f.read()
    except FileNotFoundError:
        return ""


def missing_module(code):
    """The first top-level module a Python block imports that is not installed, or None."""
    for name in re.findall(r"^\s*(?:import|from)\s+([A-Za-z_][A-Za-z0-9_]*)", code, re.M):
        if name != "sdgbehave" and importlib.util.find_spec(name) is None:
            return name
    return None


def json_shape_problems(block, output):
    """Each JSON answer the command printed has the keys the page shows."""
    shown = doc_blocks.json_answers(block.text)
    printed = [line for line in output.splitlines() if line.startswith("{")]
    if len(printed) < len(shown):
        return [f"the page shows {len(shown)} JSON answers, the commands printed {len(printed)}"]
    problems = []
    for number, (page_text, answer) in enumerate(zip(shown, printed[-len(shown):]), 1):
        try:
            page_value = json.loads(page_text)
        except ValueError as e:
            problems.append(f"answer {number} as shown is not JSON even without its '...': {e}")
            continue
        try:
            value = json.loads(answer)
        except ValueError:
            problems.append(f"answer {number} printed is not JSON: {answer[:200]}")
            continue
        if set(value) != set(page_value):
            problems.append(f"answer {number} has the keys {sorted(value)}, the page shows {sorted(page_value)}")
    return problems


class Runner:
    def __init__(self, binary, work, scratch, env):
        self.binary, self.work, self.scratch, self.env = binary, work, scratch, env
        self.failures, self.ran, self.not_run, self.slowest, self.log = [], 0, [], [], []

    def fail(self, block, message, stdout="", stderr=""):
        text = f"FAIL  {block.where()}: {message}"
        if stdout.strip():
            text += "\n--- stdout\n" + stdout.rstrip()[-3000:]
        if stderr.strip():
            text += "\n--- stderr\n" + stderr.rstrip()[-3000:]
        self.log.append(text)
        self.failures.append(f"{block.where()}: {message.splitlines()[0]}")

    def ok(self, block, what, started):
        took = time.time() - started
        self.slowest.append((took, block.where()))
        self.log.append(f"ok    {block.where()}: {what[:90]} ({took:.1f} s)")

    def page(self, name, text, pool):
        blocks = doc_blocks.fenced_blocks(name, text)
        context = doc_snippets.find_context(blocks)
        # Behavior snippets and scripts depend on nothing before them: run
        # them now, beside the page's shell, and report them in page order.
        in_behavior = None
        if context:
            chosen = [b for b in blocks if b.language == "python" and not b.needs and not b.save_as]
            snippets = [b for b in chosen if doc_snippets.is_snippet(b)]
            scripts = [b for b in chosen if not doc_snippets.is_snippet(b) and doc_snippets.script_name(b)]
            folder = tempfile.mkdtemp(prefix=f"behavior_{name.replace('/', '_')}_", dir=self.scratch)
            in_behavior = pool.submit(doc_snippets.run_all, self.binary, snippets, scripts, context, folder,
                                      self.env)
        shell = PageShell(self.work, self.scratch, self.env)
        last_output = None
        try:
            for block in blocks:
                if block.save_as:
                    target = os.path.join(self.work, block.save_as)
                    os.makedirs(os.path.dirname(target), exist_ok=True)
                    with open(target, "w") as f:
                        f.write(block.text)
                    self.log.append(f"saved {block.where()}: {block.save_as}")
                    continue
                if block.language == "json" and block.adjacent and last_output is not None:
                    for problem in json_shape_problems(block, last_output):
                        self.fail(block, problem)
                    last_output = None
                    continue
                last_output = None
                if block.language not in doc_blocks.RUNS:
                    continue
                if block.needs:
                    self.not_run.append(f"{block.where()}: needs {block.needs}")
                    self.log.append(f"not run {block.where()}: needs {block.needs}")
                    continue
                self.ran += 1
                if block.language in doc_blocks.RUN_SHELL:
                    last_output = self.shell_block(shell, block)
                elif block.language == "console":
                    self.console_block(shell, block)
                else:
                    self.python_block(block, in_behavior)
        finally:
            shell.close()

    def shell_block(self, shell, block):
        started = time.time()
        code, failure, out, err = shell.run(block.text)
        if code is None or failure:
            line, _, what = failure.partition(": ")
            where = f"line {block.line - 1 + int(line)}: " if line.isdigit() else ""
            self.fail(block, f"{where}{what or failure}", out, err)
            return None
        self.ok(block, block.body[0].strip(), started)
        return out

    def console_block(self, shell, block):
        steps = doc_blocks.console_steps(block.body)
        if not steps:
            self.fail(block, "a console block with no `$ ` command")
        for step in steps:
            started = time.time()
            code, _, output, _ = shell.run(step.command + "\n", merge_output=True)
            line = block.line + step.offset
            if code != step.exit_code:
                self.fail(block, f"line {line}: `{step.command}` exited {code}, the page shows {step.exit_code}"
                          + ("" if step.exit_code else " (add `$ echo $?` and the code if it is meant to fail)"),
                          output)
                continue
            printed = [printed_line.rstrip() for printed_line in output.splitlines()]
            missing = [s for s in step.shown if s.strip() != "..." and s not in printed]
            if missing:
                self.fail(block, f"line {line}: `{step.command}` did not print, as the page shows:\n  "
                          + "\n  ".join(missing), output)
                continue
            self.ok(block, f"$ {step.command}", started)

    def python_block(self, block, in_behavior):
        started = time.time()
        if in_behavior and block.line in in_behavior.result():
            problems, compared = in_behavior.result()[block.line]
            for problem in problems:
                self.fail(block, problem)
            if not problems:
                self.ok(block, f"in a behavior, {compared} values as shown", started)
            return
        missing = missing_module(block.text)
        if missing:
            self.not_run.append(f"{block.where()}: imports {missing}, which is not installed")
            self.log.append(f"not run {block.where()}: imports {missing}, which is not installed")
            return
        path = os.path.join(self.scratch, f"block_{block.line}.py")
        with open(path, "w") as f:
            f.write(block.text)
        try:
            result = subprocess.run([PYTHON, path], cwd=self.work, env=self.env, capture_output=True, text=True,
                                    timeout=BLOCK_TIMEOUT)
        except subprocess.TimeoutExpired:
            self.fail(block, f"timed out after {BLOCK_TIMEOUT} s")
            return
        if result.returncode != 0:
            self.fail(block, f"{PYTHON} exited {result.returncode}", result.stdout, result.stderr)
            return
        printed = [line.rstrip() for line in result.stdout.splitlines()]
        shown = re.findall(r"#\s*prints:\s*(.+?)\s*$", block.text, re.M)
        missing = [line for line in shown if line not in printed]
        if missing:
            self.fail(block, "did not print, as the page shows:\n  " + "\n  ".join(missing), result.stdout)
            return
        self.ok(block, f"python, {len(shown)} printed lines as shown", started)


def main():
    if len(sys.argv) < 4:
        print(__doc__)
        return 2
    binary, source, build = (os.path.abspath(a) for a in sys.argv[1:4])
    only = set(sys.argv[4:])
    with open(os.path.join(source, "README.md"), encoding="utf-8") as f:
        readme = f.read()
    pages = doc_blocks.reading_order(readme, sorted(os.path.relpath(p, source)
                                                    for p in glob.glob(os.path.join(source, "docs", "*.md"))))
    unknown = only - set(pages)
    if unknown:
        print("not a docs page: " + ", ".join(sorted(unknown)))
        return 2

    chosen = [page for page in pages if not only or page in only]
    lanes = [[page for page in chosen if page not in SECOND_LANE], [page for page in chosen if page in SECOND_LANE]]
    print_lock = threading.Lock()
    with tempfile.TemporaryDirectory(prefix="sdg_docs_", dir=memory_folder()) as tmp:
        started = time.time()
        with ThreadPoolExecutor(max_workers=2) as pool, ThreadPoolExecutor(max_workers=2) as lane_pool:
            runners = list(lane_pool.map(lambda lane: run_lane(lane[0], lane[1], binary, source, build, tmp, pool,
                                                                print_lock), enumerate(lanes)))
        ran = sum(r.ran for r in runners)
        not_run = [item for r in runners for item in r.not_run]
        failures = [item for r in runners for item in r.failures]
        slowest = sorted(item for r in runners for item in r.slowest)[::-1][:8]
        print(f"\n{ran} blocks run in {time.time() - started:.0f} s, {len(not_run)} not run, {len(failures)} failures")
        print("slowest: " + ", ".join(f"{where} {took:.1f} s" for took, where in slowest))
        for item in not_run:
            print(f"  not run: {item}")
        for failure in failures:
            print(f"  FAIL {failure}")
        return 1 if failures else 0


def memory_folder():
    """/dev/shm when it is a writable folder with 1 GiB free that allows
    executables (an example builds and loads a plugin), else None (the default
    temporary folder): removing the copies' thousands of files takes seconds
    on a disk mounted with `discard`, and none in memory."""
    try:
        fs = os.statvfs("/dev/shm")
    except OSError:
        return None
    usable = os.access("/dev/shm", os.W_OK) and not fs.f_flag & getattr(os, "ST_NOEXEC", 8)
    return "/dev/shm" if usable and fs.f_bavail * fs.f_frsize > 1 << 30 else None


def run_lane(number, pages, binary, source, build, tmp, pool, print_lock):
    """The pages of one lane, in reading order, in a copy of the checkout of their own."""
    work, scratch = os.path.join(tmp, f"checkout{number + 1}"), os.path.join(tmp, f"scratch{number + 1}")
    os.makedirs(scratch)
    copy_checkout(source, build, work)
    env = dict(os.environ)
    env["PATH"] = os.path.dirname(binary) + os.pathsep + env.get("PATH", "")
    env["PYTHONPATH"] = os.path.join(work, "python")
    env["TMPDIR"] = scratch  # what an example leaves in a temporary folder goes with the copy
    env.pop("SDGBEHAVE_ISAAC_ASSETS", None)  # the docs' commands must work without one
    runner = Runner(binary, work, scratch, env)
    lane_started = time.time()
    for page in pages:
        page_started = time.time()
        with open(os.path.join(work, page), encoding="utf-8") as f:
            runner.page(page, f.read(), pool)
        with print_lock:
            print(f"== {page} (lane {number + 1}: {time.time() - page_started:.1f} s, the lane's "
                  f"{time.time() - lane_started:.0f} s)\n" + "\n".join(runner.log), flush=True)
        runner.log = []
    return runner


if __name__ == "__main__":
    sys.exit(main())
