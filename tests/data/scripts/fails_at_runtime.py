"""Raises on its third apply, to test how a failing script stops a run."""
import sdgbehave


class FailsLater(sdgbehave.IntervalBehavior):
    BEHAVIOR_NS = "failsLater"
    VARIABLES_TO_EXPOSE = [
        {"attr_name": "failAt", "attr_type": "uint", "default_value": 3, "doc": "The apply that raises."},
    ]

    def setup(self):
        self.applies = 0

    def apply(self):
        self.applies += 1
        self.prim.set_location((0.0, 0.0, 0.1 * self.applies))
        if self.applies == self.get_exposed_variable("failAt"):
            raise ValueError(f"apply number {self.applies} fails on purpose")
