"""pxr.UsdShade: materials, their shader inputs and the binding API over
sdgbehave's Material prims.

sdgbehave's Material prim holds its OmniPBR shader's inputs itself
(`inputs:diffuse_texture`, `inputs:texture_scale`, ...), which the renderer
reads: `UsdShade.Shader` of a material (what omni.usd.get_shader_from_material
returns) is the Material prim, and a value set on one of its inputs is the
surface of the next frame. A texture file set on an input must exist where
the scene resolves assets (its folder, asset roots, --isaac-assets for
/Isaac/... paths): a missing file is an error naming it."""
from _isaac_compat import Located as _Located, module_getattr as _module_getattr, unsupported as _unsupported

from . import Sdf, Usd

__getattr__ = _module_getattr(__name__)


class Tokens:
    strongerThanDescendants = "strongerThanDescendants"
    weakerThanDescendants = "weakerThanDescendants"
    allPurpose = ""
    full, preview, physics = "full", "preview", "physics"
    surface = "surface"


class Input(_Located):
    """`inputs:<name>` of a shader (a Material prim here)."""
    __slots__ = ("_attr",)

    def __init__(self, attr):
        self._attr = attr

    def __bool__(self):
        return bool(self._attr)

    def GetAttr(self):
        return self._attr

    def GetBaseName(self):
        return self._attr.GetName()[len("inputs:"):]

    GetFullName = lambda self: self._attr.GetName()  # noqa: E731

    def GetTypeName(self):
        return self._attr.GetTypeName()

    def Get(self, time=None):
        return self._attr.Get(time)

    def Set(self, value, time=None):
        # Only a path is checked (per prim per frame, most values are numbers): is the input a file?
        if isinstance(value, (str, Sdf.AssetPath)) and \
                self._attr._prim._h.attribute_type(self._attr.GetName()) in ("asset", None):
            value = _resolved_file(self._attr, value.path if isinstance(value, Sdf.AssetPath) else str(value))
        return self._attr.Set(value, time)


def _resolved_file(attr, path):
    """`path` as given (the renderer resolves it as the built-ins' files), once it is known to exist.
    Scripts set a texture per prim per frame: a path found once is not looked up again by this stage."""
    if not path:
        return path
    stage = attr._prim._stage
    found = stage._cache.get("files")
    if found is None:
        found = stage._cache["files"] = set()
    if path in found:
        return path
    if stage._s.resolve_asset(path) is None:
        raise _unsupported(f"UsdShade.Input.Set({path!r}) on {attr._prim._h.path}.{attr.GetName()}",
                           "the file does not exist below the scene's folder, its asset roots or --isaac-assets")
    found.add(path)
    return path


class Shader(Usd.Typed):
    __slots__ = ()

    @staticmethod
    def _sdg_is_a(handle):
        return handle.type_name == "Material"

    def GetInput(self, name):
        return Input(Usd.Attribute(self._prim, "inputs:" + name))

    def CreateInput(self, name, type_name):
        return Input(self._prim.CreateAttribute("inputs:" + name, type_name))

    def GetInputs(self, onlyAuthored=True):
        return [Input(a) for a in self._prim.GetAttributes() if a.GetName().startswith("inputs:")]

    def GetIdAttr(self):
        return Usd.Attribute(self._prim, "info:id")


class Material(Usd.Typed):
    __slots__ = ()

    @staticmethod
    def _sdg_is_a(handle):
        return handle.type_name == "Material"

    @staticmethod
    def Define(stage, path):
        return Material(stage.DefinePrim(path, "Material"))

    @staticmethod
    def Get(stage, path):
        return Material(stage.GetPrimAtPath(path))

    def GetInput(self, name):
        return Input(Usd.Attribute(self._prim, "inputs:" + name))

    def CreateInput(self, name, type_name):
        return Input(self._prim.CreateAttribute("inputs:" + name, type_name))


class MaterialBindingAPI(Usd.APISchemaBase):
    """A prim's material binding (one per prim: sdgbehave has no purposes)."""
    __slots__ = ()

    @staticmethod
    def _sdg_is_a(handle):
        return True

    _sdg_has_api = staticmethod(lambda handle: handle.material_path is not None)

    @staticmethod
    def Apply(prim):
        return MaterialBindingAPI(prim)

    def Bind(self, material, bindingStrength=Tokens.weakerThanDescendants, materialPurpose=Tokens.allPurpose):
        if materialPurpose == Tokens.physics:
            # The physics binding only feeds the simulation (friction, restitution): the layer keeps it.
            from ._physics_schemas import bind_physics_material
            bind_physics_material(self._prim, material.GetPath())
            return True
        if materialPurpose not in (Tokens.allPurpose, Tokens.full, Tokens.preview):
            raise _unsupported(f"UsdShade.MaterialBindingAPI.Bind(materialPurpose={materialPurpose!r})",
                               "sdgbehave binds one material per prim, for rendering")
        self._prim._h.bind_material(str(material.GetPath()), bindingStrength or Tokens.weakerThanDescendants)
        return True

    def UnbindAllBindings(self):
        if self._prim._h.material_path is not None:
            self._prim._h.unbind_material()
        return True

    UnbindDirectBinding = UnbindAllBindings

    def GetDirectBinding(self, materialPurpose=Tokens.allPurpose):
        return _DirectBinding(self._prim)

    def ComputeBoundMaterial(self, materialPurpose=Tokens.allPurpose, *args):
        """(material, None) as USD resolves it: the closest binding, unless an
        ancestor binds strongerThanDescendants (the outermost such wins)."""
        closest = strongest = None
        p = self._prim
        while p:
            h = p._h
            path = h.material_path
            if path is not None:
                target = p._stage.GetPrimAtPath(path)
                if target and target.GetTypeName() == "Material":
                    if closest is None:
                        closest = target
                    if p is not self._prim and h.material_strength == Tokens.strongerThanDescendants:
                        strongest = target
            parent = h.parent
            p = Usd.Prim(parent, p._stage) if parent is not None else None
        found = strongest or closest
        return Material(found if found is not None else Usd.Prim(None, self._prim._stage)), None


class _DirectBinding(_Located):
    __slots__ = ("_prim",)

    def __init__(self, prim):
        self._prim = prim

    def GetMaterialPath(self):
        return Sdf.Path(self._prim._h.material_path or "")

    def GetMaterial(self):
        return Material.Get(self._prim._stage, self.GetMaterialPath())
