"""pxr.Usd: stages, prims, attributes and prim ranges over sdgbehave's stage.

A Usd.Prim wraps the behavior's native handle (sdgbehave.Prim): every
write goes through the behavior's journal, so sdgbehave restores it on stop.
"""
from _isaac_compat import Located as _Located, missing as _missing, module_getattr as _module_getattr, \
    unsupported as _unsupported

from . import Gf, Sdf

__getattr__ = _module_getattr(__name__)

_VEC3D = {"double3", "vector3d", "point3d"}
_VEC3F = {"float3", "color3f"}


def _to_gf(value, native_type):
    """A native value (tuples) as the Gf/Sdf type USD returns for `native_type`."""
    if value is None:
        return None
    if native_type in _VEC3D:
        return Gf.Vec3d._make(list(value))
    if native_type in _VEC3F:
        return Gf.Vec3f(value)
    if native_type == "float2":
        return Gf.Vec2f(value)
    if native_type == "double2":
        return Gf.Vec2d(value)
    if native_type == "int2":
        return Gf.Vec2i(value)
    if native_type == "quatd":
        return Gf.Quatd(*value)
    if native_type == "quatf":
        return Gf.Quatf(*value)
    if native_type == "matrix4d":
        return Gf.Matrix4d(value)
    if native_type == "asset":
        return Sdf.AssetPath(value)
    if native_type == "asset[]":
        return Sdf.AssetPathArray(value)
    return value


def _to_native(value):
    """A Gf/Sdf value as what the native API takes (tuples, rows, strings)."""
    t = type(value)
    if t is float or t is str or t is bool or t is int:
        return value
    if isinstance(value, Gf._Vec):
        return tuple(value)
    if isinstance(value, Gf._Quat):
        return value._w, value._x, value._y, value._z
    if isinstance(value, Gf.Matrix4d):
        return tuple(tuple(r) for r in value._m)
    if isinstance(value, Sdf.AssetPath):
        return value.path
    if isinstance(value, (list, tuple)) and value and isinstance(value[0], Sdf.AssetPath):
        return [a.path for a in value]
    if isinstance(value, (Sdf.Path,)):
        return value.pathString
    return value


class TimeCode(_Located):
    __slots__ = ("_t",)

    def __init__(self, t=float("nan")):
        self._t = float(t.GetValue() if isinstance(t, TimeCode) else t)

    @staticmethod
    def Default():
        return TimeCode()

    @staticmethod
    def EarliestTime():
        return TimeCode(-1.7976931348623157e308)

    def IsDefault(self):
        return self._t != self._t

    def GetValue(self):
        return self._t


class Attribute(_Located):
    """An attribute by name on a prim; falsy when the prim does not have it."""
    __slots__ = ("_prim", "_name", "_pending")

    def __init__(self, prim, name, pending=None):
        self._prim, self._name, self._pending = prim, name, pending

    def IsValid(self):
        if self._name == "xformOpOrder":  # sdgbehave keeps the order with the ops, not as an attribute
            return self._pending is not None or bool(self._prim._h.xform_op_names)
        return self._pending is not None or self._prim._h.has_attribute(self._name)

    __bool__ = IsValid

    def GetName(self):
        return self._name

    def GetBaseName(self):
        return self._name.rsplit(":", 1)[-1]

    def GetPath(self):
        return Sdf.Path(f"{self._prim._h.path}.{self._name}")

    def GetPrim(self):
        return self._prim

    def GetTypeName(self):
        native = self._prim._h.attribute_type(self._name)
        if native is None:
            return self._pending or Sdf.ValueTypeName("", "")
        return Sdf.ValueTypeNames.Find(native)

    def Get(self, time=None):
        if self._name == "xformOpOrder":
            return list(self._prim._h.xform_op_names) or None
        h = self._prim._h
        if self._name.startswith("xformOp:"):  # an op: sdgbehave keeps ops with the prim, not as attributes
            for name, value in h.xform_ops:
                if name == self._name:
                    return _to_gf(value, h.attribute_type(name))
            return None
        return _to_gf(h.get_attribute(self._name), h.attribute_type(self._name))

    def Set(self, value, time=None):
        if self._name == "xformOpOrder":
            names = list(self._prim._h.xform_op_names)
            if list(value) != names:
                raise _unsupported("Setting xformOpOrder to anything but the ops' own order",
                                   "sdgbehave orders ops as they were added")
            return True
        h = self._prim._h
        if self._name.startswith("xformOp:"):
            h.set_xform_op(self._name, _to_native(value))
            return True
        pending = self._pending  # a type to create the attribute with, unless it exists by now
        native = None if not pending or h.has_attribute(self._name) else pending.native
        h.set_attribute(self._name, _to_native(value), native)
        self._pending = None
        return True

    def HasValue(self):
        return self.IsValid()

    HasAuthoredValue = HasValue

    def SetDocumentation(self, doc):
        return True  # sdgbehave keeps the VARIABLES_TO_EXPOSE doc, shown by describe

    def GetDocumentation(self):
        return ""

    def __repr__(self):
        return f"Usd.Prim(<{self._prim._h.path}>).GetAttribute('{self._name}')"


class Prim(_Located):
    # _ops: UsdGeom.Xformable's (op names, XformOp objects), reused while the names match.
    __slots__ = ("_h", "_stage", "_hash", "_ops")

    def __init__(self, handle=None, stage=None):
        self._h, self._stage, self._hash, self._ops = handle, stage, None, None

    def IsValid(self):
        return self._h is not None and self._h.is_valid

    __bool__ = IsValid

    def __eq__(self, other):
        return isinstance(other, Prim) and self._h == other._h

    def __hash__(self):
        # Scripts key dicts by prim (per prim per frame): the path is asked once.
        h = self._hash
        if h is None:
            h = self._hash = hash(self._h.path) if self._h is not None else 0
        return h

    def __repr__(self):
        return f"Usd.Prim(<{self._h.path if self._h is not None else ''}>)"

    def _wrap(self, handle):
        return Prim(handle, self._stage) if handle is not None else Prim(None, self._stage)

    def GetPath(self):
        return Sdf.Path(self._h.path if self._h is not None else "")

    def GetPrimPath(self):
        return self.GetPath()

    def GetName(self):
        return self._h.name

    def GetTypeName(self):
        return self._h.type_name

    def GetStage(self):
        return self._stage

    def GetParent(self):
        return self._wrap(self._h.parent)

    def GetChildren(self):
        return [Prim(c, self._stage) for c in self._h.children]

    GetAllChildren = GetChildren
    GetFilteredChildren = lambda self, predicate=None: self.GetChildren()  # noqa: E731

    def IsA(self, schema):
        test = getattr(schema, "_sdg_is_a", None)
        if test is None:
            raise _missing(f"pxr.Usd.Prim.IsA({getattr(schema, '__name__', schema)})", "schema")
        return self._h is not None and test(self._h)

    def HasAPI(self, schema, *args):
        """The applied schemas sdgbehave's prims carry (UsdLux.LightAPI on lights,
        UsdShade.MaterialBindingAPI); any other answers False."""
        test = getattr(schema, "_sdg_has_api", None)
        return bool(self._h is not None and test is not None and test(self._h))

    def IsActive(self):
        return True

    def GetAttribute(self, name):
        return Attribute(self, name)

    def HasAttribute(self, name):
        return self._h.has_attribute(name) or (name == "xformOpOrder" and bool(self._h.xform_op_names))

    def CreateAttribute(self, name, type_name, custom=True, variability=None):
        if self._h.has_attribute(name):
            return Attribute(self, name)
        return Attribute(self, name, pending=type_name)

    def GetAttributes(self):
        return [Attribute(self, n) for n in self._h.attribute_names()]

    def GetPropertyNames(self):
        return list(self._h.attribute_names()) + list(self._h.xform_op_names)

    GetAuthoredPropertyNames = GetPropertyNames

    def RemoveProperty(self, name):
        return self._h.remove_attribute(str(name))

    def GetReferences(self):
        return References(self)

    def GetRelationship(self, name):
        raise _unsupported(f"Usd.Prim.GetRelationship({name!r})", "sdgbehave's stage has no relationships")


class References(_Located):
    """A prim's references, as far as sdgbehave's stage composes them: one mesh file referenced by an
    empty Xform the behavior made (Isaac's create_asset) makes that prim a Mesh prim showing the file
    (`asset` attribute), which is what sdgbehave's stage holds for a referenced mesh asset."""
    __slots__ = ("_prim",)

    def __init__(self, prim):
        self._prim = prim

    def AddReference(self, assetPath, primPath=None, layerOffset=None, position=None):
        prim = self._prim
        url = assetPath.path if isinstance(assetPath, Sdf.AssetPath) else str(assetPath)
        h = prim._h
        if primPath is not None or h.type_name != "Xform" or h.children:
            raise _unsupported(f"Usd.References.AddReference({url!r}) on {h.path} ({h.type_name})",
                               "only an empty Xform the behavior made may reference one mesh file")
        path, stage = h.path, prim._stage._s
        stage.remove_prim(path)
        mesh = stage.define_prim(path, "Mesh")
        mesh.set_attribute("asset", url, "asset")
        prim._h = mesh
        return True


class Stage(_Located):
    """The behavior's view of the stage (sdgbehave.Stage)."""
    __slots__ = ("_s", "_cache")

    def __init__(self, native):
        self._s, self._cache = native, {}

    def __bool__(self):
        return True

    def __eq__(self, other):
        return isinstance(other, Stage)

    def __hash__(self):
        return 1

    def GetPrimAtPath(self, path):
        return Prim(self._s.get_prim(str(path)), self)

    def DefinePrim(self, path, type_name="Xform"):
        path = str(path)
        existing = self._s.get_prim(path)
        if existing is not None:
            return Prim(existing, self)
        return Prim(self._s.define_prim(path, type_name or "Xform"), self)

    def RemovePrim(self, path):
        """Removes a prim this behavior created. An empty Scope another
        behavior created is left to that behavior (False), as sdgbehave removes
        every behavior's own prims on stop anyway."""
        handle = self._s.get_prim(str(path))
        if handle is None:
            return False
        try:
            self._s.remove_prim(str(path))
            from ._physics_schemas import forget
            forget(str(path))
        except ValueError as e:
            if handle.type_name == "Scope" and "was not created by" in str(e):
                return False
            raise
        return True

    def Traverse(self, *args):
        return [Prim(h, self) for h in self._s.traverse()]

    def GetPseudoRoot(self):
        raise _unsupported("Usd.Stage.GetPseudoRoot", "walk from a prim instead")

    def GetMetersPerUnit(self):
        return self._s.meters_per_unit

    def GetTimeCodesPerSecond(self):
        return self._s.time_codes_per_second


class PrimRange(_Located):
    """The prim and every descendant, pre-order."""
    __slots__ = ("_prims",)

    def __init__(self, prim, predicate=None):
        self._prims = [Prim(h, prim._stage) for h in prim._stage._s.traverse(prim._h)] if prim else []

    def __iter__(self):
        return iter(self._prims)

    @staticmethod
    def Stage(stage, predicate=None):
        return stage.Traverse()


class StageCache(_Located):
    pass


class SchemaBase(_Located):
    __slots__ = ("_prim",)

    def __init__(self, prim=None):
        self._prim = prim

    def GetPrim(self):
        return self._prim

    def GetPath(self):
        return self._prim.GetPath()

    def __bool__(self):
        return bool(self._prim) and self._sdg_is_a(self._prim._h)

    @staticmethod
    def _sdg_is_a(handle):
        return True


class Typed(SchemaBase):
    __slots__ = ()


class APISchemaBase(SchemaBase):
    __slots__ = ()
