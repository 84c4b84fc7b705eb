"""USD's procedural shapes as triangle meshes, exactly as sdgbehave builds them.

A line-by-line port of lib/assets/primitives.cpp (same vertex order, same
triangles, same normals and uvs), so Blender renders the very triangles the
rasterizer draws: a Sphere is the same 48 x 24 polyhedron in both, not two
different approximations of a sphere. Keep it in step with primitives.cpp.

Each function returns a dict of flat lists: positions [[x, y, z], ...],
normals (unit, per vertex), uvs [[u, v], ...] and indices (triangles).
"""
import math

SEGMENTS = 48  # around an axis (kSegments)
RINGS = 24     # pole to pole (kRings)


def _normalized(v):
    n = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    return [v[0] / n, v[1] / n, v[2] / n] if n > 0 else [0.0, 0.0, 0.0]


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


class _Builder:
    def __init__(self):
        self.positions, self.normals, self.uvs, self.indices = [], [], [], []

    def vertex(self, p, n, u, v):
        self.positions.append([float(x) for x in p])
        self.normals.append(_normalized(n))
        self.uvs.append([float(u), float(v)])
        return len(self.positions) - 1

    def triangle(self, a, b, c):
        self.indices += [a, b, c]

    def quad(self, a, b, c, d):
        self.triangle(a, b, c)
        self.triangle(a, c, d)

    def revolve(self, profile):
        """Surface of revolution about +Z from (radius, z, normal r, normal z) rows."""
        start = len(self.positions)
        for i, (r, z, nr, nz) in enumerate(profile):
            for s in range(SEGMENTS + 1):
                a = 2 * math.pi * s / SEGMENTS
                c, sn = math.cos(a), math.sin(a)
                self.vertex([r * c, r * sn, z], [nr * c, nr * sn, nz], s / SEGMENTS, i / (len(profile) - 1))
        for i in range(len(profile) - 1):
            for s in range(SEGMENTS):
                a = start + i * (SEGMENTS + 1) + s
                b = a + 1
                c = a + SEGMENTS + 1
                d = c + 1
                self.quad(a, b, d, c)

    def disk(self, radius, z, up):
        nz = 1.0 if up else -1.0
        centre = self.vertex([0, 0, z], [0, 0, nz], 0.5, 0.5)
        first = len(self.positions)
        for s in range(SEGMENTS + 1):
            a = 2 * math.pi * s / SEGMENTS
            self.vertex([radius * math.cos(a), radius * math.sin(a), z], [0, 0, nz],
                        0.5 + 0.5 * math.cos(a), 0.5 + 0.5 * math.sin(a))
        for s in range(SEGMENTS):
            if up:
                self.triangle(centre, first + s, first + s + 1)
            else:
                self.triangle(centre, first + s + 1, first + s)

    def finish(self, axis):
        """Shapes are built along +Z; a cyclic permutation turns Z into the axis."""
        def permute(v):
            if axis == "X":
                return [v[2], v[0], v[1]]
            if axis == "Y":
                return [v[1], v[2], v[0]]
            return v
        return {"positions": [permute(p) for p in self.positions], "normals": [permute(n) for n in self.normals],
                "uvs": self.uvs, "indices": self.indices}


def cube(size):
    b = _Builder()
    h = size / 2
    for n in ([1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]):
        t1 = [1, 0, 0] if abs(n[2]) > 0.5 else [0, 0, 1]
        t2 = _cross(n, t1)
        t1 = _cross(t2, n)
        corner = lambda s1, s2: [h * (n[k] + s1 * t1[k] + s2 * t2[k]) for k in range(3)]
        a = b.vertex(corner(-1, -1), n, 0, 0)
        c = b.vertex(corner(1, -1), n, 1, 0)
        d = b.vertex(corner(1, 1), n, 1, 1)
        e = b.vertex(corner(-1, 1), n, 0, 1)
        b.quad(a, c, d, e)
    return b.finish("Z")


def sphere(radius):
    b = _Builder()
    profile = []
    for i in range(RINGS + 1):
        polar = -math.pi / 2 + math.pi * i / RINGS
        r, z = math.cos(polar), math.sin(polar)
        profile.append((radius * r, radius * z, r, z))
    b.revolve(profile)
    return b.finish("Z")


def cylinder(radius, height, axis):
    b = _Builder()
    h = height / 2
    b.revolve([(radius, -h, 1, 0), (radius, h, 1, 0)])
    b.disk(radius, h, True)
    b.disk(radius, -h, False)
    return b.finish(axis)


def cone(radius, height, axis):
    b = _Builder()
    h = height / 2
    n = _normalized([height, 0, radius])  # the side normal leans up by the slope
    b.revolve([(radius, -h, n[0], n[2]), (0, h, n[0], n[2])])
    b.disk(radius, -h, False)
    return b.finish(axis)


def capsule(radius, height, axis):
    b = _Builder()
    h = height / 2
    profile = []
    for i in range(RINGS // 2 + 1):  # bottom cap: south pole to equator
        polar = -math.pi / 2 + (math.pi / 2) * i / (RINGS // 2)
        profile.append((radius * math.cos(polar), -h + radius * math.sin(polar), math.cos(polar), math.sin(polar)))
    for i in range(RINGS // 2 + 1):  # top cap: equator to north pole
        polar = (math.pi / 2) * i / (RINGS // 2)
        profile.append((radius * math.cos(polar), h + radius * math.sin(polar), math.cos(polar), math.sin(polar)))
    b.revolve(profile)
    return b.finish(axis)


def plane(width, length, axis):
    """Width along the first and length along the second of the other two axes (X, Y, Z order)."""
    b = _Builder()
    w, l = width / 2, length / 2
    n = [0, 0, 1]
    a = b.vertex([-w, -l, 0], n, 0, 0)
    c = b.vertex([w, -l, 0], n, 1, 0)
    d = b.vertex([w, l, 0], n, 1, 1)
    e = b.vertex([-w, l, 0], n, 0, 1)
    b.quad(a, c, d, e)
    if axis == "Y":
        # (x, y, z) -> (x, z, -y) keeps width on X, length on Z and a +Y normal.
        b.positions = [[p[0], p[2], -p[1]] for p in b.positions]
        b.normals = [[q[0], q[2], -q[1]] for q in b.normals]
        return b.finish("Z")
    return b.finish("X" if axis == "X" else "Z")


def cylinder_light_side(radius, length):
    """The emitting side of a USD CylinderLight (along X, no caps), for an emissive mesh."""
    b = _Builder()
    h = length / 2
    b.revolve([(radius, -h, 1, 0), (radius, h, 1, 0)])
    return b.finish("X")


def mesh_for(prim_type, attrs):
    """The mesh of a procedural prim from its (defaults-filled) attributes."""
    if prim_type == "Cube":
        return cube(float(attrs["size"]))
    if prim_type == "Sphere":
        return sphere(float(attrs["radius"]))
    if prim_type == "Cylinder":
        return cylinder(float(attrs["radius"]), float(attrs["height"]), attrs["axis"])
    if prim_type == "Cone":
        return cone(float(attrs["radius"]), float(attrs["height"]), attrs["axis"])
    if prim_type == "Capsule":
        return capsule(float(attrs["radius"]), float(attrs["height"]), attrs["axis"])
    if prim_type == "Plane":
        return plane(float(attrs["width"]), float(attrs["length"]), attrs["axis"])
    raise ValueError(f"not a procedural shape: {prim_type}")
