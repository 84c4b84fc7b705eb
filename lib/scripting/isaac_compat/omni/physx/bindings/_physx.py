"""omni.physx.bindings._physx: the setting names Isaac's scene_utils uses."""
from _isaac_compat import module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)

# Whether stopping the timeline puts back what the simulation moved (carb.settings path).
SETTING_RESET_ON_STOP = "/physics/resetOnStop"
