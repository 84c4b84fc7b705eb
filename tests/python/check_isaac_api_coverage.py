#!/usr/bin/python3
"""Which pxr/carb/omni/usdrt/isaacsim names Isaac Sim's behavior files use, and whether sdgbehave's
Isaac layer provides each: parses every .py under the shared folder with `ast`, collects each attribute
chain rooted at an import of those packages (module.Name, and module.Class.Member one level down), and
looks each up in the layer's sources (top-level definitions; class bodies, bases included). Fails when a
file listed in SUPPORTED uses a name the layer lacks; prints what the other files lack.

usage: check_isaac_api_coverage.py LAYER_DIR SHARED_DIR"""
import ast
import os
import sys

ROOTS = ("pxr", "carb", "omni", "usdrt", "isaacsim")
SUPPORTED = {"location_randomizer.py", "rotation_randomizer.py", "look_at_behavior.py", "light_randomizer.py",
             "texture_randomizer.py", "volume_stack_randomizer.py", "scene_utils.py", "example_behavior.py",
             "example_custom_event_behavior.py", "base_behavior.py", "example_base_behavior.py", "global_variables.py", "behavior_utils.py", "extension.py", "__init__.py"}


def chains(path):
    tree = ast.parse(open(path).read(), path)
    names = {}  # local name -> module path
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name.split(".")[0] in ROOTS:
                    names[(a.asname or a.name).split(".")[0]] = a.asname and a.name or a.name.split(".")[0]
        elif isinstance(node, ast.ImportFrom) and node.module and node.module.split(".")[0] in ROOTS \
                and not node.module.startswith("isaacsim.replicator"):
            for a in node.names:
                names[a.asname or a.name] = f"{node.module}.{a.name}"
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute):
            parts, n = [], node
            while isinstance(n, ast.Attribute):
                parts.append(n.attr)
                n = n.value
            if isinstance(n, ast.Name) and n.id in names:
                found.add(".".join([names[n.id]] + parts[::-1]))
        elif isinstance(node, ast.ImportFrom) and node.module and node.module.split(".")[0] in ROOTS \
                and not node.module.startswith("isaacsim.replicator"):
            found.update(f"{node.module}.{a.name}" for a in node.names)
    return found


def module_file(layer, parts):
    base = os.path.join(layer, *parts)
    for candidate in (base + ".py", os.path.join(base, "__init__.py")):
        if os.path.isfile(candidate):
            return candidate
    return None


def defined(tree_body):
    out = {}
    for node in tree_body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            out[node.name] = node
        elif isinstance(node, ast.Assign):
            for t in node.targets:
                for e in (t.elts if isinstance(t, ast.Tuple) else [t]):
                    if isinstance(e, ast.Name):
                        out[e.id] = node
                    elif isinstance(e, ast.Attribute):
                        out[e.attr] = node
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            for a in node.names:
                out[a.asname or a.name.split(".")[0]] = node
    return out


def provided(layer, chain):
    parts = chain.split(".")
    for i in range(len(parts), 0, -1):  # the longest prefix that is a module of the layer
        f = module_file(layer, parts[:i])
        if f:
            rest = parts[i:]
            break
    else:
        return False
    if not rest:
        return True
    tree = ast.parse(open(f).read())
    top = defined(tree.body)
    if rest[0] not in top:
        return module_file(layer, parts[:i] + rest[:1]) is not None
    node = top[rest[0]]
    if len(rest) == 1 or not isinstance(node, ast.ClassDef):
        return True
    classes = {n.name: n for n in ast.walk(tree) if isinstance(n, ast.ClassDef)}
    if rest[0] == "ValueTypeNames" or (isinstance(node, ast.Assign)):
        return True
    todo = [node]
    while todo:
        c = todo.pop()
        if rest[1] in defined(c.body):
            return True
        todo += [classes[b.id] for b in c.bases if isinstance(b, ast.Name) and b.id in classes]
    return False


def main():
    layer, shared = sys.argv[1:3]
    if not os.path.isdir(shared):
        print(f"skipped: Isaac Sim's behavior files are not at {shared}")
        return 77
    failed, report = False, []
    for folder, _, files in sorted(os.walk(shared)):
        for name in sorted(files):
            if not name.endswith(".py"):
                continue
            missing = sorted(c for c in chains(os.path.join(folder, name)) if not provided(layer, c))
            if missing and name in SUPPORTED:
                failed = True
                print(f"FAIL {name}: the layer lacks {', '.join(missing)}")
            elif missing:
                report.append(f"{name}: not provided: {', '.join(missing)}")
    print("\n".join(report))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
