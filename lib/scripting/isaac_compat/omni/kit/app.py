"""omni.kit.app: next_update_async() resumes on the next update (pre-roll updates included)."""
import _isaac_compat
from _isaac_compat import Located as _Located, module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)


class _App(_Located):
    __slots__ = ()

    def next_update_async(self):
        return _isaac_compat.next_update()

    def is_running(self):
        return True


_APP = _App()


def get_app():
    return _APP


get_app_interface = get_app
