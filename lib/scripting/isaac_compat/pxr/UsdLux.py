"""pxr.UsdLux: the light schemas over sdgbehave's light prims (DistantLight,
SphereLight, RectLight, DiskLight, CylinderLight, DomeLight), whose
`inputs:*` attributes the renderer reads: a value a script sets is the light
of the next frame."""
from _isaac_compat import module_getattr as _module_getattr

from . import Usd, UsdGeom

__getattr__ = _module_getattr(__name__)

_LIGHT_INPUTS = ("intensity", "exposure", "color", "normalize", "diffuse", "specular")


def _input_getters(cls, names):
    """GetXAttr / CreateXAttr for each `inputs:x` (the attribute, by name)."""
    for name in names:
        title = "".join(part[:1].upper() + part[1:] for part in name.split(":"))
        attr = "inputs:" + name

        def get(self, _attr=attr):
            return Usd.Attribute(self._prim, _attr)

        def create(self, default_value=None, write_sparsely=False, _attr=attr):
            a = Usd.Attribute(self._prim, _attr)
            if default_value is not None:
                a.Set(default_value)
            return a

        setattr(cls, f"Get{title}Attr", get)
        setattr(cls, f"Create{title}Attr", create)
    return cls


class LightAPI(Usd.APISchemaBase):
    """Applied to every sdgbehave light prim (`prim.HasAPI(UsdLux.LightAPI)`)."""
    __slots__ = ()

    @staticmethod
    def _sdg_is_a(handle):
        return handle.is_light

    _sdg_has_api = _sdg_is_a


_input_getters(LightAPI, _LIGHT_INPUTS)


class BoundableLightBase(UsdGeom.Xformable):
    __slots__ = ()

    @staticmethod
    def _sdg_is_a(handle):
        return handle.is_light and handle.type_name != "DomeLight" and handle.type_name != "DistantLight"


class NonboundableLightBase(UsdGeom.Xformable):
    __slots__ = ()

    @staticmethod
    def _sdg_is_a(handle):
        return handle.type_name in ("DomeLight", "DistantLight")


def _light(name, base, inputs):
    cls = type(name, (base,), {"__slots__": (), "_sdg_is_a": staticmethod(lambda h: h.type_name == name)})

    def define(stage, path):
        return cls(stage.DefinePrim(path, name))

    cls.Define = staticmethod(define)
    return _input_getters(cls, _LIGHT_INPUTS + inputs)


DistantLight = _light("DistantLight", NonboundableLightBase, ("angle",))
DomeLight = _light("DomeLight", NonboundableLightBase, ("texture:file", "texture:format"))
SphereLight = _light("SphereLight", BoundableLightBase, ("radius",))
RectLight = _light("RectLight", BoundableLightBase, ("width", "height", "texture:file"))
DiskLight = _light("DiskLight", BoundableLightBase, ("radius",))
CylinderLight = _light("CylinderLight", BoundableLightBase, ("length", "radius"))
