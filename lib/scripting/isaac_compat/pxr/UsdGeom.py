"""pxr.UsdGeom: Xformable and its ops, XformCache, Imageable, the geometry schemas.

sdgbehave's stage holds every xform op in double precision: an op added with
PrecisionFloat holds doubles and reports double type names."""
from _isaac_compat import Located as _Located, module_getattr as _module_getattr, unsupported as _unsupported

from . import Gf, Sdf, Usd

__getattr__ = _module_getattr(__name__)


class Tokens:
    x, y, z = "X", "Y", "Z"
    invisible, inherited = "invisible", "inherited"
    default_, render, proxy, guide = "default", "render", "proxy", "guide"


class XformOp(_Located):
    """One op of a prim, by attribute name ("xformOp:translate")."""
    __slots__ = ("_prim", "_name", "_type")
    # Op types and precisions, as UsdGeom.XformOp's enums.
    TypeInvalid, TypeTranslate, TypeScale = "", "translate", "scale"
    TypeRotateX, TypeRotateY, TypeRotateZ = "rotateX", "rotateY", "rotateZ"
    TypeRotateXYZ, TypeRotateXZY, TypeRotateYXZ = "rotateXYZ", "rotateXZY", "rotateYXZ"
    TypeRotateYZX, TypeRotateZXY, TypeRotateZYX = "rotateYZX", "rotateZXY", "rotateZYX"
    TypeOrient, TypeTransform = "orient", "transform"
    PrecisionDouble, PrecisionFloat, PrecisionHalf = "double", "float", "half"

    def __init__(self, prim, name):
        self._prim, self._name, self._type = prim, name, None

    def __bool__(self):
        return True

    def GetOpName(self):
        return self._name

    GetName = GetOpName

    def GetOpType(self):
        return self._name.split(":")[1]

    def GetPrecision(self):
        return XformOp.PrecisionDouble

    def GetTypeName(self):
        # An op's type is its kind's (sdgbehave holds every op in doubles): asked once per op object.
        t = self._type
        if t is None:
            t = Sdf.ValueTypeNames.Find(self._prim._h.attribute_type(self._name))
            if t.native:
                self._type = t
        return t

    def GetAttr(self):
        return Usd.Attribute(self._prim, self._name)

    def Get(self, time=None):
        h = self._prim._h
        for name, value in h.xform_ops:
            if name == self._name:
                return Usd._to_gf(value, h.attribute_type(name))
        return None

    def Set(self, value, time=None):
        # A Gf vector is a list of floats, which the native call takes as it is; a quaternion its four floats.
        t = type(value)
        if t is Gf.Quatd or t is Gf.Quatf:
            value = (value._w, value._x, value._y, value._z)
        elif not isinstance(value, Gf._Vec):
            value = Usd._to_native(value)
        self._prim._h.set_xform_op(self._name, value)
        return True

    def GetOpTransform(self, time=None):
        raise _unsupported("UsdGeom.XformOp.GetOpTransform")

    def __repr__(self):
        return f"UsdGeom.XformOp({self._name!r})"


class Imageable(Usd.Typed):
    __slots__ = ()

    def MakeInvisible(self, time=None):
        self._prim._h.set_attribute("visibility", "invisible")

    def MakeVisible(self, time=None):
        self._prim._h.set_attribute("visibility", "inherited")

    def GetVisibilityAttr(self):
        return Usd.Attribute(self._prim, "visibility")


class Xformable(Imageable):
    __slots__ = ()

    @staticmethod
    def _sdg_is_a(handle):
        return handle.is_xformable

    def GetOrderedXformOps(self):
        # Scripts list the ops per prim per frame: the XformOp objects (a prim
        # and a name, nothing else) are made once and reused while the prim's
        # op names are the same; the caller gets its own list.
        prim = self._prim
        names = prim._h.xform_op_names
        cached = prim._ops
        if cached is None or cached[0] != names:
            cached = prim._ops = (names, [XformOp(prim, name) for name in names])
        return list(cached[1])

    def GetXformOpOrderAttr(self):
        return Usd.Attribute(self._prim, "xformOpOrder")

    def AddXformOp(self, op_type, precision=XformOp.PrecisionDouble, suffix="", is_inverse_op=False):
        if is_inverse_op:
            raise _unsupported("UsdGeom.Xformable.AddXformOp(isInverseOp=True)")
        name = f"xformOp:{op_type}" + (f":{suffix}" if suffix else "")
        self._prim._h.add_xform_op(name)
        return XformOp(self._prim, name)

    def AddTranslateOp(self, precision=XformOp.PrecisionDouble, opSuffix=""):
        return self.AddXformOp(XformOp.TypeTranslate, precision, opSuffix)

    def AddOrientOp(self, precision=XformOp.PrecisionFloat, opSuffix=""):
        return self.AddXformOp(XformOp.TypeOrient, precision, opSuffix)

    def AddRotateXYZOp(self, precision=XformOp.PrecisionFloat, opSuffix=""):
        return self.AddXformOp(XformOp.TypeRotateXYZ, precision, opSuffix)

    def AddScaleOp(self, precision=XformOp.PrecisionFloat, opSuffix=""):
        return self.AddXformOp(XformOp.TypeScale, precision, opSuffix)

    def AddTransformOp(self, precision=XformOp.PrecisionDouble, opSuffix=""):
        return self.AddXformOp(XformOp.TypeTransform, precision, opSuffix)

    def GetLocalTransformation(self, time=None):
        return _matrix_from_columns(self._prim._h.get_local_matrix())

    def ComputeLocalToWorldTransform(self, time=None):
        return _matrix_from_columns(self._prim._h.get_world_matrix())


def _matrix_from_columns(m):
    """sdgbehave's column-vector 4x4 (four tuples of four floats) as a Gf.Matrix4d (rows, translation
    last)."""
    a, b, c, d = m
    return Gf.Matrix4d._adopt([[float(a[0]), float(b[0]), float(c[0]), float(d[0])],
                               [float(a[1]), float(b[1]), float(c[1]), float(d[1])],
                               [float(a[2]), float(b[2]), float(c[2]), float(d[2])],
                               [float(a[3]), float(b[3]), float(c[3]), float(d[3])]])


class XformCache(_Located):
    __slots__ = ("_time",)

    def __init__(self, time=None):
        self._time = time

    def GetLocalToWorldTransform(self, prim):
        return _matrix_from_columns(prim._h.get_world_matrix())

    def GetParentToWorldTransform(self, prim):
        parent = prim.GetParent()
        return self.GetLocalToWorldTransform(parent) if parent else Gf.Matrix4d()

    def GetLocalTransformation(self, prim):
        return _matrix_from_columns(prim._h.get_local_matrix()), False

    def Clear(self):
        pass

    def SetTime(self, time):
        self._time = time


class BBoxCache(_Located):
    """World bounds of geometry: each gprim's bounds in its own frame (Cube, Sphere, ... from their
    attributes; mesh files loaded as sdgbehave loads them) under its world matrix, combined as
    Gf.BBox3d.Combine does. Purposes and visibility are not filtered: every gprim counts."""
    __slots__ = ("_time",)

    def __init__(self, time=None, includedPurposes=None, useExtentsHint=False, ignoreVisibility=False):
        self._time = time

    def ComputeWorldBound(self, prim):
        box = Gf.BBox3d()
        for p in Usd.PrimRange(prim):
            collider = p._h.collider()
            if collider is not None:
                local = collider.bounds
                box = Gf.BBox3d.Combine(box, Gf.BBox3d(Gf.Range3d(*local),
                                                       _matrix_from_columns(p._h.get_world_matrix())))
        return box

    def Clear(self):
        pass

    def SetTime(self, time):
        self._time = time


class Xform(Xformable):
    __slots__ = ()

    @staticmethod
    def _sdg_is_a(handle):
        return handle.type_name == "Xform"


class Boundable(Xformable):
    __slots__ = ()


class Gprim(Boundable):
    __slots__ = ()

    @staticmethod
    def _sdg_is_a(handle):
        return handle.is_geometry


class Camera(Xformable):
    __slots__ = ()

    @staticmethod
    def _sdg_is_a(handle):
        return handle.is_camera


def _typed(name):
    return type(name, (Gprim,), {"__slots__": (), "_sdg_is_a": staticmethod(lambda h: h.type_name == name)})


Mesh, Cube, Sphere, Cylinder, Cone, Capsule, Plane = (_typed(n) for n in
                                                      ("Mesh", "Cube", "Sphere", "Cylinder", "Cone", "Capsule",
                                                       "Plane"))


class Scope(Imageable):
    __slots__ = ()

    @staticmethod
    def _sdg_is_a(handle):
        return handle.type_name == "Scope"


def GetStageUpAxis(stage):
    return stage._s.up_axis


def GetStageMetersPerUnit(stage):
    return stage._s.meters_per_unit


def SetStageUpAxis(stage, axis):
    """Only a driver program (sdgbehave exec) sets the stage's metadata."""
    stage._s.set_metadata(up_axis=str(axis))
    return True


def SetStageMetersPerUnit(stage, meters_per_unit):
    stage._s.set_metadata(meters_per_unit=float(meters_per_unit))
    return True


class XformCommonAPI(_Located):
    """USD's common transform: translate, rotate (one three-axis op), scale, in that order, on the prim's ops.
    Pivots are not supported."""
    __slots__ = ("_prim",)

    RotationOrderXYZ, RotationOrderXZY, RotationOrderYXZ = "XYZ", "XZY", "YXZ"
    RotationOrderYZX, RotationOrderZXY, RotationOrderZYX = "YZX", "ZXY", "ZYX"
    OpTranslate, OpRotate, OpScale, OpPivot = "translate", "rotate", "scale", "pivot"

    def __init__(self, prim=None):
        self._prim = prim.GetPrim() if isinstance(prim, Usd.SchemaBase) else prim

    def __bool__(self):
        return bool(self._prim) and self._prim._h.is_xformable

    def GetPrim(self):
        return self._prim

    def _op(self, name, make):
        for op in Xformable(self._prim).GetOrderedXformOps():
            if op.GetOpName() == name:
                return op
        return make()

    def _rotate_op(self, order):
        for op in Xformable(self._prim).GetOrderedXformOps():
            if op.GetOpName().startswith("xformOp:rotate") and len(op.GetOpName()) == len("xformOp:rotateXYZ"):
                return op
        return Xformable(self._prim).AddXformOp("rotate" + order)

    def SetTranslate(self, translation, time=None):
        self._op("xformOp:translate", lambda: Xformable(self._prim).AddTranslateOp()).Set(Gf.Vec3d(translation))
        return True

    def SetRotate(self, rotation, rotOrder="XYZ", time=None):
        self._rotate_op(str(rotOrder)).Set(Gf.Vec3f(rotation))
        return True

    def SetScale(self, scale, time=None):
        self._op("xformOp:scale", lambda: Xformable(self._prim).AddScaleOp()).Set(Gf.Vec3f(scale))
        return True

    def SetXformVectors(self, translation, rotation, scale, pivot=None, rotOrder="XYZ", time=None):
        if pivot is not None and any(float(p) != 0.0 for p in pivot):
            raise _unsupported("UsdGeom.XformCommonAPI pivots")
        return self.SetTranslate(translation) and self.SetRotate(rotation, rotOrder) and self.SetScale(scale)

    def SetPivot(self, pivot, time=None):
        if any(float(p) != 0.0 for p in pivot):
            raise _unsupported("UsdGeom.XformCommonAPI pivots")
        return True

    def GetXformVectors(self, time=None):
        """(translation, rotation in degrees, scale, pivot, rotation order) from the prim's ops."""
        translation, rotation, scale, order = Gf.Vec3d(0, 0, 0), Gf.Vec3f(0, 0, 0), Gf.Vec3f(1, 1, 1), "XYZ"
        for op in Xformable(self._prim).GetOrderedXformOps():
            name = op.GetOpName()
            if name == "xformOp:translate":
                translation = Gf.Vec3d(op.Get())
            elif name == "xformOp:scale":
                scale = Gf.Vec3f(op.Get())
            elif name.startswith("xformOp:rotate") and len(name) == len("xformOp:rotateXYZ"):
                rotation, order = Gf.Vec3f(op.Get()), name[len("xformOp:rotate"):]
        return translation, rotation, scale, Gf.Vec3f(0, 0, 0), order

    GetXformVectorsByAccumulation = GetXformVectors
