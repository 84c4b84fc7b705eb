#!/usr/bin/python3
"""One bad scene: `sdgbehave validate` must exit 2 and print every message in
the file's `# expect:` lines; the JSON Schema must reject it too, unless a
`# schema-limit:` line says why JSON Schema cannot express the check (then
the schema must accept it, which keeps that note true)."""
import os
import subprocess
import sys

import jsonschema

from scene_json import InstanceError, load_instance


def main():
    binary, schema_path, scene = sys.argv[1:4]
    with open(scene, encoding="utf-8") as f:
        text = f.read()
    expects = [line.split("# expect:", 1)[1].strip() for line in text.splitlines() if line.startswith("# expect:")]
    schema_limit = any(line.startswith("# schema-limit:") for line in text.splitlines())
    assert expects, f"{scene}: no '# expect:' line"

    result = subprocess.run([binary, "validate", os.path.basename(scene)], cwd=os.path.dirname(scene),
                            capture_output=True, text=True, timeout=60)
    failures = []
    if result.returncode != 2:
        failures.append(f"exit code {result.returncode}, expected 2")
    for expect in expects:
        if expect not in result.stderr:
            failures.append(f"missing message: {expect}")
    if "internal error" in result.stderr:
        failures.append("an internal error was reported")

    with open(schema_path, encoding="utf-8") as f:
        schema = jsonschema.Draft7Validator(__import__("json").load(f))
    try:
        errors = list(schema.iter_errors(load_instance(text)))
        rejected = bool(errors)
        why = errors[0].message if errors else "accepted"
    except InstanceError as e:
        rejected, why = True, str(e)
    if schema_limit and rejected:
        failures.append(f"schema-limit says the schema cannot see this, but it rejected it: {why}")
    if not schema_limit and not rejected:
        failures.append("the JSON Schema accepted the scene")

    if failures:
        print(f"{scene}:\n  " + "\n  ".join(failures))
        print("stderr was:\n" + result.stderr)
        return 1
    print(f"ok: exit 2, {len(expects)} message(s); schema: {why}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
