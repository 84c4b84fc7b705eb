"""omni.timeline: the timeline sdgbehave plays (read-only)."""
import _isaac_compat
from _isaac_compat import Located as _Located, module_getattr as _module_getattr, unsupported as _unsupported

__getattr__ = _module_getattr(__name__)


class _Timeline(_Located):
    __slots__ = ()

    def get_current_time(self):
        token = _isaac_compat._last_update
        return token if token is not None else 0.0

    def is_playing(self):
        return _isaac_compat.current is not None and _isaac_compat.current._ctx is not None

    def get_time_codes_per_seconds(self):
        b = _isaac_compat.current
        return b.stage.GetTimeCodesPerSecond() if b is not None else 60.0

    def play(self):
        raise _unsupported("omni.timeline play()", "sdgbehave drives the timeline itself")

    stop = pause = play


_TIMELINE = _Timeline()


def get_timeline_interface():
    return _TIMELINE
