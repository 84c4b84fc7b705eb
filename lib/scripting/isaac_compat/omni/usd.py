"""omni.usd: the stage (a behavior's while its hook runs; a driver program's
under `sdgbehave exec`), opening, creating and saving stages, free paths."""
import _isaac_compat
from _isaac_compat import Located as _Located, module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)


def _driver(what):
    return _isaac_compat.driver_for(f"omni.usd.get_context().{what}", "only a driver program (sdgbehave exec) "
                                    "opens stages; a behavior works on the stage it runs on")


class _Context(_Located):
    __slots__ = ()

    def get_stage(self):
        b = _isaac_compat.current
        if b is not None:
            return b.stage
        return _isaac_compat.driver_stage() if _isaac_compat.driver is not None else None

    def get_stage_id(self):
        return 1

    def get_stage_url(self):
        return ""

    def new_stage(self, *args, **kwargs):
        _driver("new_stage").new_stage()
        _isaac_compat.stage_changed()
        return True

    async def new_stage_async(self, *args, **kwargs):
        return self.new_stage()

    def open_stage(self, url, *args, **kwargs):
        _driver("open_stage").open_stage(str(url))
        _isaac_compat.stage_changed()
        return True

    async def open_stage_async(self, url, *args, **kwargs):
        return self.open_stage(url)

    def save_as_stage(self, url, *args, **kwargs):
        _driver("save_as_stage").save_stage(str(url))
        return True

    async def save_as_stage_async(self, url, *args, **kwargs):
        return self.save_as_stage(url), ""

    def close_stage(self, *args, **kwargs):
        return self.new_stage()

    async def close_stage_async(self, *args, **kwargs):
        return self.close_stage()


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
