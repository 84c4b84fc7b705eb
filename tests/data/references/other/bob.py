"""Another script that claims the name bob."""
import sdgbehave


class OtherBob(sdgbehave.IntervalBehavior):
    BEHAVIOR_NS = "bob"

    def apply(self):
        pass
