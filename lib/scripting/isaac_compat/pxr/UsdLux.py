"""pxr.UsdLux: not provided yet by sdgbehave's Isaac Sim layer; every name raises a
located error (see docs/isaac-scripts.md)."""
from _isaac_compat import module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)
