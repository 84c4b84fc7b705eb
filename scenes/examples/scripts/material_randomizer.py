"""materialRandomizer: gives every geometry prim its own material with a
random diffuse colour, roughness and metalness.

On the first play, each geometry prim at or below the attached prim (only
the attached prim with includeChildren false) gets a Material prim of its
own, /Behaviors/materialRandomizer/Looks/<prim name> (made unique with a
_01, _02 ... suffix), bound with strongerThanDescendants. On every apply
each material draws, in this order, red, green and blue uniformly between
range:minColor and range:maxColor (channel by channel), then a roughness
from roughnessRange and a metalness from metallicRange, and writes them to
inputs:diffuse_color_constant, inputs:reflection_roughness_constant and
inputs:metallic_constant. The material replaces any texture the prim had.
On stop sdgbehave removes the materials and restores the prims' own
bindings by itself.

Exposed variables (attributes exposedVar:materialRandomizer:<name>):
    range:minColor   color3f  (0.05, 0.05, 0.05)  lower bound of r, g, b
    range:maxColor   color3f  (0.95, 0.95, 0.95)  upper bound of r, g, b
    roughnessRange   float2   (0.1, 0.9)          reflection roughness (min, max), 0 .. 1
    metallicRange    float2   (0, 1)              metalness (min, max), 0 .. 1
    includeChildren  bool     true                also every geometry prim below
    interval         uint     0                   apply every N updates; 0: every update
    seed             int      -1                  -1 derives the stream from the run seed; >= 0 fixes it

Example (a whole scene: scenes/examples/material_randomizer.yaml):

    scripts: [scripts/material_randomizer.py]
    prims:
      /World/Shapes:
        behaviors:
          materialRandomizer:
            range:minColor: [0.2, 0.0, 0.0]
            range:maxColor: [1.0, 0.6, 0.3]
            metallicRange: [0, 0.5]
"""
import sdgbehave

LOOKS = "/Behaviors/materialRandomizer/Looks"


class MaterialRandomizer(sdgbehave.IntervalBehavior):
    """Gives each geometry prim its own material with a random diffuse colour, roughness and metalness."""

    BEHAVIOR_NS = "materialRandomizer"
    VARIABLES_TO_EXPOSE = [
        {"attr_name": "range:minColor", "attr_type": "color3f", "default_value": (0.05, 0.05, 0.05), "minimum": 0,
         "doc": "Lower bound of the diffuse colour, per channel (r, g, b)."},
        {"attr_name": "range:maxColor", "attr_type": "color3f", "default_value": (0.95, 0.95, 0.95), "minimum": 0,
         "doc": "Upper bound of the diffuse colour, per channel (r, g, b)."},
        {"attr_name": "roughnessRange", "attr_type": "float2", "default_value": (0.1, 0.9), "minimum": 0,
         "doc": "Reflection roughness (min, max), within 0 .. 1."},
        {"attr_name": "metallicRange", "attr_type": "float2", "default_value": (0.0, 1.0), "minimum": 0,
         "doc": "Metalness (min, max), within 0 .. 1."},
        {"attr_name": "includeChildren", "attr_type": "bool", "default_value": True,
         "doc": "Also give every geometry prim below the attached prim its own material."},
        {"attr_name": "seed", "attr_type": "int", "default_value": -1,
         "doc": "-1 derives the stream from the run seed; >= 0 fixes it."},
    ]

    def setup(self):
        low, high = self.get_exposed_variable("range:minColor"), self.get_exposed_variable("range:maxColor")
        for channel, lo, hi in zip("rgb", low, high):
            if lo > hi:
                raise ValueError(f"materialRandomizer: range:minColor exceeds range:maxColor in {channel} "
                                 f"({lo} > {hi})")
        self.color = list(zip(low, high))
        self.roughness = self._unit_range("roughnessRange")
        self.metallic = self._unit_range("metallicRange")
        prims = self.stage.traverse(self.prim) if self.get_exposed_variable("includeChildren") else [self.prim]
        self.materials = []
        for prim in prims:
            if not prim.is_geometry:
                continue
            path = self.stage.next_free_path(f"{LOOKS}/{prim.name}")
            material = self.stage.define_prim(path, "Material")
            prim.bind_material(path, "strongerThanDescendants")
            self.materials.append(material)
        if not self.materials:
            self.log.warn("no geometry prim at or below the prim; nothing to randomize")

    def apply(self):
        for material in self.materials:
            color = [self.rng.uniform(lo, hi) for lo, hi in self.color]
            material.set_attribute("inputs:diffuse_color_constant", color)
            material.set_attribute("inputs:reflection_roughness_constant", self.rng.uniform(*self.roughness))
            material.set_attribute("inputs:metallic_constant", self.rng.uniform(*self.metallic))

    def reset(self):
        self.materials = []  # the prims themselves are removed by sdgbehave

    def _unit_range(self, name):
        low, high = self.get_exposed_variable(name)
        if low > high or high > 1:
            raise ValueError(f"materialRandomizer.{name}: expected 0 <= min <= max <= 1, found ({low}, {high})")
        return low, high
