"""Draws from every source a script might use: self.rng (the supported
one), Python's random and numpy's global generator (seeded by sdgbehave per
iteration), and iterates a set of strings (hash seed fixed)."""
import random

import numpy
import sdgbehave


class Jitter(sdgbehave.IntervalBehavior):
    BEHAVIOR_NS = "jitter"
    VARIABLES_TO_EXPOSE = [
        {"attr_name": "amount", "attr_type": "double", "default_value": 0.3, "doc": "Largest offset per axis."},
    ]

    def setup(self):
        self.amount = self.get_exposed_variable("amount")
        self.start = self.prim.get_location()
        self.order = "".join(sorted({"b", "a", "c"}, key=lambda s: hash(s) % 7))

    def apply(self):
        a = self.amount
        x = self.rng.uniform(-a, a)
        y = random.uniform(-a, a)
        z = float(numpy.random.uniform(0, a))
        self.prim.set_location((self.start[0] + x, self.start[1] + y, self.start[2] + z))
        self.prim.set_attribute("user:order", self.order, type="string")
