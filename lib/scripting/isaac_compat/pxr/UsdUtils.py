"""pxr.UsdUtils: the stage cache (one stage: the behavior's)."""
import _isaac_compat
from _isaac_compat import module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)


class _Id:
    def __init__(self, value):
        self._value = value

    def ToLongInt(self):
        return self._value

    def IsValid(self):
        return True


class StageCache:
    @staticmethod
    def Get():
        return _CACHE

    def GetId(self, stage):
        return _Id(1)


_CACHE = StageCache()


def _stage_of(stage_id):
    b = _isaac_compat.current
    return b.stage if b is not None else None
