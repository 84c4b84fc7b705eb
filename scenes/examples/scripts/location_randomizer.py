"""locationRandomizer, written again as a script with the documented API
only. Attached in place of the built-in (under the namespace
scriptedLocationRandomizer), it draws from the built-in's random stream
(RNG_STREAM) and writes the same values, so a dataset made with it is byte
for byte the one the built-in makes (the test suite checks this)."""
import sdgbehave


class ScriptedLocationRandomizer(sdgbehave.IntervalBehavior):
    """Moves prims to random positions within a box, optionally relative to a target prim."""

    BEHAVIOR_NS = "scriptedLocationRandomizer"
    RNG_STREAM = "locationRandomizer"
    VARIABLES_TO_EXPOSE = [
        {"attr_name": "range:minPosition", "attr_type": "vector3d", "default_value": (-1.0, -1.0, -1.0),
         "doc": "Lower bound of the random offset per axis."},
        {"attr_name": "range:maxPosition", "attr_type": "vector3d", "default_value": (1.0, 1.0, 1.0),
         "doc": "Upper bound of the random offset per axis."},
        {"attr_name": "frame:useRelativeFrame", "attr_type": "bool", "default_value": True,
         "doc": "Keep the initial position (or offset from the target) and add the random offset."},
        {"attr_name": "frame:targetPrimPath", "attr_type": "string", "default_value": "", "prim_path": True,
         "doc": "Optional prim whose world position anchors the random offset."},
        {"attr_name": "includeChildren", "attr_type": "bool", "default_value": True,
         "doc": "Also move every Xformable descendant."},
        {"attr_name": "interval", "attr_type": "uint", "default_value": 0,
         "doc": "Apply every N updates; 0 means every update."},
        {"attr_name": "seed", "attr_type": "int", "default_value": -1,
         "doc": "-1 derives the stream from the run seed; >= 0 fixes it."},
    ]

    def setup(self):
        self.low = self.get_exposed_variable("range:minPosition")
        self.high = self.get_exposed_variable("range:maxPosition")
        self.relative = self.get_exposed_variable("frame:useRelativeFrame")
        self.target = self._target()
        prims = self.stage.traverse(self.prim) if self.get_exposed_variable("includeChildren") else [self.prim]
        self.entries = []
        for prim in prims:
            if not prim.is_xformable:
                continue
            offset = None
            if self.target is not None:
                here, there = prim.get_world_location(), self.target.get_world_location()
                offset = tuple(a - b for a, b in zip(here, there))
            self.entries.append((prim, prim.get_location(), offset))

    def apply(self):
        for prim, initial, offset in self.entries:
            o = [self.rng.uniform(lo, hi) for lo, hi in zip(self.low, self.high)]
            if self.target is None:
                prim.set_location([a + b for a, b in zip(initial, o)] if self.relative else o)
                continue
            anchor = self.target.get_world_location()
            if self.relative:
                anchor = [a + b for a, b in zip(anchor, offset)]
            prim.set_world_location([a + b for a, b in zip(anchor, o)])

    def _target(self):
        path = self.get_exposed_variable("frame:targetPrimPath")
        if not path:
            return None
        prim = self.stage.get_prim(path)
        if prim is None or not prim.is_xformable:
            self.log.warn(f"invalid target prim path {path}; using no target")
            return None
        return prim
