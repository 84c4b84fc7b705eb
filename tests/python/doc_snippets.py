"""Behavior-script examples of a docs page, run inside a real sdgbehave run
(for check_docs.py).

A page that documents the script API (docs/scripting.md) shows, once, a
scene (a ```yaml block listing `scripts: [example.py]`) and an example
behavior (a ```python block with `BEHAVIOR_NS = "example"` and the line
`pass  # an example's lines go here`). Then:

- a snippet (a ```python block that uses `self` but defines no class) runs
  inside that behavior's first `apply()`, statement by statement; a statement
  whose comment is `# SomeError: MESSAGE` must raise that exception with
  MESSAGE in its text; one whose comment says `# -> VALUE` is evaluated and must give VALUE, where
  VALUE is a Python literal (floats to 1e-3, `...` in a sequence for the rest
  of it; `/home/me/project` stands for the scene's folder) or a repr such as
  `<Prim /World/Box>`; a comment that is neither is not compared;
- a script (a ```python block defining a class with its own BEHAVIOR_NS) is
  attached to the scene's /World/Box instead of `example` and run one frame.

All snippets of a page run in one sdgbehave run, one snippet per iteration
(`--iterations N --frames 1`): the stop at the end of each iteration puts
back what the snippet changed, as the timeline's stop does for a reader's
run. All scripts run in one more run, attached together. A snippet or script
that fails there runs again alone, in a folder of its own, and only a
failure alone counts: one example's changes never reach another's."""
import json
import os
import re
import subprocess

CONTEXT_MARK = "pass  # an example's lines go here"

CHECKER = r'''

def _docs_same(actual, expected):
    if expected is Ellipsis:
        return True
    if isinstance(expected, bool) or expected is None:
        return actual is expected
    if isinstance(expected, (int, float)):
        if isinstance(actual, bool) or not isinstance(actual, (int, float)):
            return False
        if isinstance(expected, float) != isinstance(actual, float):
            return False
        return abs(actual - expected) <= 1e-3 * max(1.0, abs(expected))
    if isinstance(expected, (tuple, list)):
        if type(actual) is not type(expected):
            return False
        if Ellipsis in expected:
            head = expected[:expected.index(Ellipsis)]
            return len(actual) >= len(head) and all(_docs_same(a, e) for a, e in zip(actual, head))
        return len(actual) == len(expected) and all(_docs_same(a, e) for a, e in zip(actual, expected))
    if isinstance(expected, dict):
        return (isinstance(actual, dict) and set(actual) == set(expected)
                and all(_docs_same(actual[k], expected[k]) for k in expected))
    return actual == expected


def _docs_run(self):
    """Runs the next snippet, once per play (one iteration each)."""
    import ast
    import json
    import os
    import re
    cls = type(self)
    if getattr(cls, "_docs_ran_this_play", False):
        return
    cls._docs_ran_this_play = True
    folder = os.environ["SDG_DOC_FOLDER"]
    names = json.load(open(os.path.join(folder, "snippets.json")))
    index = getattr(cls, "_docs_next", 0)
    cls._docs_next = index + 1
    if index >= len(names):
        return
    source = open(os.path.join(folder, names[index])).read()
    lines = source.splitlines()
    scope = dict(globals())
    scope["self"] = self
    report = {"compared": 0, "problems": []}
    for statement in ast.parse(source).body:
        rest = lines[statement.end_lineno - 1][statement.end_col_offset:]
        comment = rest.split("#", 1)[1] if "#" in rest else ""
        where = statement.lineno
        raises = re.match(r"\s*([A-Za-z_]\w*(?:Error|Exception)): (.+)$", comment)
        try:
            if "->" in comment and isinstance(statement, ast.Expr):
                actual = eval(compile(ast.Expression(statement.value), "snippet.py", "eval"), scope)
                shown = comment.rsplit("->", 1)[1].strip()
                try:
                    expected = ast.literal_eval(shown.replace("/home/me/project", folder))
                except (ValueError, SyntaxError):
                    if shown.startswith("<"):
                        report["compared"] += 1
                        if repr(actual) != shown:
                            report["problems"].append(f"{where}: gives {actual!r}, the page shows {shown}")
                    continue
                report["compared"] += 1
                if not _docs_same(actual, expected):
                    report["problems"].append(f"{where}: gives {actual!r}, the page shows {shown}")
            elif raises and isinstance(statement, ast.Expr):
                report["compared"] += 1
                try:
                    eval(compile(ast.Expression(statement.value), "snippet.py", "eval"), scope)
                    report["problems"].append(f"{where}: raised nothing, the page shows {raises.group(0).strip()}")
                except Exception as e:
                    if type(e).__name__ != raises.group(1) or raises.group(2).strip() not in str(e):
                        report["problems"].append(f"{where}: raised {type(e).__name__}: {e}, "
                                                  f"the page shows {raises.group(0).strip()}")
            else:
                exec(compile(ast.Module([statement], []), "snippet.py", "exec"), scope)
        except Exception as e:
            report["problems"].append(f"{where}: {type(e).__name__}: {e}")
            break
    with open(os.path.join(folder, names[index] + ".json"), "w") as out:
        json.dump(report, out)


def _docs_once_per_play(cls):
    """Lets _docs_run run again in the next play (the next iteration)."""
    original = getattr(cls, "on_play", None)

    def on_play(self, *args, **kwargs):
        type(self)._docs_ran_this_play = False
        return original(self, *args, **kwargs) if original else None
    cls.on_play = on_play
'''


def find_context(blocks):
    """(scene yaml, example behavior) of a page, or None."""
    scene = next((b.text for b in blocks if b.language == "yaml" and "scripts: [example.py]" in b.text), None)
    behavior = next((b.text for b in blocks if b.language == "python" and CONTEXT_MARK in b.text), None)
    return (scene, behavior) if scene and behavior else None


def is_snippet(block):
    return re.search(r"\bself\b", block.text) is not None and not re.search(r"^class ", block.text, re.M)


def script_name(block):
    """The BEHAVIOR_NS a script block registers, or None when it is not a script."""
    if not re.search(r"^class ", block.text, re.M):
        return None
    found = re.search(r"^\s+BEHAVIOR_NS = \"([^\"]+)\"", block.text, re.M)
    return found.group(1) if found else None


def run_all(binary, snippets, scripts, context, folder, env):
    """Runs a page's snippet and script blocks in its example scene, all
    together first and alone where that fails; returns {block line:
    (problems, number of values compared)}."""
    results = {}
    os.makedirs(folder, exist_ok=True)
    if snippets:
        results.update(_run_snippets(binary, snippets, context, os.path.join(folder, "snippets"), env))
    if scripts:
        results.update(_run_scripts(binary, scripts, context, os.path.join(folder, "scripts"), env))
    for block in snippets + scripts:
        if results[block.line][0]:
            print(f"again alone: {block.where()}: {results[block.line][0][0][:600]}", flush=True)
            alone = os.path.join(folder, f"alone_{block.line}")
            if block in snippets:
                results[block.line] = _run_snippets(binary, [block], context, alone, env)[block.line]
            else:
                results[block.line] = _run_scripts(binary, [block], context, alone, env)[block.line]
    return results


def _run(binary, folder, iterations, env):
    """The run of folder/scene.yaml: None, or what went wrong."""
    try:
        # --no-render takes one iteration only, so several render a tiny frame.
        frames = ["--no-render"] if iterations == 1 else ["--resolution", "8x8", "--iterations", str(iterations)]
        result = subprocess.run([binary, "run", "scene.yaml", "--frames", "1", "--out", "out"] + frames,
                                cwd=folder, env=dict(env, SDG_DOC_FOLDER=folder), capture_output=True,
                                text=True, timeout=120)
    except subprocess.TimeoutExpired:
        return "the run did not end within 120 s"
    return f"the run exited {result.returncode}:\n{result.stderr.rstrip()}" if result.returncode else None


def _run_snippets(binary, blocks, context, folder, env):
    scene, behavior = context
    os.makedirs(folder)
    classes = re.findall(r"^class (\w+)", behavior, re.M)
    with open(os.path.join(folder, "example.py"), "w") as f:
        f.write(behavior.replace(CONTEXT_MARK, "_docs_run(self)") + CHECKER
                + "".join(f"\n_docs_once_per_play({name})\n" for name in classes))
    names = []
    for block in blocks:
        names.append(f"snippet_{block.line}.py")
        with open(os.path.join(folder, names[-1]), "w") as f:
            f.write(block.text)
    with open(os.path.join(folder, "snippets.json"), "w") as f:
        json.dump(names, f)
    with open(os.path.join(folder, "scene.yaml"), "w") as f:
        f.write(scene if len(blocks) == 1 else scene.rstrip("\n") + "\nwriter: {type: BasicWriter, rgb: true}\n")
    failed = _run(binary, folder, len(blocks), env)
    results = {}
    for block, name in zip(blocks, names):
        report_path = os.path.join(folder, name + ".json")
        if failed:
            results[block.line] = ([failed], 0)
        elif not os.path.exists(report_path):
            results[block.line] = (["apply() never ran the snippet"], 0)
        else:
            report = json.load(open(report_path))
            results[block.line] = ([f"{block.page}:{block.line - 1 + int(p.split(':', 1)[0])}:{p.split(':', 1)[1]}"
                                    for p in report["problems"]], report["compared"])
    return results


def _run_scripts(binary, blocks, context, folder, env):
    """Every script block attached to /World/Box, in one run of one frame."""
    scene, _ = context
    os.makedirs(folder)
    files = [f"script_{block.line}.py" for block in blocks]
    for block, name in zip(blocks, files):
        with open(os.path.join(folder, name), "w") as f:
            f.write(block.text)
    scene = scene.replace("scripts: [example.py]", "scripts: [%s]" % ", ".join(files))
    attached = ", ".join("%s: {}" % script_name(block) for block in blocks)
    scene = re.sub(r"behaviors: \{example: \{[^}]*\}\}", "behaviors: {%s}" % attached, scene)
    with open(os.path.join(folder, "scene.yaml"), "w") as f:
        f.write(scene)
    failed = _run(binary, folder, 1, env)
    return {block.line: ([failed] if failed else [], 0) for block in blocks}
