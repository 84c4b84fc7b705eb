"""{{NAME}}: an event-driven behavior script made by
`sdgbehave new-behavior {{NAME}} --events`.

It listens on the event {{NAME}}.in for {"action": "place"} (addressed to
one prim with "prim_path", or to all), places its prim at a random height
between minHeight and maxHeight, and answers on {{NAME}}.out with
{"prim_path": ..., "state_name": "PLACED"}. A scene's `events:` pre-roll can
publish the action and wait for the answer:

    scripts: [{{FILE}}]
    events:
      - {publish: {{NAME}}.in, payload: {action: place}, wait_for: {state_name: PLACED}, max_updates: 10}
    prims:
      /World/Box:
        type: Cube
        behaviors:
          {{NAME}}: {minHeight: 0.5, maxHeight: 2.0}
"""
import sdgbehave

EVENT_IN = "{{NAME}}.in"
EVENT_OUT = "{{NAME}}.out"


class {{CLASS}}(sdgbehave.Behavior):
    """Places its prim at a random height when asked by an event."""

    BEHAVIOR_NS = "{{NAME}}"
    VARIABLES_TO_EXPOSE = [
        {"attr_name": "minHeight", "attr_type": "double", "default_value": 0.5, "doc": "Lowest height."},
        {"attr_name": "maxHeight", "attr_type": "double", "default_value": 2.0, "doc": "Highest height."},
    ]

    def on_init(self):
        # Subscriptions end by themselves when the behavior is destroyed.
        self.subscribe(EVENT_IN, self.on_event)

    def on_event(self, payload):
        target = payload.get("prim_path", "")
        if target and target != self.prim_path:
            return  # addressed to another prim
        if payload.get("action") == "place":
            x, y, _ = self.prim.get_location()
            z = self.rng.uniform(self.get_exposed_variable("minHeight"), self.get_exposed_variable("maxHeight"))
            self.prim.set_location((x, y, z))
            self.publish(EVENT_OUT, {"prim_path": self.prim_path, "state_name": "PLACED"})
