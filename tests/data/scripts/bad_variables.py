import sdgbehave


class BadVariables(sdgbehave.IntervalBehavior):
    BEHAVIOR_NS = "badVariables"
    VARIABLES_TO_EXPOSE = [
        {"attr_name": "speed", "attr_type": "float", "default_value": 1.0, "doc": "Fine."},
        {"attr_name": "size", "attr_type": "vector3", "default_value": (1, 1, 1), "doc": "Unknown type."},
        {"attr_name": "count", "attr_type": "uint", "default_value": -3, "doc": "Negative uint."},
        {"attr_name": "mode", "attr_type": "string", "default_value": "a", "dok": "Misspelt key."},
    ]

    def apply(self):
        pass
