"""carb.eventdispatcher over sdgbehave's event bus: dispatch_event publishes from
the behavior whose hook is running (delivered on the next update, as every
sdgbehave event), observe_event subscribes it (ended when it is destroyed)."""
import _isaac_compat
from _isaac_compat import module_getattr as _module_getattr

from .events import IEvent

__getattr__ = _module_getattr(__name__)


def _behavior(what):
    b = _isaac_compat.current
    if b is None and _isaac_compat.driver is not None:
        return _isaac_compat.DriverEvents()
    if b is None:
        raise RuntimeError(f"carb.eventdispatcher.{what}: called outside a behavior hook; sdgbehave's events belong "
                           f"to a behavior ({_isaac_compat.DOCS})")
    return b


def _payload(payload):
    """Payload values sdgbehave's bus carries (str, number, bool); others as their str()."""
    out = {}
    for k, v in (payload or {}).items():
        out[str(k)] = v if isinstance(v, (str, bool, int, float)) else str(v)
    return out


class _Subscription:
    def __init__(self, behavior, sid):
        self._behavior, self._sid = behavior, sid

    def reset(self):
        if self._sid is not None:
            try:
                self._behavior.unsubscribe(self._sid)
            except RuntimeError:
                pass  # the behavior is already destroyed: its subscriptions ended with it
            self._sid = None

    unsubscribe = reset


class _Dispatcher:
    def dispatch_event(self, event_name, payload=None):
        _behavior("dispatch_event").publish(str(event_name), _payload(payload))

    def observe_event(self, event_name, on_event, observer_name="", order=0, filter=None):
        behavior = _behavior("observe_event")
        name = str(event_name)

        def deliver(payload):
            previous = _isaac_compat.current
            _isaac_compat.current = None if isinstance(behavior, _isaac_compat.DriverEvents) else behavior
            try:
                on_event(IEvent(name, payload))
                _isaac_compat.run_ready()  # coroutines the callback started run now (and raise here)
            finally:
                _isaac_compat.current = previous

        return _Subscription(behavior, behavior.subscribe(name, deliver))


_DISPATCHER = _Dispatcher()


def get_eventdispatcher():
    return _DISPATCHER
