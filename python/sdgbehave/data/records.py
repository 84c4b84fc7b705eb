"""What a frame's annotations read into: plain classes holding numpy arrays."""
from dataclasses import dataclass, field

import numpy as np


@dataclass
class Segmentation:
    """A per-pixel id image and what each id means.

    ids: (H, W) uint32. Colourised masks are decoded back to their ids, so
    raw and colourised outputs read alike.
    labels: {id: {taxonomy: label}} (semantic and instance segmentation).
    paths: {id: prim path} (instance and instance-id segmentation; 0 and 1
    of instance segmentation are "BACKGROUND" and "UNLABELLED")."""
    ids: np.ndarray
    labels: dict = field(default_factory=dict)
    paths: dict = field(default_factory=dict)

    def mask(self, ident):
        """(H, W) bool: the pixels of one id."""
        return self.ids == ident


@dataclass
class Boxes2D:
    """2D boxes, one row per labelled entity in stage order.

    xyxy: (N, 4) int32 inclusive pixel bounds (x_min, y_min, x_max, y_max) as
    the BasicWriter writes them; `xyxy_float()` gives torchvision's
    continuous corners (x_max + 1, y_max + 1).
    semantic_ids: (N,) uint32; labels: {semantic id: {taxonomy: label}};
    prim_paths: N entity prim paths; occlusion: (N,) float32 hidden fraction."""
    xyxy: np.ndarray
    semantic_ids: np.ndarray
    labels: dict
    prim_paths: list
    occlusion: np.ndarray

    def __len__(self):
        return len(self.xyxy)

    def xyxy_float(self):
        """(N, 4) float32 corners with the far edge exclusive: the boxes torchvision expects."""
        out = self.xyxy.astype(np.float32)
        out[:, 2:] += 1.0
        return out

    def label_names(self, taxonomy="class"):
        """N label strings of one taxonomy ("" where an entity has none)."""
        return [self.labels.get(int(i), {}).get(taxonomy, "") for i in self.semantic_ids]


@dataclass
class Boxes3D:
    """3D boxes: local extents of each entity in its root prim's frame and that frame's
    local-to-world transform, in scene units (x metres_per_unit for metres).

    extent_min, extent_max: (N, 3) float32; local_to_world: (N, 4, 4) float32
    in the column-vector convention (point_world = M @ [x, y, z, 1]; the .npy
    holds its transpose, USD's row-vector layout)."""
    extent_min: np.ndarray
    extent_max: np.ndarray
    local_to_world: np.ndarray
    semantic_ids: np.ndarray
    labels: dict
    prim_paths: list
    occlusion: np.ndarray

    def __len__(self):
        return len(self.extent_min)

    def corners(self):
        """(N, 8, 3) float64 world-space corners (x varies slowest, z fastest)."""
        lo, hi = self.extent_min.astype(np.float64), self.extent_max.astype(np.float64)
        bits = np.array([[i >> 2 & 1, i >> 1 & 1, i & 1] for i in range(8)], dtype=np.float64)
        local = lo[:, None, :] + bits[None] * (hi - lo)[:, None, :]
        homogeneous = np.concatenate([local, np.ones(local.shape[:2] + (1,))], axis=2)
        world = np.einsum("nij,nkj->nki", self.local_to_world.astype(np.float64), homogeneous)
        return world[..., :3] / world[..., 3:4]


@dataclass
class Camera:
    """A render product's camera for one frame (from camera_params_X.json).

    world_to_camera: (4, 4) float64, column-vector convention, USD camera axes
    (x right, y up, looking down -z), scene units.
    world_to_camera_cv: the same in OpenCV axes (x right, y down, z forward).
    projection: (4, 4) float64 column-vector OpenGL-style projection
    (reverse-Z, infinite far for perspective cameras).
    K: (3, 3) float64 pinhole intrinsics in pixels, OpenCV convention (pixel
    centres at integer coordinates), or None for an orthographic camera.
    resolution: (width, height); meters_per_unit; model ("pinhole",
    "orthographic"); raw: the JSON as written (every Replicator key)."""
    world_to_camera: np.ndarray
    world_to_camera_cv: np.ndarray
    projection: np.ndarray
    K: object
    resolution: tuple
    meters_per_unit: float
    model: str
    raw: dict

    def project(self, points_world):
        """(N, 3) world points -> (N, 2) pixel coordinates (OpenCV convention) and (N,) depth along
        the optical axis in scene units, through the projection matrix as the renderer does."""
        p = np.asarray(points_world, dtype=np.float64)
        homogeneous = np.concatenate([p, np.ones((len(p), 1))], axis=1)
        camera = homogeneous @ self.world_to_camera.T
        clip = camera @ self.projection.T
        ndc = clip[:, :2] / clip[:, 3:4]
        width, height = self.resolution
        pixels = np.stack([(ndc[:, 0] + 1) * width / 2 - 0.5, (1 - ndc[:, 1]) * height / 2 - 0.5], axis=1)
        return pixels, -camera[:, 2]


def camera_from_params(params):
    """A Camera from the JSON of camera_params_X.json."""
    width, height = (int(v) for v in params["renderProductResolution"])
    view = np.array(params["cameraViewTransform"], dtype=np.float64).reshape(4, 4).T
    projection = np.array(params["cameraProjection"], dtype=np.float64).reshape(4, 4).T
    model = str(params.get("cameraModel", "pinhole"))
    K = None
    if model != "orthographic":
        # u = W/2 (1 + x_ndc) - 1/2 with x_ndc = (P00 x + P02 z) / -z; OpenCV's z is USD's -z.
        fx, fy = projection[0, 0] * width / 2, projection[1, 1] * height / 2
        cx = width / 2 * (1 - projection[0, 2]) - 0.5
        cy = height / 2 * (1 + projection[1, 2]) - 0.5
        K = np.array([[fx, 0, cx], [0, fy, cy], [0, 0, 1]], dtype=np.float64)
    flip = np.diag([1.0, -1.0, -1.0, 1.0])
    return Camera(world_to_camera=view, world_to_camera_cv=flip @ view, projection=projection, K=K,
                  resolution=(width, height), meters_per_unit=float(params.get("metersPerSceneUnit", 1.0)),
                  model=model, raw=params)
