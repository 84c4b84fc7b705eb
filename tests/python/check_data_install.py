#!/usr/bin/python3
"""`sdgbehave.data` installs and imports:

1. `cmake --install BUILD_DIR --component python --prefix TMP` installs every
   .py file of python/sdgbehave/ (and nothing else) below
   TMP/SDG_PYTHON_INSTALL_DIR, and the installed copy imports from there;
2. that folder, under the prefixes /usr/local and /usr, is one Debian's
   /usr/bin/python3 searches, so `make install` needs no PYTHONPATH;
3. the build tree's python/ (a link to the source folder) imports too.

Exits 77 (skipped) when cmake is missing. Standard library only (and checklib).

usage: check_data_install.py BUILD_DIR SOURCE_DIR"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

from checklib import check, finish

PYTHON = "/usr/bin/python3"
PROBE = "import sdgbehave.data as d; print(d.__file__); print(d.Dataset.__name__)"


def cache_value(build, name):
    with open(os.path.join(build, "CMakeCache.txt"), encoding="utf-8") as f:
        for line in f:
            m = re.match(rf"{re.escape(name)}:[A-Z]+=(.*)$", line.rstrip("\n"))
            if m:
                return m.group(1)
    return None


def imported_from(pythonpath, cwd):
    result = subprocess.run([PYTHON, "-c", PROBE], cwd=cwd, capture_output=True, text=True,
                            env=dict(os.environ, PYTHONPATH=pythonpath))
    if result.returncode != 0:
        raise SystemExit(f"FAIL: import sdgbehave.data with PYTHONPATH={pythonpath}:\n{result.stderr}")
    return result.stdout.splitlines()[0]


def main():
    build, source = (os.path.abspath(a) for a in sys.argv[1:3])
    cmake = shutil.which("cmake")
    if not cmake:
        print("skipped: no cmake")
        return 77
    relative = cache_value(build, "SDG_PYTHON_INSTALL_DIR")
    if not relative:
        print(f"FAIL: {build}/CMakeCache.txt has no SDG_PYTHON_INSTALL_DIR")
        return 1
    with tempfile.TemporaryDirectory(prefix="sdg_pyinstall_") as prefix:
        result = subprocess.run([cmake, "--install", build, "--component", "python", "--prefix", prefix],
                                capture_output=True, text=True)
        if result.returncode != 0:
            print(f"FAIL: cmake --install --component python: {result.stderr}")
            return 1
        site = os.path.join(prefix, relative)
        installed = sorted(os.path.relpath(os.path.join(root, n), prefix)
                           for root, _, names in os.walk(prefix) for n in names)
        package = os.path.join(source, "python")
        expected = sorted(os.path.join(relative, os.path.relpath(os.path.join(root, n), package))
                          for root, dirs, names in os.walk(package) for n in names
                          if n.endswith(".py") and "__pycache__" not in root)
        check(installed == expected, f"installed {installed}, expected {expected}")
        where = imported_from(site, prefix)
        check(where.startswith(site + os.sep), f"the installed package imported from {where}, not below {site}")
    for default_prefix in ("/usr/local", "/usr"):
        searched = subprocess.run([PYTHON, "-c", "import sys; print('\\n'.join(sys.path))"], capture_output=True,
                                  text=True, check=True).stdout.splitlines()
        check(os.path.join(default_prefix, relative) in searched,
              f"{default_prefix}/{relative} is not on {PYTHON}'s sys.path {searched}")
    linked = imported_from(os.path.join(build, "python"), build)
    check(linked.startswith(os.path.join(build, "python") + os.sep), f"the build tree's package imported from {linked}")
    return finish(f"ok: installed below <prefix>/{relative}, imports from there and from {build}/python")


if __name__ == "__main__":
    sys.exit(main())
