"""steadyMotion: moves its prim by a fixed step and turns it by a fixed
angle about world Z on every update, so a test knows exactly where
everything is in each frame (check_flow.py)."""
import math

import sdgbehave


class SteadyMotion(sdgbehave.Behavior):
    BEHAVIOR_NS = "steadyMotion"
    VARIABLES_TO_EXPOSE = [
        {"attr_name": "step", "attr_type": "vector3d", "default_value": (0.0, 0.0, 0.0),
         "doc": "Added to the prim's location on every update."},
        {"attr_name": "turn", "attr_type": "float", "default_value": 0.0,
         "doc": "Degrees about world Z added to the prim's rotation on every update."},
    ]

    def on_update(self, current_time, delta_time):
        x, y, z = self.prim.get_location()
        dx, dy, dz = self.get_exposed_variable("step")
        self.prim.set_location((x + dx, y + dy, z + dz))
        a = math.radians(self.get_exposed_variable("turn"))
        if a:
            c, s = math.cos(a), math.sin(a)
            r = self.prim.get_rotation()
            turn = ((c, -s, 0.0), (s, c, 0.0), (0.0, 0.0, 1.0))
            self.prim.set_rotation(tuple(tuple(sum(turn[i][k] * r[k][j] for k in range(3)) for j in range(3))
                                         for i in range(3)))
