#!/usr/bin/python3
"""A C++ behavior plugin built outside the source tree against an installed
sdgbehave (docs/plugins.md), loaded by the installed executable.

usage: check_install.py BUILD_DIR SOURCE_DIR

1. `cmake --install BUILD_DIR --prefix TMP/prefix`; the installed headers
   must be exactly the include closure (`c++ -MM`) of the plugin templates
   in lib/builtin_behaviors/templates/, so an #include added to an API header
   without installing the header fails here.
2. A fresh folder with a copy of example_behavior.cpp and the CMakeLists.txt
   of docs/plugins.md (its first ```cmake block: find_package(sdgbehave),
   a MODULE library linking sdgbehave::plugin), configured with
   CMAKE_PREFIX_PATH=TMP/prefix and built; no compile command may name the
   source tree.
3. The installed TMP/prefix/bin/sdgbehave lists the plugin's behavior
   (`describe --plugin`), validates a small scene that loads it through
   `plugins:`, and runs it (`run --no-render`), the behavior logging.

Exits 77 (skipped) when cmake or a C++ compiler is missing. Standard
library only."""
import os
import re
import shutil
import subprocess
import sys
import tempfile

SKIP = 77
TEMPLATE = "example_behavior.cpp"
BEHAVIOR = "exampleBehavior"
SCENE = """version: 1
plugins: [build/libmyplugin.so]
prims:
  /World:
    behaviors:
      exampleBehavior: {interval: 1, includeChildren: true}
  /World/Child: {type: Cube}
"""


def cache_value(build, name):
    """A CMakeCache.txt entry of the build being installed, or None."""
    try:
        with open(os.path.join(build, "CMakeCache.txt")) as f:
            for line in f:
                m = re.match(rf"{re.escape(name)}:[A-Z]+=(.*)$", line.rstrip("\n"))
                if m:
                    return m.group(1)
    except OSError:
        pass
    return None


def clean_env():
    """The environment for nested builds: none of an enclosing make's jobserver."""
    env = dict(os.environ)
    for key in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL", "MAKEOVERRIDES"):
        env.pop(key, None)
    return env


def run(cmd, cwd=None, timeout=600):
    print("$ " + " ".join(cmd), flush=True)
    result = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=timeout, env=clean_env())
    return result


def must(cmd, what, cwd=None):
    result = run(cmd, cwd=cwd)
    if result.returncode != 0:
        raise SystemExit(f"FAIL: {what}: exit {result.returncode}\n--- stdout\n{result.stdout}--- stderr\n{result.stderr}")
    return result


def doc_cmakelists(source):
    """The first ```cmake block of docs/plugins.md: the CMakeLists.txt users copy."""
    path = os.path.join(source, "docs", "plugins.md")
    with open(path) as f:
        blocks = re.findall(r"^```cmake\n(.*?)^```", f.read(), re.S | re.M)
    if not blocks:
        raise SystemExit(f"FAIL: {path} has no ```cmake block")
    return blocks[0]


def template_closure(cxx, source):
    """The headers below lib/ that the plugin templates include, directly or
    not, relative to lib/ (missing third-party headers are ignored: -MG)."""
    lib = os.path.join(source, "lib")
    templates = os.path.join(lib, "builtin_behaviors", "templates")
    headers = set()
    for name in sorted(os.listdir(templates)):
        if not name.endswith((".cpp", ".h")):
            continue
        result = must([cxx, "-std=c++20", "-MM", "-MG", "-x", "c++", f"-I{lib}", f"-I{templates}",
                       os.path.join(templates, name)], f"c++ -MM {name}")
        for dep in result.stdout.replace("\\\n", " ").split(":", 1)[1].split():
            if not os.path.isabs(dep):  # a third-party header -MG could not find
                continue
            dep = os.path.realpath(dep)
            if dep.startswith(lib + os.sep) and dep.endswith(".h"):
                headers.add(os.path.relpath(dep, lib))
    return headers


def main():
    build, source = (os.path.abspath(a) for a in sys.argv[1:3])
    cmake = cache_value(build, "CMAKE_COMMAND") or shutil.which("cmake")
    if not cmake or not os.access(cmake, os.X_OK):
        print("skipped: cmake is not installed")
        return SKIP
    # The compiler sdgbehave was built with: a plugin must share its C++ ABI.
    cxx = cache_value(build, "CMAKE_CXX_COMPILER")
    if not cxx or not os.access(cxx, os.X_OK):
        cxx = shutil.which("c++") or shutil.which("g++") or shutil.which("clang++")
    if not cxx:
        print("skipped: no C++ compiler (c++, g++, clang++)")
        return SKIP
    print(f"cmake: {cmake}\nC++ compiler: {cxx}")

    tmp = tempfile.mkdtemp(prefix="sdg_install_")
    failures = []
    try:
        prefix = os.path.join(tmp, "prefix")
        must([cmake, "--install", build, "--prefix", prefix], "cmake --install")
        binary = os.path.join(prefix, "bin", "sdgbehave")
        include = os.path.join(prefix, "include", "sdgbehave")
        package = os.path.join(prefix, "lib", "cmake", "sdgbehave")
        for path in (binary, os.path.join(include, "behavior", "plugin_api.h"),
                     os.path.join(package, "sdgbehaveConfig.cmake"),
                     os.path.join(package, "sdgbehaveConfigVersion.cmake")):
            if not os.path.isfile(path):
                failures.append(f"not installed: {os.path.relpath(path, prefix)}")
        installed = {os.path.relpath(os.path.join(d, f), include)
                     for d, _, files in os.walk(include) for f in files}
        wanted = template_closure(cxx, source)
        print(f"installed {len(installed)} headers; the templates' include closure has {len(wanted)}")
        for h in sorted(wanted - installed):
            failures.append(f"header the templates include but not installed (cmake/install.cmake): {h}")
        for h in sorted(installed - wanted):
            failures.append(f"installed header outside the templates' include closure: {h}")
        if failures:
            raise SystemExit("FAIL:\n" + "\n".join(failures))

        # The plugin project, out of the source tree, as docs/plugins.md has it.
        project = os.path.join(tmp, "myplugin")
        os.makedirs(project)
        shutil.copy(os.path.join(source, "lib", "builtin_behaviors", "templates", TEMPLATE), project)
        cmakelists = doc_cmakelists(source)
        with open(os.path.join(project, "CMakeLists.txt"), "w") as f:
            f.write(cmakelists)
        print(f"plugin project {project}: {TEMPLATE} and CMakeLists.txt:\n{cmakelists}", end="")
        must([cmake, "-S", project, "-B", os.path.join(project, "build"), "-DCMAKE_BUILD_TYPE=Release",
              f"-DCMAKE_PREFIX_PATH={prefix}", f"-DCMAKE_CXX_COMPILER={cxx}", "-DCMAKE_EXPORT_COMPILE_COMMANDS=ON"],
             "configuring the plugin project")
        must([cmake, "--build", os.path.join(project, "build")], "building the plugin")
        plugin = os.path.join(project, "build", "libmyplugin.so")
        if not os.path.isfile(plugin):
            raise SystemExit(f"FAIL: the build made no {plugin}")
        with open(os.path.join(project, "build", "compile_commands.json")) as f:
            commands = f.read()
        if source in commands:
            failures.append(f"a compile command names the source tree {source}:\n{commands}")

        # The installed executable loads it.
        result = run([binary, "describe", "--plugin", plugin])
        listed = [line for line in result.stdout.splitlines() if line.split()[:1] == [BEHAVIOR]]
        if result.returncode != 0 or not listed:
            failures.append(f"describe --plugin: exit {result.returncode}, no '{BEHAVIOR}' line:\n"
                            f"{result.stdout}{result.stderr}")
        else:
            print(f"  {listed[0]}")
        with open(os.path.join(project, "scene.yaml"), "w") as f:
            f.write(SCENE)
        result = run([binary, "validate", "scene.yaml"], cwd=project)
        if result.returncode != 0 or "scene.yaml: valid (2 prims, 1 behaviors" not in result.stdout:
            failures.append(f"validate: exit {result.returncode}:\n{result.stdout}{result.stderr}")
        else:
            print("  " + result.stdout.strip())
        result = run([binary, "run", "scene.yaml", "--no-render", "--frames", "2"], cwd=project)
        for text in (f"{BEHAVIOR}: applied to /World", f"{BEHAVIOR}: applied to /World/Child", "2 frames, 1 behaviors"):
            if text not in result.stderr:
                failures.append(f"run --no-render: exit {result.returncode}, stderr lacks '{text}':\n{result.stderr}")
                break
        else:
            if result.returncode != 0:
                failures.append(f"run --no-render: exit {result.returncode}:\n{result.stderr}")
            else:
                print(f"  run: {result.stderr.strip().splitlines()[-1]}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if failures:
        print("FAIL:\n" + "\n".join(failures))
        return 1
    print("ok: plugin built out of tree against the installed package and loaded by the installed sdgbehave")
    return 0


if __name__ == "__main__":
    sys.exit(main())
