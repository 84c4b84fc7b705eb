"""cameraOrbit: puts a camera (or any Xformable prim) at a random point on a
shell around a target and aims it there.

On every apply the prim is moved to

    target + distance * (cos(elevation) * (cos(azimuth) * e1 + sin(azimuth) * e2)
                         + sin(elevation) * up)

with azimuth, elevation (degrees) and distance drawn uniformly, in that order,
from their ranges; e1, e2, up are an orthonormal frame around `upAxis`:
azimuth 0 is world X projected onto the ground plane (world Y when up is
within about 25 degrees of X), and azimuth grows counter-clockwise seen
from above. The prim is then turned so that its local -Z looks at the target
with +Y toward `upAxis` (a camera's convention), as lookAtBehavior does.

The target is `targetPrimPath`'s world position when it is set, else the
world point `targetLocation`; a prim target that moves (it has a behavior
of its own) is followed, as long as it comes before this prim in the
scene, since behaviors run in stage order.

Exposed variables (attributes exposedVar:cameraOrbit:<name>):
    targetPrimPath  string    ""            prim to orbit; wins over targetLocation
    targetLocation  vector3d  (0, 0, 0)     world point to orbit when no prim is given
    azimuthRange    float2    (0, 360)      degrees around upAxis
    elevationRange  float2    (15, 60)      degrees above the ground plane (-90 .. 90)
    distanceRange   float2    (4, 8)        distance from the target (>= 0)
    upAxis          vector3d  (0, 0, 1)     world up
    interval        uint      0             apply every N updates; 0: every update
    seed            int       -1            -1 derives the stream from the run seed; >= 0 fixes it

Example (a whole scene: scenes/examples/camera_orbit.yaml):

    scripts: [scripts/camera_orbit.py]
    prims:
      /World/Camera:
        type: Camera
        behaviors:
          cameraOrbit:
            targetPrimPath: /World/Statue
            azimuthRange: [0, 360]
            elevationRange: [10, 50]
            distanceRange: [3, 5]
"""
import math

import sdgbehave


def _normalized(v):
    n = math.sqrt(sum(x * x for x in v))
    return tuple(x / n for x in v)


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def orbit_frame(up):
    """(e1, e2, u): an orthonormal, right-handed frame with u along `up`; e1 is
    world X (or Y when up is close to X) projected onto the plane normal to u."""
    u = _normalized(up)
    reference = (1.0, 0.0, 0.0) if abs(u[0]) < 0.9 else (0.0, 1.0, 0.0)
    e1 = _normalized(tuple(r - _dot(reference, u) * c for r, c in zip(reference, u)))
    e2 = _cross(u, e1)
    return e1, e2, u


def orbit_point(target, frame, azimuth_deg, elevation_deg, distance):
    """The world point at (azimuth, elevation, distance) from target in frame."""
    e1, e2, u = frame
    az, el = math.radians(azimuth_deg), math.radians(elevation_deg)
    ground = math.cos(el)
    return tuple(t + distance * (ground * (math.cos(az) * a + math.sin(az) * b) + math.sin(el) * c)
                 for t, a, b, c in zip(target, e1, e2, u))


class CameraOrbit(sdgbehave.IntervalBehavior):
    """Places a camera at a random azimuth, elevation and distance around a target prim or point and aims it there."""

    BEHAVIOR_NS = "cameraOrbit"
    VARIABLES_TO_EXPOSE = [
        {"attr_name": "targetPrimPath", "attr_type": "string", "default_value": "", "prim_path": True,
         "doc": "Prim to orbit (its world position); when set it wins over targetLocation."},
        {"attr_name": "targetLocation", "attr_type": "vector3d", "default_value": (0.0, 0.0, 0.0),
         "doc": "World point to orbit when targetPrimPath is empty."},
        {"attr_name": "azimuthRange", "attr_type": "float2", "default_value": (0.0, 360.0),
         "doc": "Azimuth around upAxis, degrees (min, max); 0 is world X projected onto the ground plane."},
        {"attr_name": "elevationRange", "attr_type": "float2", "default_value": (15.0, 60.0),
         "doc": "Elevation above the ground plane, degrees (min, max), within -90 .. 90."},
        {"attr_name": "distanceRange", "attr_type": "float2", "default_value": (4.0, 8.0), "minimum": 0,
         "doc": "Distance from the target (min, max), scene units."},
        {"attr_name": "upAxis", "attr_type": "vector3d", "default_value": (0.0, 0.0, 1.0),
         "doc": "World up: the orbit's pole and the camera's +Y direction."},
        {"attr_name": "seed", "attr_type": "int", "default_value": -1,
         "doc": "-1 derives the stream from the run seed; >= 0 fixes it."},
    ]

    def setup(self):
        if not self.prim.is_xformable:
            raise ValueError(f"{self.prim_path} is a {self.prim.type_name}, which has no transform to orbit")
        self.azimuth = self._range("azimuthRange")
        self.elevation = self._range("elevationRange")
        self.distance = self._range("distanceRange")
        if self.elevation[0] < -90 or self.elevation[1] > 90:
            raise ValueError(f"cameraOrbit.elevationRange must lie within -90 .. 90, found {self.elevation}")
        self.up = self.get_exposed_variable("upAxis")
        if _dot(self.up, self.up) == 0:
            raise ValueError("cameraOrbit.upAxis must not be (0, 0, 0)")
        self.frame = orbit_frame(self.up)
        self.location = self.get_exposed_variable("targetLocation")
        self.target = None
        path = self.get_exposed_variable("targetPrimPath")
        if path:
            self.target = self.stage.get_prim(path)
            if self.target is None or not self.target.is_xformable:
                self.log.warn(f"invalid target prim path {path}; orbiting targetLocation instead")
                self.target = None

    def apply(self):
        target = self.target.get_world_location() if self.target is not None else self.location
        azimuth = self.rng.uniform(*self.azimuth)
        elevation = self.rng.uniform(*self.elevation)
        distance = self.rng.uniform(*self.distance)
        eye = orbit_point(target, self.frame, azimuth, elevation, distance)
        self.prim.set_world_location(eye)
        rotation = sdgbehave.look_at_rotation(eye, target, self.up)
        if rotation is not None:  # None: a distance of 0 puts the camera on the target; keep its aim
            self.prim.set_world_rotation(rotation)

    def _range(self, name):
        low, high = self.get_exposed_variable(name)
        if low > high:
            raise ValueError(f"cameraOrbit.{name}: the minimum {low} exceeds the maximum {high}")
        return low, high
