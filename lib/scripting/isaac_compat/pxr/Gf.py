"""pxr.Gf: vectors, quaternions, rotations, matrices and ranges with USD's
conventions (row vectors: p' = p * M, translation in the last row;
Rotation(a) * Rotation(b) applies a first, then b)."""
import math as _math
import struct as _struct

from _isaac_compat import Located as _Located, module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)

_F32 = _struct.Struct("f")


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
        if len(args) == 3 and self._round is None:
            x, y, z = args
            list.__init__(self, (float(x), float(y), float(z)))
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


class _Quat(_Located):
    __slots__ = ("_w", "_i")
    _vec = Vec3d

    def __init__(self, *args):
        if not args:
            w, i = 0.0, (0.0, 0.0, 0.0)
        elif len(args) == 1 and isinstance(args[0], _Quat):
            w, i = args[0].GetReal(), tuple(args[0].GetImaginary())
        elif len(args) == 1:
            w, i = float(args[0]), (0.0, 0.0, 0.0)
        elif len(args) == 2:
            w, i = float(args[0]), tuple(args[1])
        elif len(args) == 4:
            w, i = float(args[0]), args[1:]
        else:
            raise TypeError(f"Gf.{type(self).__name__}(w, x, y, z), (w, imaginary) or (quat)")
        self._w = _f32(w) if self._vec is Vec3f else float(w)
        self._i = self._vec(*i)

    def GetReal(self):
        return self._w

    def GetImaginary(self):
        return self._vec(self._i)

    def SetReal(self, w):
        self._w = float(w)

    def SetImaginary(self, *i):
        self._i = self._vec(*i)

    def GetLength(self):
        return _math.sqrt(self._w * self._w + self._i.GetDot(self._i))

    def GetNormalized(self, eps=1e-10):
        n = self.GetLength()
        if n < eps:
            return type(self).GetIdentity()
        return type(self)(self._w / n, *(x / n for x in self._i))

    def Normalize(self, eps=1e-10):
        q = self.GetNormalized(eps)
        self._w, self._i = q._w, q._i
        return self

    def GetConjugate(self):
        return type(self)(self._w, *(-x for x in self._i))

    def GetInverse(self):
        n2 = self._w * self._w + self._i.GetDot(self._i)
        c = self.GetConjugate()
        return type(self)(c._w / n2, *(x / n2 for x in c._i))

    def __mul__(self, o):
        if isinstance(o, _Quat):  # Hamilton product, as GfQuatd
            w1, (x1, y1, z1) = self._w, self._i
            w2, (x2, y2, z2) = o._w, o._i
            return type(self)(w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                              w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)
        return type(self)(self._w * o, *(x * o for x in self._i))

    def Transform(self, v):
        q = self * type(self)(0.0, *v) * self.GetInverse()
        return type(v)(*q._i) if isinstance(v, _Vec3) else Vec3d(*q._i)

    def __eq__(self, o):
        return isinstance(o, _Quat) and self._w == o._w and self._i == o._i

    __hash__ = None

    def __repr__(self):
        return f"Gf.{type(self).__name__}({self._w!r}, Gf.{self._vec.__name__}{tuple(self._i)!r})"

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
    w, (x, y, z) = q.GetReal(), q.GetImaginary()
    return [[1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (z * x - y * w)],
            [2 * (x * y - z * w), 1 - 2 * (z * z + x * x), 2 * (y * z + x * w)],
            [2 * (z * x + y * w), 2 * (y * z - x * w), 1 - 2 * (y * y + x * x)]]


def _rows_quat(m):
    """The unit quaternion of a 3x3 rotation block (row vectors), as GfMatrix4d::ExtractRotationQuat."""
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:
        s = _math.sqrt(tr + 1.0) * 2
        w = 0.25 * s
        x, y, z = (m[1][2] - m[2][1]) / s, (m[2][0] - m[0][2]) / s, (m[0][1] - m[1][0]) / s
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = _math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2
        w, x = (m[1][2] - m[2][1]) / s, 0.25 * s
        y, z = (m[1][0] + m[0][1]) / s, (m[2][0] + m[0][2]) / s
    elif m[1][1] > m[2][2]:
        s = _math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2
        w, x = (m[2][0] - m[0][2]) / s, (m[1][0] + m[0][1]) / s
        y, z = 0.25 * s, (m[2][1] + m[1][2]) / s
    else:
        s = _math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2
        w, x = (m[0][1] - m[1][0]) / s, (m[2][0] + m[0][2]) / s
        y, z = (m[2][1] + m[1][2]) / s, 0.25 * s
    q = Quatd(w, x, y, z).GetNormalized()
    return q if q.GetReal() >= 0 else q * -1.0


class Rotation(_Located):
    """An axis and an angle in degrees, as GfRotation."""
    __slots__ = ("_axis", "_angle")

    def __init__(self, *args):
        if not args:
            self._axis, self._angle = Vec3d(1.0, 0.0, 0.0), 0.0
        elif len(args) == 1 and isinstance(args[0], _Quat):
            self.SetQuat(args[0])
        elif len(args) == 1 and isinstance(args[0], Rotation):
            self._axis, self._angle = Vec3d(args[0]._axis), args[0]._angle
        elif len(args) == 2 and isinstance(args[0], _Vec3) and isinstance(args[1], _Vec3):
            self.SetRotateInto(args[0], args[1])
        elif len(args) == 2:
            self.SetAxisAngle(args[0], args[1])
        else:
            raise TypeError("Gf.Rotation(), (axis, angle), (quat) or (rotateFrom, rotateTo)")

    def SetAxisAngle(self, axis, angle):
        self._axis = Vec3d(axis).GetNormalized()
        self._angle = float(angle)
        return self

    def SetQuat(self, q):
        q = Quatd(q)
        n = q.GetImaginary().GetLength()
        if n > 1e-10:
            self._axis = q.GetImaginary() / n
            self._angle = 2.0 * _math.degrees(_math.acos(max(-1.0, min(1.0, q.GetReal() / q.GetLength()))))
        else:
            self._axis, self._angle = Vec3d(1.0, 0.0, 0.0), 0.0
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
        return self.SetAxisAngle(Vec3d(a).GetCross(Vec3d(b)).GetNormalized(), _math.degrees(_math.acos(c)))

    def SetIdentity(self):
        self._axis, self._angle = Vec3d(1.0, 0.0, 0.0), 0.0
        return self

    def GetAxis(self):
        return Vec3d(self._axis)

    def GetAngle(self):
        return self._angle

    def GetQuat(self):
        r = _math.radians(self._angle) / 2.0
        return Quatd(_math.cos(r), self._axis * _math.sin(r)).GetNormalized()

    GetQuaternion = GetQuat

    def GetInverse(self):
        return Rotation(self._axis, -self._angle)

    def __mul__(self, o):
        # GfRotation::operator*=: q = r.q * this.q, so `self` applies first.
        if isinstance(o, Rotation):
            q = (o.GetQuat() * self.GetQuat()).GetNormalized()
            r = Rotation()
            n = q.GetImaginary().GetLength()
            if n > 1e-10:
                r._axis = q.GetImaginary() / n
                r._angle = 2.0 * _math.degrees(_math.acos(max(-1.0, min(1.0, q.GetReal()))))
            else:
                r._axis, r._angle = Vec3d(self._axis), 0.0
            return r
        return Rotation(self._axis, self._angle * o)

    def TransformDir(self, v):
        return Matrix4d().SetRotate(self).TransformDir(v)

    def Decompose(self, axis0, axis1, axis2):
        """GfRotation::Decompose, line for line (Shoemake's Euler conversion)."""
        mat = _quat_rows(self.GetQuat())
        n0, n1, n2 = Vec3d(axis0).GetNormalized(), Vec3d(axis1).GetNormalized(), Vec3d(axis2).GetNormalized()
        axes = [[n0[0], n1[0], n2[0]], [n0[1], n1[1], n2[1]], [n0[2], n1[2], n2[2]]]
        axes_t = [list(r) for r in zip(*axes)]
        m = _mul3(_mul3(axes_t, mat), axes)
        i, j, k = 0, 1, 2
        cy = _math.sqrt(m[i][i] * m[i][i] + m[j][i] * m[j][i])
        if cy > 1e-6:
            r0, r1, r2 = _math.atan2(m[k][j], m[k][k]), _math.atan2(-m[k][i], cy), _math.atan2(m[j][i], m[i][i])
        else:
            r0, r1, r2 = _math.atan2(-m[j][k], m[j][j]), _math.atan2(-m[k][i], cy), 0.0
        if n0.GetCross(n1).GetDot(n2) >= 0.0:
            r0, r1, r2 = -r0, -r1, -r2
        return Vec3d(_math.degrees(r0), _math.degrees(r1), _math.degrees(r2))

    def __eq__(self, o):
        return isinstance(o, Rotation) and self._axis == o._axis and self._angle == o._angle

    __hash__ = None

    def __repr__(self):
        return f"Gf.Rotation({self._axis!r}, {self._angle!r})"


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
        rows = [Vec3d(r[:3]).GetNormalized() for r in self._m[:3]]
        return _rows_quat([list(r) for r in rows])

    def ExtractRotation(self):
        return Rotation(self.ExtractRotationQuat())

    def GetTranspose(self):
        return Matrix4d([list(c) for c in zip(*self._m)])

    def GetDeterminant(self):
        import numpy
        return float(numpy.linalg.det(self._m))

    def GetInverse(self):
        import numpy
        return Matrix4d(numpy.linalg.inv(self._m).tolist())

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
        view = (Vec3d(center) - Vec3d(eye)).GetNormalized()
        right = view.GetCross(Vec3d(up)).GetNormalized()
        upv = right.GetCross(view).GetNormalized()
        rot = [[right[0], upv[0], -view[0], 0.0], [right[1], upv[1], -view[1], 0.0],
               [right[2], upv[2], -view[2], 0.0], [0.0, 0.0, 0.0, 1.0]]
        trans = Matrix4d().SetTranslate(-Vec3d(eye))
        self._m = _mul4(trans._m, rot)
        return self


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
