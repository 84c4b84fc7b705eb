"""pxr.PhysicsSchemaTools: sdfPathToInt / intToSdfPath, the body ids
omni.physx's interfaces take. Ids are handed out in order of first use and
map back to the path; they are not PhysX's encoded SdfPath pointers."""
from _isaac_compat import module_getattr as _module_getattr

from . import Sdf

__getattr__ = _module_getattr(__name__)

_ids = {}
_paths = []


def sdfPathToInt(path):
    key = str(path)
    found = _ids.get(key)
    if found is None:
        found = _ids[key] = len(_paths) + 1
        _paths.append(key)
    return found


def intToSdfPath(value):
    return Sdf.Path(_paths[value - 1]) if 0 < value <= len(_paths) else Sdf.Path("")
