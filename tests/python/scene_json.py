"""Turns a YAML scene into the JSON instance that JSON Schema validates.

Strict on purpose: duplicate keys, aliases and non-finite numbers have no
JSON equivalent, so they make the instance invalid (InstanceError).
"""
import json

import yaml


class InstanceError(Exception):
    pass


class _StrictLoader(yaml.SafeLoader):
    pass


def _construct_mapping(loader, node, deep=False):
    seen = set()
    for key_node, _ in node.value:
        key = loader.construct_object(key_node, deep=deep)
        if key in seen:
            raise InstanceError(f"duplicate key {key!r} at line {key_node.start_mark.line + 1}")
        seen.add(key)
    return yaml.SafeLoader.construct_mapping(loader, node, deep)


_StrictLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _construct_mapping)


def load_instance(text):
    """Returns the JSON value of the YAML text, or raises InstanceError."""
    try:
        for event in yaml.parse(text, Loader=yaml.SafeLoader):
            if isinstance(event, yaml.AliasEvent):
                raise InstanceError("YAML aliases have no JSON equivalent")
        data = yaml.load(text, Loader=_StrictLoader)
    except yaml.YAMLError as e:
        raise InstanceError(f"not YAML: {e}") from e
    try:
        return json.loads(json.dumps(data, allow_nan=False))
    except (ValueError, TypeError) as e:
        raise InstanceError(f"not representable as JSON: {e}") from e
