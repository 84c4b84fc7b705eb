#!/usr/bin/python3
"""The USD corpus runner (tools/usd_corpus.py), on files it must pass and on binaries it must catch.

  check_usd_corpus.py BIN REPO cases   tests/data/usd/corpus_cases: the referenced layer in parts/ is a
                                       dependency, not a row; scene.usda runs to a frame that shows
                                       something, with its prims by type; bad_syntax.usda and
                                       missing_reference.usda fail with exit 2 at their file:line:col;
                                       the runner exits 0. Then stand-in binaries that crash, time out,
                                       exit 1 or 2 without a message, or write a black frame: the runner
                                       exits 1 naming each.
  check_usd_corpus.py BIN REPO real    ../shared/usd-samples and ../shared/usd-corpus: every entry layer
                                       keeps the rule (exit 77 when the folders are absent).
"""
import json
import os
import stat
import subprocess
import sys
import tempfile

from checklib import check, finish

FAKE_BINARY = r'''#!/usr/bin/python3
# A stand-in for sdgbehave whose misbehaviour FAKE_MODE picks, for the corpus runner's own test.
import os, signal, sys, time
mode, step = os.environ["FAKE_MODE"], sys.argv[1]
if step == "--version":
    print("fake"); sys.exit(0)
if mode == "crash" and step == "inspect":
    os.kill(os.getpid(), signal.SIGSEGV)
if mode == "hang" and step == "validate":
    time.sleep(30)
if mode == "silent1" and step == "run":
    sys.exit(1)
if mode == "unlocated2" and step == "validate":
    print('{"level":"error","file":"","line":0,"column":0,"message":"something went wrong"}', file=sys.stderr)
    sys.exit(2)
if mode == "black" and step == "run":
    import numpy as np
    from PIL import Image
    out = sys.argv[sys.argv.index("--out") + 1]
    os.makedirs(out)
    Image.fromarray(np.zeros((16, 16, 3), np.uint8)).save(os.path.join(out, "rgb_0000.png"))
if step == "inspect":
    print("prims (1):\n/World  Xform")
sys.exit(0)
'''


def runner(repo, *args, env=None, timeout=600):
    tool = os.path.join(repo, "tools", "usd_corpus.py")
    return subprocess.run(["/usr/bin/python3", tool, *args], capture_output=True, text=True, timeout=timeout,
                          env=env)


def check_cases(binary, repo, tmp):
    cases = os.path.join(repo, "tests", "data", "usd", "corpus_cases")
    listing = runner(repo, "--bin", binary, "--list", cases)
    check(listing.returncode == 0, f"--list: exit {listing.returncode}: {listing.stderr}")
    check("dependency corpus_cases/parts/box.usda" in listing.stdout.splitlines(),
          f"parts/box.usda is referenced by scene.usda, expected a dependency: {listing.stdout}")

    report = os.path.join(tmp, "cases.json")
    table = os.path.join(tmp, "cases.md")
    # From another working directory, by relative paths, as a user would.
    elsewhere = os.path.join(tmp, "elsewhere")
    os.makedirs(elsewhere)
    result = runner(repo, "--bin", binary, "--cwd", elsewhere, "--json", report, "--markdown", table, cases)
    check(result.returncode == 0, f"runner on corpus_cases: exit {result.returncode}: {result.stdout}{result.stderr}")
    if not os.path.exists(report):
        return
    rows = {r["label"]: r for r in json.load(open(report))["rows"]}
    check(sorted(rows) == ["corpus_cases/bad_syntax.usda", "corpus_cases/missing_reference.usda",
                           "corpus_cases/scene.usda"], f"rows {sorted(rows)}, expected the three entry layers")
    scene = rows.get("corpus_cases/scene.usda")
    if scene:
        check(scene["argument"].startswith(".."), f"scene.usda was named {scene['argument']}, expected a relative path")
        check(scene["verdict"] == "runs", f"scene.usda: {scene['verdict']} {scene['problems']}")
        check(scene["frame"]["shows"], f"scene.usda's frame shows nothing: {scene['frame']}")
        for kind in ("Cube", "Camera", "Mesh", "DistantLight"):
            check(scene["prims"].get(kind) == 1, f"scene.usda prims {scene['prims']}: expected one {kind}")
        check(all(scene["steps"][s]["peak_mb"] > 1 for s in ("validate", "inspect", "run")),
              "scene.usda: a step's peak memory was not measured")
    for name, line in (("bad_syntax.usda", 14), ("missing_reference.usda", 10)):
        row = rows.get("corpus_cases/" + name)
        if not row:
            continue
        check(row["verdict"] == "fails, naming the cause", f"{name}: {row['verdict']} {row['problems']}")
        for step in ("validate", "inspect", "run"):
            s = row["steps"][step]
            errors = [r for r in s["records"] if r.get("level") == "error"]
            check(s["exit"] == 2 and any(r.get("file", "").endswith(name) and r.get("line") == line for r in errors),
                  f"{name} {step}: exit {s['exit']}, expected 2 with an error at {name}:{line}: {errors}")
    text = open(table).read()
    check("| `corpus_cases/bad_syntax.usda` | 2 | 2 | 2 |" in text, f"the table lacks bad_syntax's row:\n{text}")


def check_fakes(repo, tmp):
    """The runner's rule, on stand-in binaries that break it one way each."""
    fake = os.path.join(tmp, "fake_sdgbehave")
    with open(fake, "w") as f:
        f.write(FAKE_BINARY)
    os.chmod(fake, os.stat(fake).st_mode | stat.S_IXUSR)
    layer = os.path.join(repo, "tests", "data", "usd", "corpus_cases", "scene.usda")
    expected = {"crash": "inspect: killed by signal 11 (exit 139)",
                "hang": "validate: timed out",
                "silent1": "run: exit 1 without a message",
                "unlocated2": "validate: exit 2 without an error located at file:line:col or naming scene.usda",
                "black": "run: exit 0 but frame shows nothing (1 colours, 100.0% black), and no warning says so"}
    for mode, problem in expected.items():
        result = runner(repo, "--bin", fake, "--timeout", "2", layer, env=dict(os.environ, FAKE_MODE=mode))
        check(result.returncode == 1 and problem in result.stdout,
              f"stand-in '{mode}': runner exit {result.returncode}, expected 1 saying '{problem}': {result.stdout}"
              f"{result.stderr}")
    result = runner(repo, "--bin", fake, layer, env=dict(os.environ, FAKE_MODE="fine"))
    check(result.returncode == 1 and "no rgb image" in result.stdout,
          f"a run that writes no image: runner exit {result.returncode}: {result.stdout}")


def main():
    binary, repo, what = sys.argv[1], os.path.abspath(sys.argv[2]), sys.argv[3]
    with tempfile.TemporaryDirectory() as tmp:
        if what == "cases":
            check_cases(binary, repo, tmp)
            check_fakes(repo, tmp)
        else:
            shared = os.path.join(repo, "..", "shared")
            result = runner(repo, "--bin", binary, "--skip-absent", "--jobs", "2", "--timeout", "60",
                            "--json", os.path.join(tmp, "real.json"),
                            os.path.join(shared, "usd-samples"), os.path.join(shared, "usd-corpus"))
            if result.returncode == 77:
                print(f"skipped: {result.stdout.strip()}")
                return 77
            print(result.stdout)
            check(result.returncode == 0, f"runner on the real files: exit {result.returncode}: {result.stderr}")
    return finish()


if __name__ == "__main__":
    sys.exit(main())
