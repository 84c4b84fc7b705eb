"""BaseBehavior: a behavior script base that exposes its VARIABLES_TO_EXPOSE
on the prim and applies itself every `interval` updates (0: every update)."""
from omni.behavior.scripting.core import BehaviorScript
from pxr import Sdf

from .global_variables import EXPOSED_ATTR_NS
from .utils.behavior_utils import (
    check_if_exposed_variables_should_be_removed,
    create_exposed_variables,
    get_exposed_variable,
    remove_exposed_variables,
)


class BaseBehavior(BehaviorScript):
    """Subclasses set BEHAVIOR_NS and VARIABLES_TO_EXPOSE and implement _apply_behavior()."""

    BEHAVIOR_NS = "baseBehavior"
    VARIABLES_TO_EXPOSE = [
        {"attr_name": "interval", "attr_type": Sdf.ValueTypeNames.UInt, "default_value": 0,
         "doc": "Interval for updating the behavior. Value 0 means every frame."},
    ]

    def on_init(self):
        self._update_counter = 0
        self._interval = 0
        create_exposed_variables(self.prim, EXPOSED_ATTR_NS, self.BEHAVIOR_NS, self.VARIABLES_TO_EXPOSE)

    def on_destroy(self):
        if check_if_exposed_variables_should_be_removed(self.prim, __file__):
            remove_exposed_variables(self.prim, EXPOSED_ATTR_NS, self.BEHAVIOR_NS, self.VARIABLES_TO_EXPOSE)

    def on_play(self):
        self._interval = self._get_exposed_variable("interval")

    def on_stop(self):
        self._interval = 0
        self._update_counter = 0

    def on_update(self, current_time, delta_time):
        if delta_time <= 0:
            return
        if self._interval <= 0:
            self._apply_behavior()
            return
        self._update_counter += 1
        if self._update_counter >= self._interval:
            self._apply_behavior()
            self._update_counter = 0

    def _apply_behavior(self):
        raise NotImplementedError(f"{type(self).__name__} must implement _apply_behavior()")

    def _get_exposed_variable(self, attr_name):
        return get_exposed_variable(self.prim, f"{EXPOSED_ATTR_NS}:{self.BEHAVIOR_NS}:{attr_name}")
