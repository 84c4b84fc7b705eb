"""One exposed variable of every USD type, to check that declarations
round-trip through describe, schema and --set."""
import sdgbehave

VARIABLES = [
    {"attr_name": "flag", "attr_type": "bool", "default_value": True, "doc": "A bool."},
    {"attr_name": "count", "attr_type": "int", "default_value": -4, "doc": "An int."},
    {"attr_name": "steps", "attr_type": "uint", "default_value": 7, "doc": "A uint.", "minimum": 1},
    {"attr_name": "ratio", "attr_type": "float", "default_value": 0.25, "doc": "A float."},
    {"attr_name": "length", "attr_type": "double", "default_value": 1.5, "doc": "A double."},
    {"attr_name": "cells", "attr_type": "int2", "default_value": (2, 3), "doc": "An int2."},
    {"attr_name": "range", "attr_type": "float2", "default_value": (0.5, 2.0), "doc": "A float2."},
    {"attr_name": "offset:xyz", "attr_type": "float3", "default_value": (1.0, 2.0, 3.0), "doc": "A float3."},
    {"attr_name": "tint", "attr_type": "color3f", "default_value": (1.0, 0.5, 0.25), "doc": "A color3f."},
    {"attr_name": "point", "attr_type": "double3", "default_value": (0.0, 0.0, 1.0), "doc": "A double3."},
    {"attr_name": "direction", "attr_type": "vector3d", "default_value": [0, 1, 0], "doc": "A vector3d."},
    {"attr_name": "turn", "attr_type": "quatd", "default_value": (1.0, 0.0, 0.0, 0.0), "doc": "A quatd."},
    {"attr_name": "label", "attr_type": "string", "default_value": "thing", "doc": "A string."},
    {"attr_name": "mode", "attr_type": "token", "default_value": "fast", "doc": "A token.",
     "allowed": ["fast", "slow"]},
    {"attr_name": "mesh", "attr_type": "asset", "default_value": "", "doc": "An asset.", "files": "mesh"},
    {"attr_name": "textures", "attr_type": "asset[]", "default_value": [], "doc": "Assets.", "files": "image"},
    {"attr_name": "names", "attr_type": "string[]", "default_value": ["a", "b"], "doc": "Strings."},
    {"attr_name": "target", "attr_type": "string", "default_value": "", "doc": "A prim.", "prim_path": True},
    {"attr_name": "event:input", "attr_type": "string", "default_value": "x.in", "doc": "Locked.", "lock": True},
]


class AllTypes(sdgbehave.Behavior):
    """Declares a variable of every type and does nothing with them."""

    BEHAVIOR_NS = "allTypes"
    VARIABLES_TO_EXPOSE = VARIABLES
