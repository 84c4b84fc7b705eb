"""lookAtBehavior, written again as a script with the documented API only:
keeps prims aimed (local -Z) at a world point or a prim, +Y toward an up
axis. Same rotations as the built-in, bit for bit."""
import sdgbehave


class ScriptedLookAt(sdgbehave.IntervalBehavior):
    """Keeps prims aimed (local -Z) at a world point or at a prim, with +Y toward an up axis."""

    BEHAVIOR_NS = "scriptedLookAtBehavior"
    VARIABLES_TO_EXPOSE = [
        {"attr_name": "targetLocation", "attr_type": "vector3d", "default_value": (0.0, 0.0, 0.0),
         "doc": "World point to look at."},
        {"attr_name": "targetPrimPath", "attr_type": "string", "default_value": "", "prim_path": True,
         "doc": "Prim to look at; when set it wins over targetLocation."},
        {"attr_name": "upAxis", "attr_type": "vector3d", "default_value": (0.0, 0.0, 1.0),
         "doc": "World up direction for the view."},
        {"attr_name": "includeChildren", "attr_type": "bool", "default_value": True,
         "doc": "Aim every Xformable descendant too (each independently)."},
    ]

    def setup(self):
        self.location = self.get_exposed_variable("targetLocation")
        self.up = self.get_exposed_variable("upAxis")
        path = self.get_exposed_variable("targetPrimPath")
        self.target = self.stage.get_prim(path) if path else None
        if path and (self.target is None or not self.target.is_xformable):
            self.log.warn(f"invalid target prim path {path}; using targetLocation")
            self.target = None
        prims = self.stage.traverse(self.prim) if self.get_exposed_variable("includeChildren") else [self.prim]
        self.prims = [p for p in prims if p.is_xformable]

    def apply(self):
        target = self.target.get_world_location() if self.target is not None else self.location
        for prim in self.prims:
            rotation = sdgbehave.look_at_rotation(prim.get_world_location(), target, self.up)
            if rotation is not None:  # None: standing on the target, keep the current aim
                prim.set_world_rotation(rotation)
