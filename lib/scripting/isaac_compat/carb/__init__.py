"""carb: logging through sdgbehave's logger, and Float3."""
import _sdgbehave as _native

from _isaac_compat import module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)


def log_info(message):
    _native.log("info", str(message))


def log_warn(message):
    _native.log("warning", str(message))


def log_error(message):
    _native.log("error", str(message))


def log_verbose(message):
    _native.log("debug", str(message))


class Float3(tuple):
    def __new__(cls, x=0.0, y=0.0, z=0.0):
        return super().__new__(cls, (float(x), float(y), float(z)))

    x = property(lambda self: self[0])
    y = property(lambda self: self[1])
    z = property(lambda self: self[2])
