#!/usr/bin/python3
"""Runs sdgbehave on every USD entry layer under some folders, as a user would, and tables the result.

  /usr/bin/python3 tools/usd_corpus.py --bin build/release/app/sdgbehave \\
      ../shared/usd-samples ../shared/usd-corpus --doc docs/usd.md --json corpus.json

For each entry layer (tools/usd_entry_layers.py says which files are entries)
it runs, from the working directory (--cwd, default the current one) with the
file's path relative to it: `validate`, `inspect` and `run --frames 1
--resolution 256x256` into a temporary folder, each with `--log-format json`.
One row per file: each step's exit status, wall time and peak memory (the
child's ru_maxrss from wait4), the prims by type (parsed from inspect's prim
tree), what was dropped (warnings carrying a "dropped" object, else the count
of warning lines), and whether the frame shows anything (the rgb PNG is not
one flat colour and not over 99.5 % black).

The rule, and the exit status (0 kept, 1 broken, 2 bad usage, 77 a folder
absent with --skip-absent): every step exits 0, or 2 with an error located at
file:line:col or naming the file, or 1 with an error message; never a signal
(exit >= 128), never a time-out (--timeout per step); and a run that exits 0
writes a frame that shows something, or warns that it is black.
Standard library, numpy and PIL only.
"""
import argparse
import collections
import concurrent.futures
import json
import os
import platform
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

import numpy as np
from PIL import Image

import usd_entry_layers

STEPS = ("validate", "inspect", "run")
DOC_BEGIN = "<!-- usd-corpus:begin (tools/usd_corpus.py writes this part) -->"
DOC_END = "<!-- usd-corpus:end -->"
BLACK_LEVEL = 8  # a pixel whose channels are all at most this is black
BLACK_LIMIT = 0.995  # a frame over this fraction black shows nothing


def run_child(argv, cwd, timeout):
    """Runs argv; returns exit (128 + signal when killed), wall seconds, peak MB, stdout, stderr, timed_out."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        start = time.monotonic()
        child = subprocess.Popen(argv, cwd=cwd, stdin=subprocess.DEVNULL, stdout=out, stderr=err,
                                 start_new_session=True)
        timed_out = threading.Event()

        def kill():
            timed_out.set()
            try:
                os.killpg(child.pid, signal.SIGKILL)  # the child's own group, started above
            except ProcessLookupError:
                pass

        timer = threading.Timer(timeout, kill)
        timer.start()
        try:
            _, status, usage = os.wait4(child.pid, 0)
        finally:
            timer.cancel()
        child.returncode = os.waitstatus_to_exitcode(status)  # reaped here: Popen must not wait again
        wall = time.monotonic() - start
        code = child.returncode if child.returncode >= 0 else 128 - child.returncode
        out.seek(0)
        err.seek(0)
        return {"exit": code, "seconds": round(wall, 3), "peak_mb": round(usage.ru_maxrss / 1024.0, 1),
                "timed_out": timed_out.is_set(),
                "stdout": out.read().decode("utf-8", "replace"), "stderr": err.read().decode("utf-8", "replace")}


def log_records(stderr):
    """The JSON log lines of stderr, and the lines that are not JSON (a crash, a library's own print)."""
    records, other = [], []
    for line in stderr.splitlines():
        try:
            record = json.loads(line)
            if isinstance(record, dict) and "level" in record:
                records.append(record)
                continue
        except ValueError:
            pass
        if line.strip():
            other.append(line)
    return records, other


def located(record):
    """Names a file: with a line in a text layer; a crate layer (binary) has no lines, so line 0 there."""
    return bool(record.get("file"))


def record_text(record):
    where = ""
    if record.get("file"):
        where = f"{record['file']}:{record.get('line', 0)}:{record.get('column', 0)}: "
    return where + str(record.get("message", ""))


def step_problem(step, result, file_name):
    """Why a step breaks the rule, or None when it keeps it."""
    if result["timed_out"]:
        return f"{step}: timed out"
    code = result["exit"]
    if code >= 128:
        return f"{step}: killed by signal {code - 128} (exit {code})"
    errors = [r for r in result["records"] if r.get("level") == "error"]
    if code == 2:
        named = any(located(r) or file_name in str(r.get("message", "")) for r in errors)
        named = named or any(file_name in line for line in result["other_stderr"])
        return None if named else f"{step}: exit 2 without an error located at file:line:col or naming {file_name}"
    if code == 1:
        return None if errors or result["other_stderr"] else f"{step}: exit 1 without a message"
    if code != 0:
        return f"{step}: unexpected exit {code}"
    return None


def prims_by_type(inspect_stdout):
    """{type: count} from inspect's prim tree: `<indent>/Path  Type`, indent two spaces per level below the root."""
    counts = collections.Counter()
    in_tree = False
    for line in inspect_stdout.splitlines():
        if re.match(r"^prims \(\d+\):$", line):
            in_tree = True
            continue
        m = re.match(r"^( *)(/\S*)  (\S+)", line) if in_tree else None
        if m and len(m.group(1)) == 2 * (m.group(2).count("/") - 1):
            counts[m.group(3)] += 1
    return dict(sorted(counts.items(), key=lambda kv: (-kv[1], kv[0])))


def frame_facts(folder):
    """The first rgb PNG under folder: its path, whether it shows anything, black fraction, distinct colours."""
    images = sorted(os.path.relpath(os.path.join(root, f), folder)
                    for root, _, files in os.walk(folder) for f in files
                    if f.startswith("rgb") and f.endswith(".png"))
    if not images:
        return {"image": None, "shows": False, "black": None, "colours": 0}
    rgb = np.asarray(Image.open(os.path.join(folder, images[0])).convert("RGB"))
    pixels = rgb.reshape(-1, 3)
    black = float((pixels.max(axis=1) <= BLACK_LEVEL).mean())
    colours = len(np.unique(pixels[:: max(1, len(pixels) // 65536)], axis=0))
    return {"image": images[0], "shows": colours > 1 and black <= BLACK_LIMIT, "black": round(black, 4),
            "colours": colours}


def dropped(records_by_step):
    """What the steps said was lost: {kind/what: count} from "dropped" objects, and the other warnings."""
    losses, warnings = {}, []
    for records in records_by_step:
        for r in records:
            if r.get("level") != "warning":
                continue
            loss = r.get("dropped")
            if isinstance(loss, dict):
                key = f"{loss.get('kind', '?')}: {loss.get('what', '?')}"
                losses[key] = max(losses.get(key, 0), int(loss.get("count") or 1))
            elif record_text(r) not in warnings:
                warnings.append(record_text(r))
    return losses, warnings


def check_file(binary, path, cwd, args):
    """Validates, inspects and runs one layer; returns its row."""
    shown = os.path.relpath(path, cwd)
    row = {"file": path, "argument": shown, "steps": {}}
    with tempfile.TemporaryDirectory(prefix="usd_corpus_") as tmp:
        out = os.path.join(tmp, "out")
        argv = {"validate": [binary, "validate", shown, "--log-format", "json"],
                "inspect": [binary, "inspect", shown, "--log-format", "json"],
                "run": [binary, "run", shown, "--log-format", "json", "--frames", "1",
                        "--resolution", args.resolution, "--out", out]}
        for step in STEPS:
            result = run_child(argv[step], cwd, args.timeout)
            result["records"], result["other_stderr"] = log_records(result["stderr"])
            result["problem"] = step_problem(step, result, os.path.basename(path))
            row["steps"][step] = result
        row["frame"] = frame_facts(out) if os.path.isdir(out) else frame_facts(tmp)
    steps = row["steps"]
    row["prims"] = prims_by_type(steps["inspect"]["stdout"]) if steps["inspect"]["exit"] == 0 else {}
    row["dropped"], row["warnings"] = dropped([steps[s]["records"] for s in STEPS])
    problems = [steps[s]["problem"] for s in STEPS if steps[s]["problem"]]
    if steps["run"]["exit"] == 0 and not row["frame"]["shows"]:
        said = any("black" in w.lower() or "empty" in w.lower() for w in row["warnings"])
        if not said:
            what = "no rgb image" if row["frame"]["image"] is None else \
                f"frame shows nothing ({row['frame']['colours']} colours, {row['frame']['black']:.1%} black)"
            problems.append(f"run: exit 0 but {what}, and no warning says so")
    row["problems"] = problems
    row["verdict"] = "broken" if problems else "runs" if steps["run"]["exit"] == 0 else "fails, naming the cause"
    for s in STEPS:  # keep the JSON small: the parsed records stay, the raw text goes
        steps[s]["stdout_lines"] = len(steps[s].pop("stdout").splitlines())
        steps[s]["stderr"] = steps[s]["stderr"][-4000:]
    return row


def first_error(row):
    for s in STEPS:
        for r in row["steps"][s]["records"]:
            if r.get("level") == "error":
                return record_text(r)
        if row["steps"][s]["exit"] != 0 and row["steps"][s]["other_stderr"]:
            return row["steps"][s]["other_stderr"][-1]
    return ""


def cell(text, limit=160):
    text = " ".join(str(text).split()).replace("|", "\\|")
    return text if len(text) <= limit else text[:limit - 1] + "…"


def markdown(rows, command, machine):
    broken = sum(1 for r in rows if r["problems"])
    runs = sum(1 for r in rows if r["verdict"] == "runs")
    lines = [f"{len(rows)} entry layers: {runs} run and show their frame (or warn that it is black), "
             f"{len(rows) - runs - broken} fail naming the cause, {broken} break the rule.", "",
             f"Command: `{command}`  ", f"Machine: {machine}", "",
             "| file | validate | inspect | run | frame | prims by type | dropped / warnings | run s | peak MB | result |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        s = r["steps"]
        frame = r["frame"]
        frame_text = "-" if frame["image"] is None else \
            ("shows" if frame["shows"] else f"blank ({frame['black']:.0%} black)")
        types = list(r["prims"].items())
        prims = ", ".join(f"{t} {n}" for t, n in types[:6]) + (", …" if len(types) > 6 else "")
        if r["dropped"]:
            losses = "; ".join(f"{k} ×{n}" for k, n in r["dropped"].items())
        else:
            losses = f"{len(r['warnings'])} warnings" if r["warnings"] else "-"
            if r["warnings"]:
                losses += ": " + r["warnings"][0]
        if r["problems"]:
            result = "**BROKEN**: " + "; ".join(r["problems"])
        elif r["verdict"] == "runs":
            result = "runs"
        else:
            result = "fails: " + first_error(r)
        peak = max(s[x]["peak_mb"] for x in STEPS)
        lines.append(f"| `{cell(r['label'], 90)}` | {s['validate']['exit']} | {s['inspect']['exit']} | "
                     f"{s['run']['exit']} | {frame_text} | {cell(prims, 120) or '-'} | {cell(losses)} | "
                     f"{s['run']['seconds']:.2f} | {peak:.0f} | {cell(result, 220)} |")
    return "\n".join(lines) + "\n"


def machine_text(binary):
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next((l.split(":", 1)[1].strip() for l in f if l.startswith("model name")), cpu)
    except OSError:
        pass
    try:
        version = subprocess.run([binary, "--version"], capture_output=True, text=True, timeout=30).stdout.strip()
    except OSError:
        version = "?"
    return f"{os.cpu_count()} cores ({cpu}), {platform.system()} {platform.release()}; {version}"


def update_doc(doc, table):
    with open(doc, encoding="utf-8") as f:
        text = f.read()
    if DOC_BEGIN not in text or DOC_END not in text:
        sys.exit(f"usd_corpus.py: {doc} has no '{DOC_BEGIN}' ... '{DOC_END}' markers to write the table between")
    head, rest = text.split(DOC_BEGIN, 1)
    tail = rest.split(DOC_END, 1)[1]
    with open(doc, "w", encoding="utf-8") as f:
        f.write(head + DOC_BEGIN + "\n" + table + DOC_END + tail)


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("paths", nargs="+", metavar="FOLDER_OR_FILE",
                   help="folders searched for entry layers; a file is taken as an entry layer")
    p.add_argument("--bin", required=True, help="the sdgbehave binary")
    p.add_argument("--cwd", default=os.getcwd(), help="run from this folder, files named relative to it (default: .)")
    p.add_argument("--resolution", default="256x256", help="the run's frame size (default 256x256)")
    p.add_argument("--timeout", type=float, default=120, help="seconds one step may take (default 120)")
    p.add_argument("--jobs", type=int, default=1, help="files checked at once (default 1: clean times)")
    p.add_argument("--all-layers", action="store_true", help="every USD file, not only the entry layers")
    p.add_argument("--skip-absent", action="store_true", help="exit 77 when a folder named is absent")
    p.add_argument("--json", help="write every row (all records, per step) to this JSON file")
    p.add_argument("--markdown", help="write the table to this file")
    p.add_argument("--doc", help="replace the table between the usd-corpus markers of this Markdown page")
    p.add_argument("--list", action="store_true", help="print the entry layers and dependencies, run nothing")
    return p.parse_args(argv)


def main(argv):
    args = parse_args(argv)
    binary = os.path.abspath(args.bin)
    cwd = os.path.abspath(args.cwd)
    absent = [p for p in args.paths if not os.path.exists(p)]
    if absent:
        print(f"usd_corpus.py: absent: {', '.join(absent)}")
        return 77 if args.skip_absent else 2
    if not os.access(binary, os.X_OK):
        print(f"usd_corpus.py: --bin {args.bin} is not an executable")
        return 2
    todo = []  # (absolute path, label)
    for p in args.paths:
        if os.path.isfile(p):
            todo.append((os.path.abspath(p), os.path.basename(p)))
            continue
        entries, deps = usd_entry_layers.entry_layers(p, args.all_layers)
        base = os.path.dirname(os.path.abspath(p).rstrip("/"))
        todo += [(e, os.path.relpath(e, base)) for e in entries]
        if args.list:
            print("\n".join(f"entry {os.path.relpath(e, base)}" for e in entries))
            print("\n".join(f"dependency {os.path.relpath(d, base)}" for d in deps))
    if args.list:
        return 0
    if not todo:
        print("usd_corpus.py: no USD file found")
        return 2

    with concurrent.futures.ThreadPoolExecutor(max(1, args.jobs)) as pool:
        rows = list(pool.map(lambda item: check_file(binary, item[0], cwd, args), todo))
    for row, (_, label) in zip(rows, todo):
        row["label"] = label
        status = "BROKEN" if row["problems"] else row["verdict"]
        print(f"{status:>24}  {label}  (exits {'/'.join(str(row['steps'][s]['exit']) for s in STEPS)})"
              + "".join(f"\n{'':>26}{p}" for p in row["problems"]))

    command = "/usr/bin/python3 tools/usd_corpus.py " + " ".join(argv)
    table = markdown(rows, command, machine_text(binary))
    if args.markdown:
        with open(args.markdown, "w", encoding="utf-8") as f:
            f.write(table)
    if args.doc:
        update_doc(args.doc, table)
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump({"command": command, "rows": rows}, f, indent=1)
    broken = [r for r in rows if r["problems"]]
    print(f"{len(rows)} files, {len(broken)} break the rule")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
