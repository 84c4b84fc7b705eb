import sdgbehave


class Broken(sdgbehave.Behavior):
    BEHAVIOR_NS = "broken"
    raise ValueError("broken at load")
