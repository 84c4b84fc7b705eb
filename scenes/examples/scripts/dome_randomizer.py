"""domeRandomizer: a random sky for every frame. The textureRandomizer's idea
applied to dome lights: on every apply the DomeLight it is attached to gets a
map drawn from a list or a folder, a turn about the stage's up axis and an
intensity, in that order.

The maps are `textures:assets` and, when `textures:folder` is set, every
image in that folder (.exr, .hdr, .png, .jpg, .jpeg, .tif, .tiff; sorted by
name, not descending into subfolders); at least one is needed. The turn is
drawn uniformly in degrees from `rotationRange` and composed with the dome's
own rotation, so a tilted dome stays tilted. The intensity is drawn
uniformly from `intensityRange`; (0, 0) keeps the light's own. On stop
sdgbehave restores the map, the rotation and the intensity by itself.

Exposed variables (attributes exposedVar:domeRandomizer:<name>):
    textures:assets  asset[]  []        maps to draw from (EXR, HDR or 8-bit lat-long images)
    textures:folder  string   ""        a folder whose images are added to the list
    rotationRange    float2   (0, 360)  turn about the up axis, degrees (min, max)
    intensityRange   float2   (0, 0)    inputs:intensity (min, max); (0, 0) keeps the light's
    interval         uint     0         apply every N updates; 0: every update
    seed             int      -1        -1 derives the stream from the run seed; >= 0 fixes it

Example (a whole scene: scenes/examples/dome_randomizer.yaml):

    scripts: [scripts/dome_randomizer.py]
    prims:
      /World/Sky:
        type: DomeLight
        behaviors:
          domeRandomizer:
            textures:assets: [../skies/sunset_sky.exr, ../skies/overcast_sky.exr]
            intensityRange: [0.5, 1.5]
"""
import math
import os

import sdgbehave

IMAGE_EXTENSIONS = (".exr", ".hdr", ".png", ".jpg", ".jpeg", ".tif", ".tiff")


class DomeRandomizer(sdgbehave.IntervalBehavior):
    """Gives a dome light a random map, a random turn about the up axis and a random intensity."""

    BEHAVIOR_NS = "domeRandomizer"
    VARIABLES_TO_EXPOSE = [
        {"attr_name": "textures:assets", "attr_type": "asset[]", "default_value": [], "files": "image",
         "doc": "Lat-long maps to draw from: EXR or HDR for real sky brightness, or 8-bit images."},
        {"attr_name": "textures:folder", "attr_type": "string", "default_value": "",
         "doc": "A folder whose images (.exr, .hdr, .png, .jpg, .jpeg, .tif, .tiff) are added to the list."},
        {"attr_name": "rotationRange", "attr_type": "float2", "default_value": (0.0, 360.0),
         "doc": "Turn about the stage's up axis in degrees (min, max)."},
        {"attr_name": "intensityRange", "attr_type": "float2", "default_value": (0.0, 0.0), "minimum": 0,
         "doc": "inputs:intensity (min, max); (0, 0) keeps the light's own."},
        {"attr_name": "seed", "attr_type": "int", "default_value": -1,
         "doc": "-1 derives the stream from the run seed; >= 0 fixes it."},
    ]

    def setup(self):
        if self.prim.type_name != "DomeLight":
            raise ValueError(f"domeRandomizer: {self.prim_path} is a {self.prim.type_name}, not a DomeLight")
        self.maps = list(self.get_exposed_variable("textures:assets")) + self._folder_maps()
        if not self.maps:
            raise ValueError("domeRandomizer: no maps: set textures:assets or textures:folder")
        self.rotation = self._ordered("rotationRange")
        self.intensity = self._ordered("intensityRange")
        self.base_rotation = self.prim.get_rotation()
        self.up = self.stage.up_axis

    def apply(self):
        self.prim.set_attribute("inputs:texture:file", self.rng.choice(self.maps))
        self.prim.set_rotation(_matmul(_turn(self.up, math.radians(self.rng.uniform(*self.rotation))),
                                       self.base_rotation))
        if self.intensity != (0.0, 0.0):
            self.prim.set_attribute("inputs:intensity", self.rng.uniform(*self.intensity))

    def _folder_maps(self):
        folder = self.get_exposed_variable("textures:folder")
        if not folder:
            return []
        found = self.stage.resolve_asset(folder)
        if found is None or not os.path.isdir(found):
            raise ValueError(f"domeRandomizer: textures:folder '{folder}' is not a folder below the scene's "
                             "folder or its asset roots")
        names = sorted(n for n in os.listdir(found) if n.lower().endswith(IMAGE_EXTENSIONS))
        if not names:
            raise ValueError(f"domeRandomizer: textures:folder '{folder}' holds no "
                             f"{', '.join(IMAGE_EXTENSIONS)} image")
        return [os.path.join(found, n) for n in names]

    def _ordered(self, name):
        low, high = self.get_exposed_variable(name)
        if low > high:
            raise ValueError(f"domeRandomizer.{name}: min exceeds max ({low} > {high})")
        return float(low), float(high)


def _turn(up_axis, angle):
    """The rotation by `angle` radians about the stage's up axis (rows)."""
    c, s = math.cos(angle), math.sin(angle)
    if up_axis == "Y":
        return ((c, 0.0, s), (0.0, 1.0, 0.0), (-s, 0.0, c))
    return ((c, -s, 0.0), (s, c, 0.0), (0.0, 0.0, 1.0))


def _matmul(a, b):
    return tuple(tuple(sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)) for i in range(3))
