"""Moves its prim up and down by a random amount within +-amplitude."""
import sdgbehave


class Bob(sdgbehave.IntervalBehavior):
    BEHAVIOR_NS = "bob"
    VARIABLES_TO_EXPOSE = [
        {"attr_name": "amplitude", "attr_type": "double", "default_value": 0.2, "doc": "Largest vertical offset."},
    ]

    def setup(self):
        self.start = self.prim.get_location()
        self.amplitude = self.get_exposed_variable("amplitude")

    def apply(self):
        x, y, z = self.start
        self.prim.set_location((x, y, z + self.rng.uniform(-self.amplitude, self.amplitude)))
