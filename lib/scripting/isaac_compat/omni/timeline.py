"""omni.timeline: the timeline sdgbehave plays. A behavior reads it; a
driver program (sdgbehave exec) also plays, pauses and stops it."""
import _isaac_compat
from _isaac_compat import Located as _Located, module_getattr as _module_getattr, unsupported as _unsupported

__getattr__ = _module_getattr(__name__)


class _Timeline(_Located):
    __slots__ = ()

    def _driver(self, what):
        return _isaac_compat.driver_for(f"omni.timeline {what}()", "sdgbehave drives the timeline itself; a "
                                        "driver program (sdgbehave exec) may play, pause and stop it")

    def get_current_time(self):
        d = _isaac_compat.driver
        if d is not None:
            return d.time
        token = _isaac_compat._last_update
        return token if token is not None else 0.0

    def is_playing(self):
        d = _isaac_compat.driver
        if d is not None:
            return d.playing
        return _isaac_compat.current is not None and _isaac_compat.current._ctx is not None

    def is_stopped(self):
        d = _isaac_compat.driver
        return not d.playing and d.time == 0.0 if d is not None else False

    def get_time_codes_per_seconds(self):
        d = _isaac_compat.driver
        if d is not None and _isaac_compat.current is None:
            return d.time_codes_per_second
        b = _isaac_compat.current
        return b.stage.GetTimeCodesPerSecond() if b is not None else 60.0

    def play(self, *args, **kwargs):
        self._driver("play").play()

    def pause(self):
        self._driver("pause").pause()

    def stop(self):
        self._driver("stop").stop()

    def commit(self):
        """Applies play/pause/stop at once: they already are, here."""
        self._driver("commit")

    commit_silently = commit

    def set_current_time(self, time):
        d = self._driver("set_current_time")
        if float(time) != d.time:
            raise _unsupported(f"omni.timeline set_current_time({time})", "sdgbehave's timeline advances one "
                               "update at a time from 0 (await next_update_async())")

    def forward_one_frame(self):
        raise _unsupported("omni.timeline forward_one_frame()", "await omni.kit.app.get_app().next_update_async()")


_TIMELINE = _Timeline()


def get_timeline_interface():
    return _TIMELINE
