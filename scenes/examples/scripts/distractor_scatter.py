"""distractorScatter: scatters distractor objects (primitive shapes and mesh
files) through a box volume, with a random pose, size and colour each time.

On the first play it creates `count` prims under
/Behaviors/distractorScatter/ (named after their shape: Cube, Cube_01,
Sphere, Mesh, ...), each drawn with rng.choice from the pool: the primitive
shapes in `shapes` (or `shapes:csv` when that is set) followed by the mesh
files in `assets`. Primitives are made one unit across (a Cube of size 1, a
Sphere of radius 0.5, a Cylinder or Cone of radius 0.5 and height 1, a
Capsule of radius 0.25 and height 0.5); meshes keep their own size. Every
distractor carries the semantic class `semanticClass` (a mesh entry
"file#label" uses its label instead; "" labels nothing).

On every apply each distractor draws, in this order: a position uniformly
in [range:minPosition, range:maxPosition] (per axis, relative to the
attached prim's world position, axis-aligned; the attached prim's rotation
and scale are ignored), three rotation angles in [range:minRotation,
range:maxRotation] degrees (applied X, then Y, then Z, about world axes), a
uniform scale in scaleRange (times assetScale for meshes), and, with
randomColor, a display colour (r, g, b in 0 .. 1; meshes whose file has its
own materials keep those). sdgbehave removes the distractors on stop by
itself.

Exposed variables (attributes exposedVar:distractorScatter:<name>):
    count               uint      8                     distractors to create
    shapes              string[]  [Cube, Sphere, Cylinder, Cone, Capsule]
    shapes:csv          string    ""                    comma-separated shapes; when set, used instead of shapes
    assets              asset[]   []                    mesh files ("file#label" sets the class)
    range:minPosition   vector3d  (-1, -1, 0)           volume's lower corner, relative to the prim
    range:maxPosition   vector3d  (1, 1, 1)             volume's upper corner, relative to the prim
    range:minRotation   vector3d  (0, 0, 0)             degrees about X, Y, Z
    range:maxRotation   vector3d  (360, 360, 360)       degrees about X, Y, Z
    scaleRange          float2    (0.2, 0.5)            uniform scale (min, max)
    assetScale          float     1                     meshes' scale is scaleRange's draw times this
    randomColor         bool      true                  draw primvars:displayColor too
    semanticClass       string    "distractor"          class label; "" for none
    interval            uint      0                     apply every N updates; 0: every update
    seed                int       -1                    -1 derives the stream from the run seed; >= 0 fixes it

Example (a whole scene: scenes/examples/distractor_scatter.yaml):

    scripts: [scripts/distractor_scatter.py]
    prims:
      /World/Table:
        type: Cube
        behaviors:
          distractorScatter:
            count: 10
            shapes:csv: "Cube,Sphere,Cone"
            assets: [props/bin.glb]
            range:minPosition: [-2, -2, 0.2]
            range:maxPosition: [2, 2, 1.5]
"""
import math

import sdgbehave

ROOT = "/Behaviors/distractorScatter"

# Attributes that make each primitive one unit across at scale 1.
UNIT_SHAPES = {
    "Cube": {"size": 1.0},
    "Sphere": {"radius": 0.5},
    "Cylinder": {"radius": 0.5, "height": 1.0},
    "Cone": {"radius": 0.5, "height": 1.0},
    "Capsule": {"radius": 0.25, "height": 0.5},
}


def rotation_xyz(degrees):
    """The 3x3 rotation (rows) that turns about world X, then Y, then Z."""
    cx, cy, cz = (math.cos(math.radians(a)) for a in degrees)
    sx, sy, sz = (math.sin(math.radians(a)) for a in degrees)
    # Rz @ Ry @ Rx
    return ((cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx),
            (sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx),
            (-sy, cy * sx, cy * cx))


class DistractorScatter(sdgbehave.IntervalBehavior):
    """Scatters labelled distractor shapes and meshes through a box volume with a random pose, size and colour."""

    BEHAVIOR_NS = "distractorScatter"
    VARIABLES_TO_EXPOSE = [
        {"attr_name": "count", "attr_type": "uint", "default_value": 8,
         "doc": "Number of distractors to create."},
        {"attr_name": "shapes", "attr_type": "string[]",
         "default_value": ["Cube", "Sphere", "Cylinder", "Cone", "Capsule"],
         "doc": "Primitive shapes to draw from: Cube, Sphere, Cylinder, Cone, Capsule."},
        {"attr_name": "shapes:csv", "attr_type": "string", "default_value": "",
         "doc": "Comma-separated primitive shapes; when set, used instead of shapes."},
        {"attr_name": "assets", "attr_type": "asset[]", "default_value": [], "files": "mesh",
         "doc": "Mesh files to draw from too; 'file#label' gives that mesh the semantic class label."},
        {"attr_name": "range:minPosition", "attr_type": "vector3d", "default_value": (-1.0, -1.0, 0.0),
         "doc": "Lower corner of the volume, relative to the prim's world position."},
        {"attr_name": "range:maxPosition", "attr_type": "vector3d", "default_value": (1.0, 1.0, 1.0),
         "doc": "Upper corner of the volume, relative to the prim's world position."},
        {"attr_name": "range:minRotation", "attr_type": "vector3d", "default_value": (0.0, 0.0, 0.0),
         "doc": "Lower bound of the rotation about X, Y and Z (degrees)."},
        {"attr_name": "range:maxRotation", "attr_type": "vector3d", "default_value": (360.0, 360.0, 360.0),
         "doc": "Upper bound of the rotation about X, Y and Z (degrees)."},
        {"attr_name": "scaleRange", "attr_type": "float2", "default_value": (0.2, 0.5), "minimum": 0,
         "doc": "Uniform scale (min, max); primitives are one unit across at scale 1."},
        {"attr_name": "assetScale", "attr_type": "float", "default_value": 1.0, "minimum": 0,
         "doc": "Mesh distractors are scaled by the scaleRange draw times this (meshes keep their own size)."},
        {"attr_name": "randomColor", "attr_type": "bool", "default_value": True,
         "doc": "Also draw each distractor's primvars:displayColor on every apply."},
        {"attr_name": "semanticClass", "attr_type": "string", "default_value": "distractor",
         "doc": "Semantic class label of the distractors; empty for none."},
        {"attr_name": "seed", "attr_type": "int", "default_value": -1,
         "doc": "-1 derives the stream from the run seed; >= 0 fixes it."},
    ]

    def setup(self):
        self.position = self._ranges("range:minPosition", "range:maxPosition")
        self.rotation = self._ranges("range:minRotation", "range:maxRotation")
        self.scale = self._ranges("scaleRange")
        self.color = self.get_exposed_variable("randomColor")
        asset_scale = self.get_exposed_variable("assetScale")
        pool = self._pool()
        count = self.get_exposed_variable("count")
        self.distractors = []
        if not pool:
            if count:
                self.log.warn("no shapes and no assets to draw from; nothing to scatter")
            return
        label = self.get_exposed_variable("semanticClass")
        for _ in range(count):
            kind, value, own_label = self.rng.choice(pool)
            prim = self.stage.define_prim(self.stage.next_free_path(f"{ROOT}/{value if kind == 'shape' else 'Mesh'}"),
                                          value if kind == "shape" else "Mesh")
            if kind == "shape":
                for name, size in UNIT_SHAPES[value].items():
                    prim.set_attribute(name, size)
            else:
                prim.set_attribute("asset", value)
            if own_label or label:
                prim.set_semantic_labels([own_label or label])
            # translate, orient, scale: the op order every apply writes into
            prim.set_location((0.0, 0.0, 0.0))
            prim.set_rotation(((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)))
            prim.set_scale((1.0, 1.0, 1.0))
            self.distractors.append((prim, 1.0 if kind == "shape" else asset_scale))

    def apply(self):
        anchor = self.prim.get_world_location() if self.prim.is_xformable else (0.0, 0.0, 0.0)
        for prim, factor in self.distractors:
            offset = [self.rng.uniform(lo, hi) for lo, hi in self.position]
            prim.set_world_location([a + o for a, o in zip(anchor, offset)])
            prim.set_world_rotation(rotation_xyz([self.rng.uniform(lo, hi) for lo, hi in self.rotation]))
            s = self.rng.uniform(*self.scale[0]) * factor
            prim.set_scale((s, s, s))
            if self.color:
                prim.set_attribute("primvars:displayColor", [self.rng.random() for _ in range(3)])

    def reset(self):
        self.distractors = []  # sdgbehave removes the prims themselves

    def _pool(self):
        """[(kind, shape name or file, label)]: the shapes, then the mesh files."""
        csv = self.get_exposed_variable("shapes:csv")
        shapes = [s.strip() for s in csv.split(",") if s.strip()] if csv else self.get_exposed_variable("shapes")
        pool = []
        for shape in shapes:
            if shape not in UNIT_SHAPES:
                raise ValueError(f"distractorScatter: unknown shape '{shape}'; the shapes are "
                                 f"{', '.join(UNIT_SHAPES)}")
            pool.append(("shape", shape, ""))
        for entry in self.get_exposed_variable("assets"):
            file, _, label = entry.rpartition("#") if "#" in entry else (entry, "", "")
            pool.append(("mesh", file, label))
        return pool

    def _ranges(self, low_name, high_name=None):
        """[(low, high)] per component: two vector variables, or one float2 (min, max)."""
        if high_name is None:
            low, high = self.get_exposed_variable(low_name)
            pairs = [(low, high)]
        else:
            pairs = list(zip(self.get_exposed_variable(low_name), self.get_exposed_variable(high_name)))
        for low, high in pairs:
            if low > high:
                raise ValueError(f"distractorScatter: {low_name} exceeds {high_name or 'its maximum'} "
                                 f"({low} > {high})")
        return pairs
