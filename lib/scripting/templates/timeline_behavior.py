"""{{NAME}}: a behavior script made by `sdgbehave new-behavior {{NAME}}`.

It gives the prim it is attached to (and, with includeChildren, every
geometry prim below it) a random uniform scale between minScale and
maxScale, every `interval` updates. Edit apply() to make it do what you
need; docs/scripting.md lists every call of the API.

Attach it in a scene:

    scripts: [{{FILE}}]
    prims:
      /World/Box:
        type: Cube
        behaviors:
          {{NAME}}: {interval: 2, minScale: 0.5, maxScale: 1.5}
"""
import sdgbehave


class {{CLASS}}(sdgbehave.IntervalBehavior):
    """Gives prims a random uniform scale."""  # the summary `sdgbehave describe` shows

    BEHAVIOR_NS = "{{NAME}}"
    # Each record becomes the attribute exposedVar:{{NAME}}:<attr_name> on the
    # prim, with a default, checked by the loader and settable with --set.
    # IntervalBehavior adds `interval` (uint, 0 = every update) by itself.
    VARIABLES_TO_EXPOSE = [
        {"attr_name": "minScale", "attr_type": "double", "default_value": 0.5, "minimum": 0.0,
         "doc": "Smallest scale factor."},
        {"attr_name": "maxScale", "attr_type": "double", "default_value": 1.5, "minimum": 0.0,
         "doc": "Largest scale factor."},
        {"attr_name": "includeChildren", "attr_type": "bool", "default_value": True,
         "doc": "Also scale every geometry prim below the attached prim."},
    ]

    def setup(self):
        # Called when the timeline starts playing: read the variables once.
        self.low = self.get_exposed_variable("minScale")
        self.high = self.get_exposed_variable("maxScale")
        if self.get_exposed_variable("includeChildren"):
            self.prims = [p for p in self.stage.traverse(self.prim) if p.is_geometry]
        else:
            self.prims = [self.prim]

    def apply(self):
        # Called as `interval` says. Draw only from self.rng: it makes the
        # same numbers for the same seed on every machine, thread count and
        # shard. sdgbehave undoes every change on stop; no restore code needed.
        for prim in self.prims:
            s = self.rng.uniform(self.low, self.high)
            prim.set_scale((s, s, s))
