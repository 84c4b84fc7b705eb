#!/usr/bin/python3
"""docs/architecture.md's module table stays true to the code: every
module a file under lib/<module>/ includes (`#include "other/..."`) must be
named in that module's "depends on" column (every module may use core; naming a module covers its
sub-modules: `render` covers `render/raster`), so the column is the list
of what the module's code really reaches, not what it reaches through. A module named in the table
that has no folder, or a folder under lib/ missing from the table, fails
too. Prints the real graph on failure, so the table can be corrected."""
import os
import re
import sys

from checklib import check, failures, finish


def table_rows(doc):
    rows = {}
    for line in open(doc, encoding="utf-8"):
        m = re.match(r"\| `lib/([a-z_/]+)` \|(.*)\|([^|]*)\|\s*$", line)
        if m:
            rows[m.group(1)] = m.group(3)
    return rows


def module_of(relpath, modules):
    # The longest module name that is a folder prefix (render/raster before render).
    best = None
    for m in modules:
        if relpath == m or relpath.startswith(m + "/"):
            if best is None or len(m) > len(best):
                best = m
    return best


def main():
    root = sys.argv[1]
    lib = os.path.join(root, "lib")
    rows = table_rows(os.path.join(root, "docs", "architecture.md"))
    modules = sorted(rows)
    folders = set()
    for entry in os.listdir(lib):
        if os.path.isdir(os.path.join(lib, entry)):
            folders.add(entry)
    for f in sorted(folders):
        check(f in rows or any(m.startswith(f + "/") for m in rows),
              f"lib/{f} has no row in docs/architecture.md's module table")
    for m in modules:
        check(os.path.isdir(os.path.join(lib, m)), f"docs/architecture.md names lib/{m}, which does not exist")

    documented = {}
    for m, column in rows.items():
        named = set(re.findall(r"\b([a-z_]+(?:/[a-z_]+)?)\b", column))
        documented[m] = {n for n in named if n in rows and n != m}

    actual = {m: set() for m in modules}
    undocumented = {}
    for dirpath, _, files in os.walk(lib):
        for name in files:
            if not name.endswith((".h", ".cpp")):
                continue
            path = os.path.join(dirpath, name)
            owner = module_of(os.path.relpath(path, lib), modules)
            if owner is None:
                continue
            for inc in re.findall(r'^#include "([^"]+)"', open(path, encoding="utf-8").read(), re.M):
                target = module_of(inc, modules)
                if target and target != owner and not owner.startswith(target + "/") and \
                        not target.startswith(owner + "/"):
                    actual[owner].add(target)
                    allowed = documented[owner] | {"core"}  # every module may use core
                    # A dependency on a module covers its sub-modules (render: render/raster too).
                    if not any(target == a or target.startswith(a + "/") for a in allowed):
                        undocumented.setdefault((owner, target), os.path.relpath(path, root) + ": " + inc)
    for (owner, target), example in sorted(undocumented.items()):
        failures.append(f"lib/{owner} uses lib/{target} (e.g. {example}), but its 'depends on' does not name it")
    if failures:
        failures.append("the includes say:")
        for m in modules:
            failures.append(f"  {m}: {', '.join(sorted(actual[m])) or '-'}")
    return finish("ok: the module table matches the includes")


if __name__ == "__main__":
    sys.exit(main())
