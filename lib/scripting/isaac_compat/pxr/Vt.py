"""pxr.Vt: arrays (plain lists here)."""
from _isaac_compat import module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)


class _Array(list):
    pass


class Vec3fArray(_Array):
    pass


class Vec3dArray(_Array):
    pass


class TokenArray(_Array):
    pass


class StringArray(_Array):
    pass


class IntArray(_Array):
    pass


class FloatArray(_Array):
    pass
