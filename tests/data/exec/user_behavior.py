# A behavior written from Isaac Sim's documentation, outside any copy of
# Isaac's extension: its imports resolve to sdgbehave's layer.
from isaacsim.replicator.behavior.base_behavior import BaseBehavior
from isaacsim.replicator.behavior.global_variables import EXPOSED_ATTR_NS  # noqa: F401
from isaacsim.replicator.behavior.utils.scene_utils import set_location
from omni.kit.scripting import BehaviorScript  # noqa: F401
from pxr import Gf, Sdf


class Lift(BaseBehavior):
    BEHAVIOR_NS = "lift"
    VARIABLES_TO_EXPOSE = BaseBehavior.VARIABLES_TO_EXPOSE + [
        {"attr_name": "step", "attr_type": Sdf.ValueTypeNames.Double, "default_value": 0.25,
         "doc": "How far the prim rises each time."},
    ]

    def on_play(self):
        super().on_play()
        self._height = 0.0

    def _apply_behavior(self):
        self._height += self._get_exposed_variable("step")
        set_location(self.prim, Gf.Vec3d(0.0, 0.0, self._height))
