"""isaacsim.storage.native: sdgbehave has no Nucleus server.

In a driver program (sdgbehave exec) the assets root is a folder holding
Isaac/: --assets-root, else $SDGBEHAVE_ASSETS_ROOT, else the stand-in root
sdgbehave ships (docs/isaac-scripts.md). In a behavior it is "", so that
`get_assets_root_path() + "/Isaac/..."` stays an Isaac asset path, which
sdgbehave resolves below --isaac-assets DIR (SDGBEHAVE_ISAAC_ASSETS, the
scene's isaac_assets:) wherever a file is read."""
import _isaac_compat
from _isaac_compat import module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)


def get_assets_root_path(skip_check=False):
    d = _isaac_compat.driver
    return d.assets_root if d is not None and _isaac_compat.current is None else ""


async def get_assets_root_path_async(skip_check=False):
    return get_assets_root_path(skip_check)
