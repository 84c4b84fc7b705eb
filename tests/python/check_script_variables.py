#!/usr/bin/python3
"""A script's VARIABLES_TO_EXPOSE round-trips: `describe --script` lists
every variable with the declared type, default and doc; `schema --script`
describes them so that JSON Schema accepts a scene using them and rejects
a wrong value; `--set` reaches them (typed, bounded, located) and `inspect`
shows the result; an unknown variable gets a did-you-mean.

usage: check_script_variables.py SDGBEHAVE SCRIPTS_DIR"""
import json
import os
import subprocess
import sys

import jsonschema

from checklib import check, finish
from scene_json import load_instance

TYPE_OF_DEFAULT = {"quatd": lambda d: list(d), "int2": lambda d: list(d), "float2": lambda d: list(d),
                   "float3": lambda d: list(d), "color3f": lambda d: list(d), "double3": lambda d: list(d),
                   "vector3d": lambda d: [float(x) for x in d]}


def sdg(binary, *args, cwd):
    return subprocess.run([binary, *args], capture_output=True, text=True, cwd=cwd, timeout=120)


def main():
    binary, folder = os.path.abspath(sys.argv[1]), sys.argv[2]
    # The declarations as plain data, read without running sdgbehave's module.
    source = open(os.path.join(folder, "all_types.py"), encoding="utf-8").read()
    declared = eval(source.split("VARIABLES = ", 1)[1].split("\n]\n", 1)[0] + "\n]")

    described = sdg(binary, "describe", "allTypes", "--script", "all_types.py", "--format", "json", cwd=folder)
    check(described.returncode == 0, f"describe: {described.stderr}")
    variables = {v["name"]: v for v in json.loads(described.stdout)["behaviors"][0]["variables"]}
    check(list(variables) == [d["attr_name"] for d in declared], f"names/order: {list(variables)}")
    for d in declared:
        v = variables.get(d["attr_name"], {})
        want = TYPE_OF_DEFAULT.get(d["attr_type"], lambda x: x)(d["default_value"])
        check(v.get("type") == d["attr_type"], f"{d['attr_name']}: type {v.get('type')}")
        check(v.get("default") == want, f"{d['attr_name']}: default {v.get('default')} != {want}")
        check(v.get("doc") == d["doc"], f"{d['attr_name']}: doc {v.get('doc')}")
        check(v.get("locked") == d.get("lock", False), f"{d['attr_name']}: locked {v.get('locked')}")
    check(variables["steps"].get("minimum") == 1, "steps: minimum lost")
    check(variables["mode"].get("allowed") == ["fast", "slow"], "mode: allowed tokens lost")
    check(variables["textures"].get("files") == "image", "textures: files kind lost")

    schema_run = sdg(binary, "schema", "--script", "all_types.py", cwd=folder)
    check(schema_run.returncode == 0, f"schema: {schema_run.stderr}")
    validator = jsonschema.Draft7Validator(json.loads(schema_run.stdout))
    scene_text = open(os.path.join(folder, "all_types.yaml"), encoding="utf-8").read()
    errors = list(validator.iter_errors(load_instance(scene_text)))
    check(not errors, f"the schema rejects all_types.yaml: {errors[0].message if errors else ''}")
    bad = scene_text.replace("mode: slow", "mode: medium")
    check(list(validator.iter_errors(load_instance(bad))), "the schema accepts mode: medium")

    ok = sdg(binary, "inspect", "all_types.yaml", "--set", "/World/Box.exposedVar:allTypes:range=[1,4]",
             "--set", "/World/Box.exposedVar:allTypes:names=[x]", cwd=folder)
    check(ok.returncode == 0 and "range [1.0, 4.0]" in ok.stdout and "names ['x']" in ok.stdout,
          f"--set not applied: {ok.returncode} {ok.stderr}")
    for target, message in (("steps=0", "at least 1"), ("mode=medium", "expected one of fast, slow"),
                            ("count=abc", "expected"), ("rnage=[1,2]", "did you mean 'exposedVar:allTypes:range'")):
        p = sdg(binary, "validate", "all_types.yaml", "--set", f"/World/Box.exposedVar:allTypes:{target}", cwd=folder)
        check(p.returncode == 2 and "--set[1]:" in p.stderr and message in p.stderr,
              f"--set {target}: exit {p.returncode}, {p.stderr.strip()}")
    return finish(f"{len(declared)} variables round-trip through describe, schema and --set")


if __name__ == "__main__":
    sys.exit(main())
