"""carb.events: the event object observers receive."""
from _isaac_compat import module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)


class IEvent:
    """An event from sdgbehave's bus: its name (event_name, type) and payload dict."""

    def __init__(self, name, payload):
        self.event_name = name
        self.type = name
        self.payload = payload


def type_from_string(name):
    return name
