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

Each runs in its own folder, so one example's changes never reach another's."""
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
    import ast
    import json
    import os
    import re
    if getattr(type(self), "_docs_done", False):
        return
    type(self)._docs_done = True
    folder = os.environ["SDG_DOC_FOLDER"]
    source = open(os.path.join(folder, "snippet.py")).read()
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
    with open(os.path.join(folder, "report.json"), "w") as out:
        json.dump(report, out)
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


def run_in_behavior(binary, block, context, folder, env):
    """Runs a snippet or script block in the page's example scene; returns
    (problems, number of values compared)."""
    scene, behavior = context
    os.makedirs(folder)
    name = script_name(block)
    if name:
        scene = scene.replace("scripts: [example.py]", "scripts: [script.py]")
        scene = re.sub(r"behaviors: \{example: \{[^}]*\}\}", "behaviors: {%s: {}}" % name, scene)
        with open(os.path.join(folder, "script.py"), "w") as f:
            f.write(block.text)
    else:
        with open(os.path.join(folder, "example.py"), "w") as f:
            f.write(behavior.replace(CONTEXT_MARK, "_docs_run(self)") + CHECKER)
        with open(os.path.join(folder, "snippet.py"), "w") as f:
            f.write(block.text)
    with open(os.path.join(folder, "scene.yaml"), "w") as f:
        f.write(scene)
    env = dict(env, SDG_DOC_FOLDER=folder)
    try:
        result = subprocess.run([binary, "run", "scene.yaml", "--no-render", "--frames", "1", "--out", "out"],
                                cwd=folder, env=env, capture_output=True, text=True, timeout=120)
    except subprocess.TimeoutExpired:
        return ["the run did not end within 120 s"], 0
    if result.returncode != 0:
        return [f"the run exited {result.returncode}:\n{result.stderr.rstrip()}"], 0
    if name:
        return [], 0
    report_path = os.path.join(folder, "report.json")
    if not os.path.exists(report_path):
        return ["apply() never ran the snippet"], 0
    report = json.load(open(report_path))
    return [f"{block.page}:{block.line - 1 + int(p.split(':', 1)[0])}:{p.split(':', 1)[1]}"
            for p in report["problems"]], report["compared"]
