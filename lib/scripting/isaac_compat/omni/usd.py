"""omni.usd: the stage of the behavior whose hook runs, and free paths."""
import _isaac_compat
from _isaac_compat import Located as _Located, module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)


class _Context(_Located):
    __slots__ = ()

    def get_stage(self):
        b = _isaac_compat.current
        return b.stage if b is not None else None

    def get_stage_id(self):
        return 1


_CONTEXT = _Context()


def get_context(name=""):
    return _CONTEXT


def get_stage_next_free_path(stage, path, prepend_default_prim=False):
    return stage._s.next_free_path(str(path))


def get_shader_from_material(material, get_prim=False):
    """The material's shader: sdgbehave's Material prim holds its shader's
    inputs itself, so the shader is the Material prim (pxr/UsdShade.py)."""
    from pxr import Usd, UsdShade
    prim = material.GetPrim() if isinstance(material, UsdShade.Material) else material
    if not isinstance(prim, Usd.Prim) or not prim or prim.GetTypeName() != "Material":
        return None
    return prim if get_prim else UsdShade.Shader(prim)
