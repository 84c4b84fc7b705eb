import sdgbehave


class Broken(sdgbehave.IntervalBehavior):
    BEHAVIOR_NS = "broken"
    def apply(self)
        pass
