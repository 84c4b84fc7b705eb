"""Scripts that talk through events: one answers the scene's pre-roll, one
publishes on every apply, one listens and writes what it heard. On stop,
the pinger logs (debug) the last current_time it saw and the listener how many
pings it heard (the last one is delivered when the timeline stops)."""
import sdgbehave


class Responder(sdgbehave.Behavior):
    """Answers test.responder.in {action: count} with the number of requests."""

    BEHAVIOR_NS = "responder"

    def on_init(self):
        self.requests = 0
        self.subscribe("test.responder.in", self.on_request)

    def on_request(self, payload):
        if payload.get("action") != "count":
            return
        self.requests += 1
        self.prim.set_attribute("user:requests", self.requests, type="int")
        self.publish("test.responder.out", {"prim_path": self.prim_path, "state_name": "COUNTED",
                                            "count": self.requests})


class Pinger(sdgbehave.IntervalBehavior):
    """Publishes test.ping {n} on every apply."""

    BEHAVIOR_NS = "pinger"

    def setup(self):
        self.sent = 0

    def apply(self):
        self.sent += 1
        self.publish("test.ping", {"n": self.sent, "from": self.prim_path})

    def on_update(self, current_time, delta_time):
        self.last_time = current_time
        super().on_update(current_time, delta_time)

    def on_stop(self):
        self.log.debug(f"sent {self.sent} pings; the last current_time was {self.last_time!r}")
        super().on_stop()


class Listener(sdgbehave.Behavior):
    """Writes the last ping it heard into user:lastPing."""

    BEHAVIOR_NS = "listener"

    def on_init(self):
        self.heard = []
        self.subscribe("test.ping", self.on_ping)

    def on_ping(self, payload):
        self.heard.append(int(payload["n"]))
        self.prim.set_attribute("user:lastPing", int(payload["n"]), type="int")

    def on_stop(self):
        self.log.debug(f"heard {len(self.heard)} pings, the last {self.heard[-1] if self.heard else None}")
