"""Checks the Isaac layer's scalar Generator.choice (omni/behavior/scripting/core.py) against numpy's own:
on many seeds and lists (str, bool, float; with and without p, p at the edges), the same element, of
the same numpy type, and the stream left at the same place afterwards; p that numpy refuses is refused
the same way. Run by ctest (scripts.isaac_choice_fast)."""
import numpy as np

import sdgbehave
import omni.behavior.scripting.core  # noqa: F401  (installs the layer's default_rng)


class ChoiceFastCheck(sdgbehave.Behavior):
    BEHAVIOR_NS = "choiceFastCheck"

    def on_play(self):
        lists = [["a"], ["a", "b", "c"], [f"/Isaac/t{i}.jpg" for i in range(7)], [True, False], [0.5, 1.5, 2.5]]
        ps = [None, [0.0, 1.0], [1.0, 0.0], [0.3, 0.7], [0.1, 0.9], [1e-17, 1.0 - 1e-17], [0.5, 0.5]]
        compared = 0
        for seed in range(400):
            ours = np.random.default_rng(seed)
            theirs = np.random.Generator(np.random.PCG64(seed))
            if type(ours) is np.random.Generator:
                raise RuntimeError("default_rng is not the layer's Generator")
            for k in range(20):
                items = lists[(seed + k) % len(lists)]
                p = ps[(seed * 7 + k) % len(ps)] if len(items) == 2 else None
                x, y = ours.choice(items, p=p), theirs.choice(items, p=p)
                if x != y or type(x) is not type(y):
                    raise RuntimeError(f"seed {seed} draw {k}: {x!r} ({type(x)}) vs numpy's {y!r} ({type(y)})")
                compared += 1
            if ours.random() != theirs.random():
                raise RuntimeError(f"seed {seed}: the streams part after the draws")
        for bad in ([0.5, 0.6], [-0.1, 1.1], [float("nan"), 1.0]):
            refused = []
            for g in (np.random.default_rng(0), np.random.Generator(np.random.PCG64(0))):
                try:
                    g.choice([True, False], p=bad)
                    refused.append(None)
                except ValueError as e:
                    refused.append(type(e).__name__)
            if refused[0] != refused[1] or refused[0] is None:
                raise RuntimeError(f"p={bad}: the layer {refused[0]}, numpy {refused[1]}")
        self.log.info(f"choice fast: {compared} draws compared, 0 differ")
