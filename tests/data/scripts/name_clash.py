import sdgbehave


class MyLocation(sdgbehave.IntervalBehavior):
    BEHAVIOR_NS = "locationRandomizer"

    def apply(self):
        pass
