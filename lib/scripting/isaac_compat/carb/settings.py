"""carb.settings: an in-process dictionary of settings (nothing reads them back but scripts)."""
from _isaac_compat import module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)


class _Settings:
    def __init__(self):
        self._values = {}

    def get(self, path):
        return self._values.get(path)

    def set(self, path, value):
        self._values[path] = value

    set_bool = set_int = set_float = set_string = set


_SETTINGS = _Settings()


def get_settings():
    return _SETTINGS
