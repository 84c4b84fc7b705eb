"""breakSensor: from the second update on, sets its Lidar prim's range
backwards, a value the loader would refuse: the run must stop with a
located error rather than cast a sweep of nothing (or of garbage)."""
import sdgbehave


class BreakSensor(sdgbehave.IntervalBehavior):
    BEHAVIOR_NS = "breakSensor"
    VARIABLES_TO_EXPOSE = []

    def setup(self):
        self.updates = 0

    def apply(self):
        self.updates += 1
        if self.updates >= 2:
            self.prim.set_attribute("range", (5.0, 2.0))
