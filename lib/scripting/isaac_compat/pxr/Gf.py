"""pxr.Gf: vectors, quaternions, rotations, matrices and ranges with USD's
conventions (row vectors: p' = p * M, translation in the last row;
Rotation(a) * Rotation(b) applies a first, then b)."""
import math as _math
import struct as _struct
from math import acos as _acos, atan2 as _atan2, cos as _cos, degrees as _degrees, radians as _radians, \
    sin as _sin, sqrt as _sqrt

from _isaac_compat import Located as _Located, module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)

# Rotation arithmetic in C++ (script_api.cpp, gf_fast), bit-identical to the Python below, which computes
# whatever they answer None to (and everything outside sdgbehave's interpreter).
try:
    from _sdgbehave import gf_decompose as _n_decompose, gf_look_at as _n_look_at, gf_product as _n_product, \
        gf_quat as _n_quat, gf_rotation_of as _n_rotation_of
except ImportError:
    _n_decompose = _n_look_at = _n_product = _n_quat = _n_rotation_of = None
_NATIVE = (_n_decompose, _n_look_at, _n_product, _n_quat, _n_rotation_of)


def _use_native(on):
    """Switches the C++ paths on or off (tests compare the two)."""
    global _n_decompose, _n_look_at, _n_product, _n_quat, _n_rotation_of
    _n_decompose, _n_look_at, _n_product, _n_quat, _n_rotation_of = _NATIVE if on else (None,) * 5

_F32 = _struct.Struct("f")
_F32X3 = _struct.Struct("3f")  # three at once, rounded as _f32 rounds each
_new_object = object.__new__


def _f32(x):
    return _F32.unpack(_F32.pack(x))[0]


class _Vec(list, _Located):
    """N components, float32-rounded when _round (the f types). A list
    underneath: indexing and iteration run at C speed (scripts index vectors
    per prim per frame); `_v` is the vector itself."""
    __slots__ = ()
    _round = None
    _N = 3

    def __init__(self, *args):
        n = self._N
        if len(args) == n and not self._round:  # Vec3d(x, y, z): the common case, per prim per frame
            list.__init__(self, [float(x) for x in args])
            return
        if not args:
            v = [0.0] * n
        elif len(args) == 1 and not isinstance(args[0], (int, float)):
            v = [float(x) for x in args[0]]
        elif len(args) == 1:
            v = [float(args[0])] * n
        else:
            v = [float(x) for x in args]
        if len(v) != n:
            raise TypeError(f"{type(self).__name__} takes {n} components, found {len(v)}")
        list.__init__(self, [_f32(x) for x in v] if self._round else v)

    @classmethod
    def _make(cls, v):
        o = list.__new__(cls)
        list.extend(o, [_f32(x) for x in v] if cls._round else v)
        return o

    @property
    def _v(self):
        return self

    def _convert(self, x):
        return _f32(x) if self._round else float(x)

    def __setitem__(self, i, x):
        if isinstance(i, slice):
            list.__setitem__(self, i, [self._convert(y) for y in x])
        else:
            list.__setitem__(self, i, self._convert(x))

    # Vector arithmetic, never the list's concatenation or repetition.
    def __add__(self, o):
        return self._make([a + b for a, b in zip(self, o)])

    __radd__ = __iadd__ = __add__

    def __sub__(self, o):
        return self._make([a - b for a, b in zip(self, o)])

    __isub__ = __sub__

    def __rsub__(self, o):
        return self._make([b - a for a, b in zip(self, o)])

    def __neg__(self):
        return self._make([-x for x in self])

    def __mul__(self, o):
        if isinstance(o, _Vec):  # USD: vec * vec is the dot product
            return sum(a * b for a, b in zip(self, o))
        return self._make([x * o for x in self])

    __imul__ = __mul__

    def __rmul__(self, o):
        return self._make([x * o for x in self])

    def __truediv__(self, o):
        return self._make([x / o for x in self])

    __itruediv__ = __truediv__

    def __eq__(self, o):
        try:
            return len(o) == self._N and all(a == b for a, b in zip(self, o))
        except TypeError:
            return False

    def __ne__(self, o):
        return not self.__eq__(o)

    __hash__ = None

    def __repr__(self):
        return f"Gf.{type(self).__name__}({', '.join(repr(x) for x in self)})"


_new_list, _extend_list = list.__new__, list.extend


class _Vec3(_Vec):
    __slots__ = ()

    # Unrolled, with no comprehension or classmethod call on the double types:
    # the hot ones (built from three draws, a location plus an offset, per
    # prim per frame).
    def __init__(self, *args):
        if len(args) == 3:
            x, y, z = args
            if self._round is None:
                list.__init__(self, (float(x), float(y), float(z)))
            else:
                list.__init__(self, _F32X3.unpack(_F32X3.pack(float(x), float(y), float(z))))
        else:
            _Vec.__init__(self, *args)

    def __add__(self, o):
        if self._round:
            return self._make([self[0] + o[0], self[1] + o[1], self[2] + o[2]])
        r = _new_list(type(self))
        _extend_list(r, (self[0] + o[0], self[1] + o[1], self[2] + o[2]))
        return r

    __radd__ = __iadd__ = __add__

    def __sub__(self, o):
        if self._round:
            return self._make([self[0] - o[0], self[1] - o[1], self[2] - o[2]])
        r = _new_list(type(self))
        _extend_list(r, (self[0] - o[0], self[1] - o[1], self[2] - o[2]))
        return r

    __isub__ = __sub__

    def GetDot(self, o):
        return self[0] * o[0] + self[1] * o[1] + self[2] * o[2]

    def GetLength(self):
        return _math.sqrt(self.GetDot(self))

    def GetNormalized(self, eps=1e-10):
        n = self.GetLength()
        return self._make([x / n for x in self]) if n > eps else self._make([x / eps for x in self])

    def Normalize(self, eps=1e-10):
        n = self.GetLength()
        self[:] = self.GetNormalized(eps)
        return n

    def GetCross(self, o):
        a, b = self, o
        return self._make([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])

    def GetProjection(self, o):
        return o * (self.GetDot(o))

    @classmethod
    def XAxis(cls):
        return cls(1.0, 0.0, 0.0)

    @classmethod
    def YAxis(cls):
        return cls(0.0, 1.0, 0.0)

    @classmethod
    def ZAxis(cls):
        return cls(0.0, 0.0, 1.0)


class Vec3d(_Vec3):
    __slots__ = ()


class Vec3f(_Vec3):
    __slots__ = ()
    _round = True


class _Vec2(_Vec):
    """Two components (ranges such as a light's intensity (min, max))."""
    __slots__ = ()
    _N = 2


class Vec2i(_Vec2):
    """Integer pairs (a count range such as the volume stack's assets:numRange)."""
    __slots__ = ()

    def __init__(self, *args):
        super().__init__(*args)
        self[:] = list(self)

    def _convert(self, x):
        return int(x)


class Vec2d(_Vec2):
    __slots__ = ()


class Vec2f(_Vec2):
    __slots__ = ()
    _round = True


class Vec3h(Vec3f):
    __slots__ = ()


def Cross(a, b):
    return a.GetCross(b)


def Dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def IsClose(a, b, eps):
    try:
        return all(abs(x - y) <= eps for x, y in zip(a, b))
    except TypeError:
        return abs(a - b) <= eps


def DegreesToRadians(d):
    return d * _math.pi / 180.0


def RadiansToDegrees(r):
    return r * 180.0 / _math.pi


def _vec3d(x, y, z):
    """A Vec3d of three floats, without the constructor's conversions."""
    v = _new_list(Vec3d)
    _extend_list(v, (x, y, z))
    return v


def _floats3(v):
    """The three floats of Vec3d(v)."""
    if type(v) is Vec3d:
        return v
    if type(v) in (list, tuple) and len(v) == 3:
        return float(v[0]), float(v[1]), float(v[2])
    return Vec3d(v)


def _unit3(v):
    """Vec3d(v).GetNormalized() as three floats (the same operations, in the same order)."""
    x, y, z = _floats3(v)
    n = _sqrt(x * x + y * y + z * z)
    if n > 1e-10:
        return x / n, y / n, z / n
    return x / 1e-10, y / 1e-10, z / 1e-10


def _unit4(w, x, y, z):
    """A quaternion's GetNormalized() as four floats: the identity below 1e-10."""
    n = _sqrt(w * w + (x * x + y * y + z * z))
    if n < 1e-10:
        return 1.0, 0.0, 0.0, 0.0
    return w / n, x / n, y / n, z / n


class _Quat(_Located):
    """w and the imaginary (x, y, z), kept as four floats (float32-rounded in the f types)."""
    __slots__ = ("_w", "_x", "_y", "_z")
    _vec = Vec3d

    def __init__(self, *args):
        if len(args) == 4:
            w, x, y, z = args
        elif not args:
            w, x, y, z = 0.0, 0.0, 0.0, 0.0
        elif len(args) == 1 and isinstance(args[0], _Quat):
            q = args[0]
            w, x, y, z = q._w, q._x, q._y, q._z
        elif len(args) == 1:
            w, x, y, z = float(args[0]), 0.0, 0.0, 0.0
        elif len(args) == 2:
            w = float(args[0])
            x, y, z = self._vec(*tuple(args[1]))
        else:
            raise TypeError(f"Gf.{type(self).__name__}(w, x, y, z), (w, imaginary) or (quat)")
        if self._vec is Vec3f:
            self._w = _f32(w)
            self._x, self._y, self._z = _F32X3.unpack(_F32X3.pack(float(x), float(y), float(z)))
        else:
            self._w, self._x, self._y, self._z = float(w), float(x), float(y), float(z)

    @classmethod
    def _of(cls, w, x, y, z):
        """cls(w, x, y, z) of four floats; no conversion in the double type."""
        if cls._vec is Vec3f:
            return cls(w, x, y, z)
        q = _new_object(cls)
        q._w, q._x, q._y, q._z = w, x, y, z
        return q

    def GetReal(self):
        return self._w

    def GetImaginary(self):
        return self._vec(self._x, self._y, self._z) if self._vec is Vec3f else _vec3d(self._x, self._y, self._z)

    def SetReal(self, w):
        self._w = float(w)

    def SetImaginary(self, *i):
        self._x, self._y, self._z = self._vec(*i)

    def GetLength(self):
        x, y, z = self._x, self._y, self._z
        return _sqrt(self._w * self._w + (x * x + y * y + z * z))

    def GetNormalized(self, eps=1e-10):
        n = self.GetLength()
        if n < eps:
            return type(self).GetIdentity()
        return type(self)._of(self._w / n, self._x / n, self._y / n, self._z / n)

    def Normalize(self, eps=1e-10):
        q = self.GetNormalized(eps)
        self._w, self._x, self._y, self._z = q._w, q._x, q._y, q._z
        return self

    def GetConjugate(self):
        return type(self)._of(self._w, -self._x, -self._y, -self._z)

    def GetInverse(self):
        x, y, z = self._x, self._y, self._z
        n2 = self._w * self._w + (x * x + y * y + z * z)
        c = self.GetConjugate()
        return type(self)._of(c._w / n2, c._x / n2, c._y / n2, c._z / n2)

    def __mul__(self, o):
        if isinstance(o, _Quat):  # Hamilton product, as GfQuatd
            w1, x1, y1, z1 = self._w, self._x, self._y, self._z
            w2, x2, y2, z2 = o._w, o._x, o._y, o._z
            return type(self)._of(w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                                  w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)
        return type(self)(self._w * o, self._x * o, self._y * o, self._z * o)

    def Transform(self, v):
        q = self * type(self)(0.0, *v) * self.GetInverse()
        return type(v)(q._x, q._y, q._z) if isinstance(v, _Vec3) else Vec3d(q._x, q._y, q._z)

    def __eq__(self, o):
        return (isinstance(o, _Quat) and self._w == o._w and self._x == o._x and self._y == o._y
                and self._z == o._z)

    __hash__ = None

    def __repr__(self):
        return f"Gf.{type(self).__name__}({self._w!r}, Gf.{self._vec.__name__}{(self._x, self._y, self._z)!r})"

    @classmethod
    def GetIdentity(cls):
        return cls(1.0, 0.0, 0.0, 0.0)

    @classmethod
    def GetZero(cls):
        return cls(0.0, 0.0, 0.0, 0.0)


class Quatd(_Quat):
    __slots__ = ()


class Quatf(_Quat):
    __slots__ = ()
    _vec = Vec3f


class Quath(Quatf):
    __slots__ = ()


def _quat_rows(q):
    """GfMatrix4d::SetRotate's 3x3 block (row vectors) of a unit quaternion."""
    return _rows_of(q._w, q._x, q._y, q._z)


def _rows_of(w, x, y, z):
    return [[1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (z * x - y * w)],
            [2 * (x * y - z * w), 1 - 2 * (z * z + x * x), 2 * (y * z + x * w)],
            [2 * (z * x + y * w), 2 * (y * z - x * w), 1 - 2 * (y * y + x * x)]]


def _rows_quat(m):
    """The unit quaternion of a 3x3 rotation block (row vectors), as GfMatrix4d::ExtractRotationQuat."""
    return Quatd._of(*_rows_quat4(m))


def _rows_quat4(m):
    """_rows_quat as four floats."""
    (m00, m01, m02), (m10, m11, m12), (m20, m21, m22) = m[0][:3], m[1][:3], m[2][:3]
    tr = m00 + m11 + m22
    if tr > 0:
        s = _sqrt(tr + 1.0) * 2
        w = 0.25 * s
        x, y, z = (m12 - m21) / s, (m20 - m02) / s, (m01 - m10) / s
    elif m00 > m11 and m00 > m22:
        s = _sqrt(1.0 + m00 - m11 - m22) * 2
        w, x = (m12 - m21) / s, 0.25 * s
        y, z = (m10 + m01) / s, (m20 + m02) / s
    elif m11 > m22:
        s = _sqrt(1.0 + m11 - m00 - m22) * 2
        w, x = (m20 - m02) / s, (m10 + m01) / s
        y, z = 0.25 * s, (m21 + m12) / s
    else:
        s = _sqrt(1.0 + m22 - m00 - m11) * 2
        w, x = (m01 - m10) / s, (m20 + m02) / s
        y, z = (m21 + m12) / s, 0.25 * s
    w, x, y, z = _unit4(float(w), float(x), float(y), float(z))
    if w >= 0:
        return w, x, y, z
    return w * -1.0, x * -1.0, y * -1.0, z * -1.0


_X_AXIS = (1.0, 0.0, 0.0)


class Rotation(_Located):
    """An axis and an angle in degrees, as GfRotation. The axis is kept as a tuple of three floats
    (scripts build and multiply rotations per prim per frame)."""
    __slots__ = ("_axis", "_angle")

    def __init__(self, *args):
        if len(args) == 2 and type(args[1]) is float and type(args[0]) is Vec3d:
            # Rotation(axis, angle), as scripts write it per prim per frame: SetAxisAngle unrolled.
            x, y, z = args[0]
            n = _sqrt(x * x + y * y + z * z)
            self._axis = (x / n, y / n, z / n) if n > 1e-10 else (x / 1e-10, y / 1e-10, z / 1e-10)
            self._angle = args[1]
        elif len(args) == 2 and not (isinstance(args[0], _Vec3) and isinstance(args[1], _Vec3)):
            self.SetAxisAngle(args[0], args[1])
        elif not args:
            self._axis, self._angle = _X_AXIS, 0.0
        elif len(args) == 1 and isinstance(args[0], _Quat):
            self.SetQuat(args[0])
        elif len(args) == 1 and isinstance(args[0], Rotation):
            self._axis, self._angle = args[0]._axis, args[0]._angle
        elif len(args) == 2:
            self.SetRotateInto(args[0], args[1])
        else:
            raise TypeError("Gf.Rotation(), (axis, angle), (quat) or (rotateFrom, rotateTo)")

    def SetAxisAngle(self, axis, angle):
        self._axis = _unit3(axis)
        self._angle = float(angle)
        return self

    def SetQuat(self, q):
        q = Quatd(q)
        return self._set_quat4(q._w, q._x, q._y, q._z)

    def _set_quat4(self, w, x, y, z):
        n = _sqrt(x * x + y * y + z * z)
        if n > 1e-10:
            self._axis = (x / n, y / n, z / n)
            self._angle = 2.0 * _degrees(_acos(max(-1.0, min(1.0, w / _sqrt(w * w + (x * x + y * y + z * z))))))
        else:
            self._axis, self._angle = _X_AXIS, 0.0
        return self

    def SetRotateInto(self, a, b):
        f, t = Vec3d(a).GetNormalized(), Vec3d(b).GetNormalized()
        c = f.GetDot(t)
        if c > 0.9999999:
            return self.SetIdentity()
        if c < -0.9999999:
            tmp = f.GetCross(Vec3d(1, 0, 0))
            if tmp.GetLength() < 0.00001:
                tmp = f.GetCross(Vec3d(0, 1, 0))
            return self.SetAxisAngle(tmp.GetNormalized(), 180.0)
        return self.SetAxisAngle(Vec3d(a).GetCross(Vec3d(b)).GetNormalized(), _degrees(_acos(c)))

    def SetIdentity(self):
        self._axis, self._angle = _X_AXIS, 0.0
        return self

    def GetAxis(self):
        return _vec3d(*self._axis)

    def GetAngle(self):
        return self._angle

    def _quat4(self):
        """GetQuat() as four floats."""
        if _n_quat is not None:
            x, y, z = self._axis
            q = _n_quat(x, y, z, self._angle)
            if q is not None:
                return q
        r = _radians(self._angle) / 2.0
        s = _sin(r)
        x, y, z = self._axis
        return _unit4(_cos(r), x * s, y * s, z * s)

    def GetQuat(self):
        return Quatd._of(*self._quat4())

    GetQuaternion = GetQuat

    def GetInverse(self):
        return Rotation(self._axis, -self._angle)

    def __mul__(self, o):
        # GfRotation::operator*=: q = r.q * this.q, so `self` applies first.
        if type(o) is Rotation or isinstance(o, Rotation):
            if _n_product is not None:
                (x1, y1, z1), (x2, y2, z2) = self._axis, o._axis
                p = _n_product(x1, y1, z1, self._angle, x2, y2, z2, o._angle)
                if p is not None:
                    r = _new_object(Rotation)
                    r._axis, r._angle = p[:3], p[3]
                    return r
            w1, x1, y1, z1 = o._quat4()
            w2, x2, y2, z2 = self._quat4()
            w, x, y, z = _unit4(w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                                w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)
            r = _new_object(Rotation)
            n = _sqrt(x * x + y * y + z * z)
            if n > 1e-10:
                r._axis = (x / n, y / n, z / n)
                r._angle = 2.0 * _degrees(_acos(max(-1.0, min(1.0, w))))
            else:
                r._axis, r._angle = self._axis, 0.0
            return r
        return Rotation(self._axis, self._angle * o)

    def TransformDir(self, v):
        return Matrix4d().SetRotate(self).TransformDir(v)

    def Decompose(self, axis0, axis1, axis2):
        """GfRotation::Decompose, line for line (Shoemake's Euler conversion). The matrix products are
        unrolled as the sums they were: 0.0 + a + b + c, left to right."""
        if _n_decompose is not None:
            x, y, z = self._axis
            f0, f1, f2 = _floats3(axis0), _floats3(axis1), _floats3(axis2)
            d = _n_decompose(x, y, z, self._angle, f0[0], f0[1], f0[2], f1[0], f1[1], f1[2], f2[0], f2[1], f2[2])
            if d is not None:
                return _vec3d(*d)
        (a00, a01, a02), (a10, a11, a12), (a20, a21, a22) = _rows_of(*self._quat4())
        n0, n1, n2 = _unit3(axis0), _unit3(axis1), _unit3(axis2)
        # axes = the normalized axes as columns; t = axes^T * rotation; m = t * axes.
        b00, b01, b02 = n0[0], n1[0], n2[0]
        b10, b11, b12 = n0[1], n1[1], n2[1]
        b20, b21, b22 = n0[2], n1[2], n2[2]
        t00 = 0.0 + b00 * a00 + b10 * a10 + b20 * a20
        t01 = 0.0 + b00 * a01 + b10 * a11 + b20 * a21
        t02 = 0.0 + b00 * a02 + b10 * a12 + b20 * a22
        t10 = 0.0 + b01 * a00 + b11 * a10 + b21 * a20
        t11 = 0.0 + b01 * a01 + b11 * a11 + b21 * a21
        t12 = 0.0 + b01 * a02 + b11 * a12 + b21 * a22
        t20 = 0.0 + b02 * a00 + b12 * a10 + b22 * a20
        t21 = 0.0 + b02 * a01 + b12 * a11 + b22 * a21
        t22 = 0.0 + b02 * a02 + b12 * a12 + b22 * a22
        m00 = 0.0 + t00 * b00 + t01 * b10 + t02 * b20
        m10 = 0.0 + t10 * b00 + t11 * b10 + t12 * b20
        m20 = 0.0 + t20 * b00 + t21 * b10 + t22 * b20
        m21 = 0.0 + t20 * b01 + t21 * b11 + t22 * b21
        m22 = 0.0 + t20 * b02 + t21 * b12 + t22 * b22
        cy = _sqrt(m00 * m00 + m10 * m10)
        if cy > 1e-6:
            r0, r1, r2 = _atan2(m21, m22), _atan2(-m20, cy), _atan2(m10, m00)
        else:
            m11 = 0.0 + t10 * b01 + t11 * b11 + t12 * b21
            m12 = 0.0 + t10 * b02 + t11 * b12 + t12 * b22
            r0, r1, r2 = _atan2(-m12, m11), _atan2(-m20, cy), 0.0
        c0, c1, c2 = (n0[1] * n1[2] - n0[2] * n1[1], n0[2] * n1[0] - n0[0] * n1[2], n0[0] * n1[1] - n0[1] * n1[0])
        if c0 * n2[0] + c1 * n2[1] + c2 * n2[2] >= 0.0:
            r0, r1, r2 = -r0, -r1, -r2
        return _vec3d(_degrees(r0), _degrees(r1), _degrees(r2))

    def __eq__(self, o):
        return isinstance(o, Rotation) and self._axis == o._axis and self._angle == o._angle

    __hash__ = None

    def __repr__(self):
        return f"Gf.Rotation({_vec3d(*self._axis)!r}, {self._angle!r})"


def _mul3(a, b):
    return [[sum(a[r][k] * b[k][c] for k in range(3)) for c in range(3)] for r in range(3)]


def _mul4(a, b):
    return [[a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c] + a[r][3] * b[3][c] for c in range(4)]
            for r in range(4)]


_IDENTITY4 = ((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0))


class Matrix4d(_Located):
    """A 4x4 matrix, rows as USD stores them: p' = p * M, translation in row 3."""
    __slots__ = ("_m",)

    def __init__(self, *args):
        if not args:
            self._m = [list(r) for r in _IDENTITY4]
        elif len(args) == 1 and isinstance(args[0], Matrix4d):
            self._m = [list(r) for r in args[0]._m]
        elif len(args) == 1 and isinstance(args[0], (int, float)):
            self._m = [[float(args[0]) if r == c else 0.0 for c in range(4)] for r in range(4)]
        elif len(args) == 1:
            self._m = [[float(x) for x in row] for row in args[0]]
        elif len(args) == 16:
            self._m = [[float(x) for x in args[r * 4:r * 4 + 4]] for r in range(4)]
        else:
            raise TypeError("Gf.Matrix4d(), (scalar), (rows) or 16 numbers")

    @classmethod
    def _adopt(cls, rows):
        """A matrix holding `rows` (four lists of four floats, not copied)."""
        m = _new_object(cls)
        m._m = rows
        return m

    def __getitem__(self, r):
        return self._m[r]

    def __len__(self):
        return 4

    def __iter__(self):
        return iter(self._m)

    def __eq__(self, o):
        return isinstance(o, Matrix4d) and self._m == o._m

    __hash__ = None

    def __repr__(self):
        return "Gf.Matrix4d(" + ", ".join(repr(tuple(r)) for r in self._m) + ")"

    def __mul__(self, o):
        if isinstance(o, Matrix4d):
            return Matrix4d(_mul4(self._m, o._m))
        return Matrix4d([[x * o for x in r] for r in self._m])

    def SetIdentity(self):
        self._m = [list(r) for r in _IDENTITY4]
        return self

    def SetTranslate(self, t):
        self.SetIdentity()
        self._m[3][:3] = [float(t[0]), float(t[1]), float(t[2])]
        return self

    def SetTranslateOnly(self, t):
        self._m[3][:3] = [float(t[0]), float(t[1]), float(t[2])]
        return self

    def SetRotate(self, r):
        q = r.GetQuat() if isinstance(r, Rotation) else Quatd(r).GetNormalized()
        rows = _quat_rows(q)
        self._m = [rows[0] + [0.0], rows[1] + [0.0], rows[2] + [0.0], [0.0, 0.0, 0.0, 1.0]]
        return self

    def SetRotateOnly(self, r):
        q = r.GetQuat() if isinstance(r, Rotation) else Quatd(r).GetNormalized()
        rows = _quat_rows(q)
        for i in range(3):
            self._m[i][:3] = rows[i]
        return self

    def SetScale(self, s):
        s = [float(s)] * 3 if isinstance(s, (int, float)) else list(s)
        self._m = [[s[r] if r == c and r < 3 else (1.0 if r == c else 0.0) for c in range(4)] for r in range(4)]
        return self

    def ExtractTranslation(self):
        return Vec3d(self._m[3][0], self._m[3][1], self._m[3][2])

    def ExtractRotationMatrix(self):
        return [row[:3] for row in self._m[:3]]

    def ExtractRotationQuat(self):
        return Quatd._of(*self._rotation_quat4())

    def _rotation_quat4(self):
        m = self._m
        return _rows_quat4([_unit3(m[0][:3]), _unit3(m[1][:3]), _unit3(m[2][:3])])

    def ExtractRotation(self):
        if _n_rotation_of is not None:
            r0, r1, r2 = self._m[0], self._m[1], self._m[2]
            q = _n_rotation_of(r0[0], r0[1], r0[2], r1[0], r1[1], r1[2], r2[0], r2[1], r2[2])
            if q is not None:
                r = _new_object(Rotation)
                r._axis, r._angle = q[:3], q[3]
                return r
        return _new_object(Rotation)._set_quat4(*self._rotation_quat4())

    def GetTranspose(self):
        return Matrix4d([list(c) for c in zip(*self._m)])

    def GetDeterminant(self):
        import numpy
        return float(numpy.linalg.det(self._m))

    def GetInverse(self):
        return Matrix4d._adopt(_inverse(self._m))

    def Transform(self, p):
        m = self._m
        x, y, z = p[0], p[1], p[2]
        out = [x * m[0][c] + y * m[1][c] + z * m[2][c] + m[3][c] for c in range(4)]
        return Vec3d(out[0] / out[3], out[1] / out[3], out[2] / out[3])

    def TransformDir(self, v):
        m = self._m
        return type(v)(*[v[0] * m[0][c] + v[1] * m[1][c] + v[2] * m[2][c] for c in range(3)]) \
            if isinstance(v, _Vec3) else Vec3d(*[v[0] * m[0][c] + v[1] * m[1][c] + v[2] * m[2][c] for c in range(3)])

    TransformAffine = Transform

    def RemoveScaleShear(self):
        t = Transform(self)
        return Matrix4d().SetRotate(t.GetRotation()).SetTranslateOnly(t.GetTranslation())

    def SetLookAt(self, eye, center, up):
        """GfMatrix4d::SetLookAt: the view matrix (world -> camera looking down -Z)."""
        ex, ey, ez = _floats3(eye)
        cx, cy, cz = _floats3(center)
        ux, uy, uz = _floats3(up)
        if _n_look_at is not None:
            rows = _n_look_at(ex, ey, ez, cx, cy, cz, ux, uy, uz)
            if rows is not None:
                self._m = rows
                return self
        vx, vy, vz = _unit3(_vec3d(cx - ex, cy - ey, cz - ez))
        rx, ry, rz = _unit3(_vec3d(vy * uz - vz * uy, vz * ux - vx * uz, vx * uy - vy * ux))
        px, py, pz = _unit3(_vec3d(ry * vz - rz * vy, rz * vx - rx * vz, rx * vy - ry * vx))
        rot = [[rx, px, -vx, 0.0], [ry, py, -vy, 0.0], [rz, pz, -vz, 0.0], [0.0, 0.0, 0.0, 1.0]]
        trans = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [-ex, -ey, -ez, 1.0]]
        self._m = _mul4(trans, rot)
        return self


_inverse_impl = None


def _inverse(rows):
    """numpy.linalg.inv(rows).tolist(): numpy's own LAPACK call (the same result), without its
    argument checks where this numpy has the call inv makes (numpy 1.x)."""
    global _inverse_impl
    if _inverse_impl is None:
        import numpy
        try:
            from numpy.linalg import linalg as _linalg
            extobj = _linalg.get_linalg_error_extobj(_linalg._raise_linalgerror_singular)
            call = _linalg._umath_linalg.inv
            call([[2.0, 0.0], [0.0, 2.0]], signature="d->d", extobj=extobj)

            def _inverse_impl(rows):
                return call(rows, signature="d->d", extobj=extobj).tolist()
        except Exception:  # another numpy: its public call
            def _inverse_impl(rows):
                return numpy.linalg.inv(rows).tolist()
    return _inverse_impl(rows)


class Transform(_Located):
    """Translation, rotation and scale of a matrix (GfTransform without pivots)."""
    __slots__ = ("_t", "_r", "_s")

    def __init__(self, m=None):
        self._t, self._r, self._s = Vec3d(), Rotation(), Vec3d(1.0, 1.0, 1.0)
        if m is not None:
            self.SetMatrix(m)

    def SetMatrix(self, m):
        rows = m._m if isinstance(m, Matrix4d) else m
        self._t = Vec3d(rows[3][:3])
        axes = [Vec3d(r[:3]) for r in rows[:3]]
        scale = [a.GetLength() for a in axes]
        if axes[0].GetCross(axes[1]).GetDot(axes[2]) < 0:
            scale = [-s for s in scale]
        self._s = Vec3d(scale)
        self._r = Rotation(_rows_quat([list(a / s) for a, s in zip(axes, scale)]))
        return self

    def GetTranslation(self):
        return Vec3d(self._t)

    def SetTranslation(self, t):
        self._t = Vec3d(t)

    def GetRotation(self):
        return Rotation(self._r)

    def SetRotation(self, r):
        self._r = Rotation(r)

    def GetScale(self):
        return Vec3d(self._s)

    def SetScale(self, s):
        self._s = Vec3d(s)

    def GetMatrix(self):
        m = Matrix4d().SetRotate(self._r)
        for i in range(3):
            m._m[i] = [x * self._s[i] for x in m._m[i][:3]] + [0.0]
        return m.SetTranslateOnly(self._t)


class Range3d(_Located):
    __slots__ = ("_min", "_max")

    def __init__(self, lo=None, hi=None):
        self._min = Vec3d(lo) if lo is not None else Vec3d(float("inf"), float("inf"), float("inf"))
        self._max = Vec3d(hi) if hi is not None else Vec3d(-float("inf"), -float("inf"), -float("inf"))

    def GetMin(self):
        return Vec3d(self._min)

    def GetMax(self):
        return Vec3d(self._max)

    def GetSize(self):
        return self._max - self._min

    def GetMidpoint(self):
        return (self._min + self._max) * 0.5

    def IsEmpty(self):
        return any(a > b for a, b in zip(self._min, self._max))


class BBox3d(_Located):
    """A box: a range in the frame of a matrix (GfBBox3d without the zero-area primitive flag)."""
    __slots__ = ("_range", "_matrix")

    def __init__(self, box_range=None, matrix=None):
        self._range = box_range if box_range is not None else Range3d()
        self._matrix = Matrix4d(matrix._m) if matrix is not None else Matrix4d()

    def GetRange(self):
        return self._range

    GetBox = GetRange

    def GetMatrix(self):
        return Matrix4d(self._matrix._m)

    def SetRange(self, box_range):
        self._range = box_range

    def SetMatrix(self, matrix):
        self._matrix = Matrix4d(matrix._m)

    def GetVolume(self):
        if self._range.IsEmpty():
            return 0.0
        size = self._range.GetSize()
        return abs(self._matrix.GetDeterminant()) * size[0] * size[1] * size[2]

    def ComputeAlignedRange(self):
        return _transformed_range(self._range, self._matrix)

    ComputeAlignedBox = ComputeAlignedRange

    def ComputeCentroid(self):
        return self._matrix.Transform(self._range.GetMidpoint())

    @staticmethod
    def Combine(b1, b2):
        """USD's rule: the result keeps the first non-empty box's frame; the other is taken into it."""
        if b1._range.IsEmpty():
            return BBox3d(b2._range, b2._matrix)
        if b2._range.IsEmpty():
            return BBox3d(b1._range, b1._matrix)
        into_b1 = b2._matrix * b1._matrix.GetInverse()
        other = _transformed_range(b2._range, into_b1)
        lo = [min(a, b) for a, b in zip(b1._range.GetMin(), other.GetMin())]
        hi = [max(a, b) for a, b in zip(b1._range.GetMax(), other.GetMax())]
        return BBox3d(Range3d(lo, hi), b1._matrix)


def _transformed_range(box_range, matrix):
    """The axis-aligned range of `box_range`'s eight corners transformed by `matrix`."""
    if box_range.IsEmpty():
        return Range3d()
    lo, hi = box_range.GetMin(), box_range.GetMax()
    corners = [matrix.Transform(Vec3d(x, y, z)) for x in (lo[0], hi[0]) for y in (lo[1], hi[1])
               for z in (lo[2], hi[2])]
    return Range3d([min(c[i] for c in corners) for i in range(3)], [max(c[i] for c in corners) for i in range(3)])


class Range1d(_Located):
    __slots__ = ("_min", "_max")

    def __init__(self, lo=float("inf"), hi=-float("inf")):
        self._min, self._max = float(lo), float(hi)

    def GetMin(self):
        return self._min

    def GetMax(self):
        return self._max
