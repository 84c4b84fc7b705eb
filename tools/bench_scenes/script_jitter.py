"""make bench: a script behavior that moves every child of its prim (1,000
cubes in the bench) to a random offset on every update: two draws and one
write per prim, the per-frame cost issue 19 bounds at 2 ms."""
import sdgbehave


class Jitter(sdgbehave.IntervalBehavior):
    """Moves every child to a random offset from its start, every update."""
    BEHAVIOR_NS = "benchJitter"

    def setup(self):
        self.entries = [(p, p.get_location()) for p in self.prim.children]

    def apply(self):
        u = self.rng.uniform
        for prim, (x, y, z) in self.entries:
            prim.set_location((x + u(-0.1, 0.1), y + u(-0.1, 0.1), z))
