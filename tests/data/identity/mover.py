"""Moves its prim by a step that a helper module beside it computes, and
fails on purpose where SDG_TEST_FAIL asks (frame N, or "stop" for on_stop),
so that check_run_identity.py can fail a run and resume it."""
import os

import sdgbehave
from step_size import step


class Mover(sdgbehave.Behavior):
    BEHAVIOR_NS = "mover"
    VARIABLES_TO_EXPOSE = []

    def on_init(self):
        self.frames = 0

    def on_update(self, current_time, delta_time):
        if os.environ.get("SDG_TEST_FAIL") == str(self.frames):
            raise RuntimeError(f"failing at update {self.frames} on purpose")
        self.frames += 1
        x, y, z = self.prim.get_location()
        self.prim.set_location((x + step(self.rng), y, z))

    def on_stop(self):
        if os.environ.get("SDG_TEST_FAIL") == "stop":
            raise RuntimeError("failing in on_stop on purpose")
