"""isaacsim.storage.native: sdgbehave has no Nucleus assets root (None, as Isaac Sim
returns when it finds none); give assets by path in the scene instead."""
import carb
from _isaac_compat import module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)


def get_assets_root_path(skip_check=False):
    carb.log_warn("isaacsim.storage.native: sdgbehave has no Isaac Sim assets root; returning None")
    return None


async def get_assets_root_path_async(skip_check=False):
    return get_assets_root_path(skip_check)
