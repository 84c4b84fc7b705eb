#!/usr/bin/python3
"""`sdgbehave describe --format json` is the machine-readable list of
behaviors: it parses with json, names every behavior the text listing names,
and gives each variable its attribute, USD type, default, doc and bounds;
`describe NAME --format json` gives that one behavior; an unknown name exits 2."""
import json
import subprocess
import sys

USD_TYPES = {"bool", "int", "uint", "float", "double", "int2", "float2", "float3", "double3", "vector3d", "point3d",
             "color3f", "quatd", "quatf", "matrix4d", "string", "token", "asset", "asset[]", "string[]"}


def run(*args):
    return subprocess.run(list(args), capture_output=True, text=True, timeout=60)


def main():
    binary = sys.argv[1]
    failures = []
    result = run(binary, "describe", "--format", "json")
    if result.returncode != 0:
        print(f"describe --format json exited {result.returncode}:\n{result.stderr}")
        return 1
    listing = json.loads(result.stdout)
    names = [b["name"] for b in listing["behaviors"]]
    text_names = [line.split()[0] for line in run(binary, "describe").stdout.splitlines()
                  if line and not line.startswith(("Run ", " "))]
    if sorted(names) != sorted(text_names):
        failures.append(f"json lists {names}, text lists {text_names}")
    for behavior in listing["behaviors"]:
        for key in ("summary", "source", "driven_by", "variables"):
            if key not in behavior:
                failures.append(f"{behavior['name']}: no '{key}'")
        for var in behavior["variables"]:
            where = f"{behavior['name']}.{var.get('name')}"
            if var["attribute"] != f"exposedVar:{behavior['name']}:{var['name']}":
                failures.append(f"{where}: attribute {var['attribute']}")
            if var["type"] not in USD_TYPES:
                failures.append(f"{where}: type {var['type']} is not a USD type name")
            if not var["doc"]:
                failures.append(f"{where}: no doc")
            if "default" not in var:
                failures.append(f"{where}: no default")
    interval = next(v for v in listing["behaviors"][0]["variables"] if v["name"] == "interval")
    if interval["type"] != "uint" or interval["default"] != 0:
        failures.append(f"interval: {interval}")
    textures = next(b for b in listing["behaviors"] if b["name"] == "textureRandomizer")
    if next(v for v in textures["variables"] if v["name"] == "textures:assets").get("files") != "image":
        failures.append("textureRandomizer.textures:assets does not say it names image files")

    one = json.loads(run(binary, "describe", "lookAtBehavior", "--format", "json").stdout)
    if [b["name"] for b in one["behaviors"]] != ["lookAtBehavior"]:
        failures.append(f"describe lookAtBehavior --format json gave {one}")
    unknown = run(binary, "describe", "lookAtBehaviour", "--format", "json")
    if unknown.returncode != 2 or "did you mean 'lookAtBehavior'" not in unknown.stderr:
        failures.append(f"unknown name: exit {unknown.returncode}, {unknown.stderr}")
    if failures:
        print("\n".join(failures))
        return 1
    print(f"{len(names)} behaviors, {sum(len(b['variables']) for b in listing['behaviors'])} variables")
    return 0


if __name__ == "__main__":
    sys.exit(main())
