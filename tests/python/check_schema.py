#!/usr/bin/python3
"""The committed JSON Schema equals what `sdgbehave schema` generates, and
every scene under scenes/ starts with the schema comment, passes the
committed schema (which accepts behaviors it does not know, as an editor
sees a scene), passes the schema `sdgbehave schema --script` makes with its
behavior scripts (which types their variables) and passes `sdgbehave
validate`; every complete scene in the docs' ```yaml blocks (one with
`version:` and `prims:`) passes the committed schema too.

usage: check_schema.py SDGBEHAVE_BINARY SCHEMA SOURCE_DIR"""
import json
import os
import re
import subprocess
import sys

import jsonschema
import yaml

from scene_json import load_instance


YAML_BLOCK = re.compile(r"^```yaml\n(.*?)^```", re.S | re.M)


def doc_scenes(source):
    """(label, instance) of every ```yaml block in README.md and docs/*.md that is a whole scene."""
    pages = [os.path.join(source, "README.md")]
    docs = os.path.join(source, "docs")
    pages += sorted(os.path.join(docs, name) for name in os.listdir(docs) if name.endswith(".md"))
    found = []
    for page in pages:
        with open(page, encoding="utf-8") as f:
            text = f.read()
        for block in YAML_BLOCK.finditer(text):
            line = text.count("\n", 0, block.start()) + 2
            try:
                loose = yaml.safe_load(block.group(1))
            except yaml.YAMLError:
                continue  # a fragment, such as alternatives of one key
            if isinstance(loose, dict) and "version" in loose and "prims" in loose:
                found.append((f"{os.path.relpath(page, source)}:{line}", load_instance(block.group(1))))
    return found


def misspelt_variable_problems(scene, instance, committed, with_scripts, script_behaviors):
    """A script behavior's variable misspelt: the committed schema accepts it (it cannot know the
    script), the schema made with the script rejects it (it types the script's variables)."""
    for prim in (instance.get("prims") or {}).values():
        for name, variables in ((prim or {}).get("behaviors") or {}).items():
            if name in script_behaviors:
                variables = dict(variables or {}, misspeltVariable=1)
                prim["behaviors"][name] = variables
                problems = []
                if not committed.is_valid(instance):
                    problems.append(f"{scene}: the committed schema rejects an unknown behavior's variable")
                if jsonschema.Draft7Validator(with_scripts).is_valid(instance):
                    problems.append(f"{scene}: the schema with its scripts accepts {name}.misspeltVariable")
                return problems
    return [f"{scene}: no prim uses a behavior of its scripts"]


def main():
    binary, schema_path, source = sys.argv[1:4]
    scenes_dir = os.path.join(source, "scenes")
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
        for error in validator.iter_errors(instance):
            failures.append(f"{scene}: committed schema: {error.message} at {list(error.absolute_path)}")
        if instance.get("scripts"):
            # With its behavior scripts loaded (`sdgbehave schema --script`)
            # the schema types the scripts' variables: checked too.
            flags = [arg for script in instance["scripts"]
                     for arg in ("--script", os.path.join(os.path.dirname(scene), script))]
            generated_here = subprocess.run([binary, "schema", *flags], capture_output=True, text=True, check=True)
            with_scripts = json.loads(generated_here.stdout)
            script_behaviors = set(with_scripts["definitions"]["behaviors"]["properties"]) - \
                set(schema["definitions"]["behaviors"]["properties"])
            if not script_behaviors:
                failures.append(f"{scene}: `sdgbehave schema {' '.join(flags)}` added no behavior")
            for error in jsonschema.Draft7Validator(with_scripts).iter_errors(instance):
                failures.append(f"{scene}: schema with its scripts: {error.message} at {list(error.absolute_path)}")
            failures += misspelt_variable_problems(scene, instance, validator, with_scripts, script_behaviors)
        result = subprocess.run([binary, "validate", scene], capture_output=True, text=True)
        if result.returncode != 0:
            failures.append(f"{scene}: sdgbehave validate exited {result.returncode}:\n{result.stderr}")
    examples = doc_scenes(source)
    if not examples:
        failures.append(f"expected whole scenes in ```yaml blocks of {source}/docs, found none")
    for label, instance in examples:
        for error in validator.iter_errors(instance):
            failures.append(f"{label}: committed schema: {error.message} at {list(error.absolute_path)}")
    if failures:
        print("\n".join(failures))
        return 1
    print(f"ok: schema up to date; {len(scenes)} scenes pass the schema and the loader; "
          f"{len(examples)} scenes in the docs pass the schema")
    return 0


if __name__ == "__main__":
    sys.exit(main())
