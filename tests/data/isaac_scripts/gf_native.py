"""Checks the Isaac layer's C++ Gf paths (script_api.cpp, gf_fast) against its Python ones (pxr/Gf.py):
rotations built, multiplied, turned into quaternions and decomposed, look-at matrices and the rotations
extracted from them, on random and special values (zeros of both signs, axes, half turns, degenerate
axes), must be bit-identical (every float compared by its bytes). Also checks that the C++ paths are
there and answer, and that they leave non-finite values to Python. Run by ctest (scripts.isaac_gf_native)."""
import math
import random
import struct

import sdgbehave
from pxr import Gf


def key(v):
    if isinstance(v, float):
        return struct.pack("d", v)
    if isinstance(v, (list, tuple)):
        return tuple(key(x) for x in v)
    if isinstance(v, Gf.Rotation):
        return ("rotation", key(list(v.GetAxis())), key(v.GetAngle()))
    if isinstance(v, Gf.Matrix4d):
        return ("matrix", key([list(r) for r in v]))
    if isinstance(v, str):
        return v
    raise TypeError(type(v))


def values(seed, count):
    rnd = random.Random(seed)
    special = [0.0, -0.0, 1.0, -1.0, 90.0, -90.0, 180.0, -180.0, 360.0, 45.0, 1e-12, -1e-12, 1e-7, 0.5]

    def num():
        c = rnd.random()
        if c < 0.2:
            return rnd.choice(special)
        return rnd.uniform(-720.0, 720.0) if c < 0.6 else rnd.uniform(-1.0, 1.0)

    def vec():
        if rnd.random() < 0.35:
            return Gf.Vec3d(*rnd.choice([(1, 0, 0), (0, 1, 0), (0, 0, 1), (0, 0, -1), (-1, 0, 0), (0, 0, 0),
                                         (-0.0, 0.0, -0.0), (1e-12, 0, 0)]))
        return Gf.Vec3d(num(), num(), num())

    X, Y, Z = Gf.Vec3d.XAxis(), Gf.Vec3d.YAxis(), Gf.Vec3d.ZAxis()
    out = []
    for _ in range(count):
        a, b, c = vec(), vec(), vec()
        r = Gf.Rotation(X, num()) * Gf.Rotation(Y, num()) * Gf.Rotation(Z, num())
        r2 = Gf.Rotation(a, num()) * Gf.Rotation(b, num()) * Gf.Rotation(c, num())
        out += [r, r2, r * r2, r2 * r, list(r.GetQuat().GetImaginary()), [r.GetQuat().GetReal()]]
        for axes in ((Z, Y, X), (Y, Z, X), (Z, X, Y), (X, Z, Y), (Y, X, Z), (X, Y, Z), (a, b, c)):
            out += [r.Decompose(*axes), r2.Decompose(*axes)]
        m = Gf.Matrix4d().SetLookAt(a, b, c)
        out += [m, m.ExtractRotation(), Gf.Matrix4d().SetRotate(r2).ExtractRotation()]
        try:
            out.append(m.GetInverse().ExtractRotation())
        except Exception as e:  # a singular matrix: the same error either way
            out.append(type(e).__name__)
    return [key(v) for v in out]


class GfNativeCheck(sdgbehave.Behavior):
    BEHAVIOR_NS = "gfNativeCheck"

    def on_play(self):
        native = Gf._NATIVE
        if not all(native):
            raise RuntimeError("the layer's C++ Gf paths are missing from _sdgbehave")
        if native[2](1.0, 0.0, 0.0, 30.0, 0.0, 1.0, 0.0, 40.0) is None:
            raise RuntimeError("gf_product answered None for ordinary values")
        if native[3](1.0, 0.0, 0.0, math.inf) is not None or native[3](1.0, 0.0, 0.0, 1) is not None:
            raise RuntimeError("gf_quat must leave non-finite and non-float values to Python")
        # A known value: a quarter turn about X decomposes to (0, 0, 90) on (Z, Y, X).
        d = Gf.Rotation(Gf.Vec3d.XAxis(), 90.0).Decompose(Gf.Vec3d.ZAxis(), Gf.Vec3d.YAxis(), Gf.Vec3d.XAxis())
        if max(abs(x - y) for x, y in zip(d, (0.0, 0.0, 90.0))) > 1e-9:
            raise RuntimeError(f"Decompose of a quarter turn about X: {d}")
        fast = values(17, 4000)
        Gf._use_native(False)
        try:
            slow = values(17, 4000)
        finally:
            Gf._use_native(True)
        differ = sum(1 for x, y in zip(fast, slow) if x != y)
        self.log.info(f"gf native: {len(fast)} values compared, {differ} differ")
        if differ or len(fast) != len(slow):
            raise RuntimeError(f"the C++ and Python Gf paths differ in {differ} of {len(fast)} values")
