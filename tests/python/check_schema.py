#!/usr/bin/python3
"""The committed JSON Schema equals what `sdgbehave schema` generates, and
every scene under scenes/ starts with the schema comment, passes the schema
(with its behavior scripts, the schema `sdgbehave schema --script` makes)
and passes `sdgbehave validate`."""
import json
import os
import subprocess
import sys

import jsonschema

from scene_json import load_instance


def main():
    binary, schema_path, scenes_dir = sys.argv[1:4]
    failures = []
    generated = subprocess.run([binary, "schema"], capture_output=True, text=True, check=True).stdout
    with open(schema_path, encoding="utf-8") as f:
        committed = f.read()
    if generated != committed:
        failures.append(f"{schema_path} differs from `sdgbehave schema`; regenerate it with "
                        f"`sdgbehave schema --out schemas/scene.schema.json`")
    schema = json.loads(committed)
    jsonschema.Draft7Validator.check_schema(schema)
    validator = jsonschema.Draft7Validator(schema)

    scenes = sorted(os.path.join(root, name) for root, _, names in os.walk(scenes_dir)
                    for name in names if name.endswith(".yaml"))
    if len(scenes) < 2:
        failures.append(f"expected scenes under {scenes_dir}, found {len(scenes)}")
    for scene in scenes:
        with open(scene, encoding="utf-8") as f:
            text = f.read()
        relative = os.path.relpath(schema_path, os.path.dirname(scene))
        if not text.startswith(f"# yaml-language-server: $schema={relative}\n"):
            failures.append(f"{scene}: first line must be '# yaml-language-server: $schema={relative}'")
        instance = load_instance(text)
        scene_validator = validator
        if instance.get("scripts"):
            # A scene with behavior scripts is checked against the schema
            # generated with those scripts (`sdgbehave schema --script`).
            flags = [arg for script in instance["scripts"]
                     for arg in ("--script", os.path.join(os.path.dirname(scene), script))]
            generated_here = subprocess.run([binary, "schema", *flags], capture_output=True, text=True, check=True)
            scene_validator = jsonschema.Draft7Validator(json.loads(generated_here.stdout))
        for error in scene_validator.iter_errors(instance):
            failures.append(f"{scene}: schema: {error.message} at {list(error.absolute_path)}")
        result = subprocess.run([binary, "validate", scene], capture_output=True, text=True)
        if result.returncode != 0:
            failures.append(f"{scene}: sdgbehave validate exited {result.returncode}:\n{result.stderr}")
    if failures:
        print("\n".join(failures))
        return 1
    print(f"ok: schema up to date; {len(scenes)} scenes pass the schema and the loader")
    return 0


if __name__ == "__main__":
    sys.exit(main())
