"""isaacsim.storage.native: sdgbehave has no Nucleus server. The assets root
is "" so that `get_assets_root_path() + "/Isaac/..."` stays an Isaac asset
path, which sdgbehave resolves below --isaac-assets DIR
(SDGBEHAVE_ISAAC_ASSETS, the scene's isaac_assets:) wherever a file is read."""
from _isaac_compat import module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)


def get_assets_root_path(skip_check=False):
    return ""


async def get_assets_root_path_async(skip_check=False):
    return get_assets_root_path(skip_check)
