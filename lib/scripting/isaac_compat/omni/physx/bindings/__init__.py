"""omni.physx.bindings: the setting names of omni.physx (see omni/physx/__init__.py)."""
from _isaac_compat import module_getattr as _module_getattr

from . import _physx  # noqa: F401

__getattr__ = _module_getattr(__name__)
