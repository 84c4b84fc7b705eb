"""One (frame, render product) of a BasicWriter dataset, read on demand into numpy."""
import json
import os

import numpy as np
from PIL import Image

from .colors import decode_mask
from .folder import DatasetError
from .records import Boxes2D, Boxes3D, Segmentation, camera_from_params

BOX2D_DTYPE = np.dtype([("semanticId", "<u4"), ("x_min", "<i4"), ("y_min", "<i4"), ("x_max", "<i4"),
                        ("y_max", "<i4"), ("occlusionRatio", "<f4")])
BOX3D_DTYPE = np.dtype([("semanticId", "<u4"), ("x_min", "<f4"), ("y_min", "<f4"), ("z_min", "<f4"),
                        ("x_max", "<f4"), ("y_max", "<f4"), ("z_max", "<f4"), ("transform", "<f4", (4, 4)),
                        ("occlusionRatio", "<f4")])
# lidar_<sensor>_X.npy: one row per LiDAR point (docs/writers.md, "lidar").
LIDAR_DTYPE = np.dtype([("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("range", "<f4"), ("intensity", "<f4"),
                        ("ring", "<u2"), ("azimuth", "<f4"), ("time", "<f4"), ("semantic_id", "<u4"),
                        ("instance_id", "<u4")])
# The BasicWriter options; a file kind belongs to the longest one it starts with
# ("instance_id_segmentation_mapping" to instance_id_segmentation), for the message when one is missing.
_OPTIONS = ("rgb", "hdr_color", "bounding_box_2d_tight", "bounding_box_2d_loose", "bounding_box_3d",
            "semantic_segmentation", "instance_id_segmentation", "instance_segmentation", "distance_to_camera",
            "distance_to_image_plane", "occlusion", "normals", "camera_params", "pointcloud", "motion_vectors",
            "forward_flow", "backward_flow", "lidar")


def _option_of(kind):
    return max((o for o in _OPTIONS if kind.startswith(o)), key=len, default=kind)


class MissingAnnotation(DatasetError, KeyError):
    """The frame has no file of this kind: the scene's writer did not enable its annotator."""

    def __str__(self):
        return self.args[0]


class Frame:
    """One frame of one render product (camera). `number` is the run's frame number, `camera` the
    render product's name (its camera prim's name), `files` {kind: {ext: relative path}}.

    Each reader returns fresh numpy arrays; nothing is cached, so a Frame is cheap to hold."""

    def __init__(self, root, number, camera, files):
        self.root, self.number, self.camera, self.files = root, number, camera, files

    def __repr__(self):
        return f"Frame({self.number}, camera={self.camera!r}, kinds={sorted(self.files)})"

    def has(self, kind):
        """Whether the frame has a file of this kind (an annotator name such as "rgb")."""
        return kind in self.files

    def path(self, kind, ext=None):
        """The absolute path of the frame's `kind` file (with `ext` when it has several)."""
        found = self.files.get(kind)
        if not found or (ext and ext not in found):
            option = _option_of(kind)
            raise MissingAnnotation(f"{self.root}: frame {self.number} of {self.camera} has no {kind}"
                                    f"{'.' + ext if ext else ''} file; the scene's writer did not enable it "
                                    f"(writer.{option}: true)")
        return os.path.join(self.root, found[ext] if ext else next(iter(found.values())))

    def _json(self, kind):
        with open(self.path(kind, "json"), encoding="utf-8") as f:
            return json.load(f)

    def _png(self, kind):
        with Image.open(self.path(kind, "png")) as image:
            return np.asarray(image)

    def _npy(self, kind):
        return np.load(self.path(kind, "npy"), allow_pickle=False)

    # Images -----------------------------------------------------------------
    def rgba(self):
        """(H, W, 4) uint8."""
        return self._png("rgb")

    def rgb(self):
        """(H, W, 3) uint8."""
        return np.ascontiguousarray(self.rgba()[..., :3])

    def hdr_color(self):
        """(H, W, 3) float32 linear radiance (render.mode: pathtraced)."""
        return self._npy("hdr_color")

    def distance_to_camera(self):
        """(H, W) float32 metres from the camera centre, +inf where nothing was hit."""
        return self._npy("distance_to_camera")

    def distance_to_image_plane(self):
        """(H, W) float32 metres along the optical axis, +inf where nothing was hit."""
        return self._npy("distance_to_image_plane")

    def depth(self):
        """distance_to_image_plane (the z-depth most code calls depth), else distance_to_camera."""
        if self.has("distance_to_image_plane"):
            return self.distance_to_image_plane()
        return self.distance_to_camera()

    def normals(self):
        """(H, W, 3) float32 world-space unit normals decoded from normals_X.png (8-bit precision)."""
        encoded = self._png("normals")[..., :3].astype(np.float32)
        return encoded / 255.0 * 2.0 - 1.0

    # Segmentation -----------------------------------------------------------
    def _ids(self, kind, mapping_kind):
        """(H, W) uint32 ids and {key: id} for the JSON keys (colour text or decimal ids)."""
        image = self._png(kind)
        mapping = self._json(mapping_kind)
        if image.ndim == 3:
            return (*decode_mask(image, list(mapping)), mapping)
        return image.astype(np.uint32), {k: int(k) for k in mapping}, mapping

    def semantic_segmentation(self):
        """Segmentation: semantic ids (shared with the boxes' semanticId) and their labels."""
        ids, key_ids, labels = self._ids("semantic_segmentation", "semantic_segmentation_labels")
        return Segmentation(ids=ids, labels={key_ids[k]: v for k, v in labels.items()})

    def instance_segmentation(self):
        """Segmentation: one id per labelled entity (0 BACKGROUND, 1 UNLABELLED), its prim path and
        labels."""
        ids, key_ids, paths = self._ids("instance_segmentation", "instance_segmentation_mapping")
        labels = self._json("instance_segmentation_semantics_mapping")
        return Segmentation(ids=ids, paths={key_ids[k]: v for k, v in paths.items()},
                            labels={key_ids[k]: v for k, v in labels.items() if k in key_ids})

    def instance_id_segmentation(self):
        """Segmentation: one id per geometry prim (its render id) and its prim path."""
        ids, key_ids, paths = self._ids("instance_id_segmentation", "instance_id_segmentation_mapping")
        return Segmentation(ids=ids, paths={key_ids[k]: v for k, v in paths.items()})

    # Boxes ------------------------------------------------------------------
    def _labelled_rows(self, kind, dtype):
        rows = self._npy(kind)
        if rows.dtype != dtype:
            raise DatasetError(f"{self.path(kind, 'npy')}: dtype {rows.dtype}, expected {dtype}")
        labels = {int(k): v for k, v in self._json(kind + "_labels").items()}
        paths = self._json(kind + "_prim_paths")
        if len(paths) != len(rows):
            raise DatasetError(f"{self.path(kind + '_prim_paths', 'json')}: {len(paths)} paths for {len(rows)} rows")
        return rows, labels, paths

    def _boxes_2d(self, kind):
        rows, labels, paths = self._labelled_rows(kind, BOX2D_DTYPE)
        xyxy = np.stack([rows["x_min"], rows["y_min"], rows["x_max"], rows["y_max"]], axis=1).astype(np.int32)
        return Boxes2D(xyxy=xyxy.reshape(-1, 4), semantic_ids=rows["semanticId"].copy(), labels=labels,
                       prim_paths=paths, occlusion=rows["occlusionRatio"].copy())

    def bounding_box_2d_tight(self):
        """Boxes2D around each entity's visible pixels."""
        return self._boxes_2d("bounding_box_2d_tight")

    def bounding_box_2d_loose(self):
        """Boxes2D around each entity's full projection, occluders ignored."""
        return self._boxes_2d("bounding_box_2d_loose")

    def bounding_box_3d(self):
        """Boxes3D of the entities in or near the view."""
        rows, labels, paths = self._labelled_rows("bounding_box_3d", BOX3D_DTYPE)
        lo = np.stack([rows["x_min"], rows["y_min"], rows["z_min"]], axis=1).reshape(-1, 3)
        hi = np.stack([rows["x_max"], rows["y_max"], rows["z_max"]], axis=1).reshape(-1, 3)
        return Boxes3D(extent_min=lo, extent_max=hi, local_to_world=np.transpose(rows["transform"], (0, 2, 1)).copy(),
                       semantic_ids=rows["semanticId"].copy(), labels=labels, prim_paths=paths,
                       occlusion=rows["occlusionRatio"].copy())

    def occlusion(self):
        """Structured (N,) array (instanceId, semanticId, occlusionRatio), one row per entity."""
        return self._npy("occlusion")

    # Motion ------------------------------------------------------------------
    def _flow(self, kind, channels):
        flow = self._npy(kind)
        if flow.dtype != np.float32 or flow.ndim != 3 or flow.shape[2] != channels:
            raise DatasetError(f"{self.path(kind, 'npy')}: {flow.dtype} {flow.shape}, "
                               f"expected float32 (H, W, {channels})")
        return flow

    def forward_flow(self):
        """(H, W, 2) float32 (delta row, delta column) pixels to where each pixel's surface point is in
        the next frame (Kubric's layout; 0 in an iteration's last frame)."""
        return self._flow("forward_flow", 2)

    def backward_flow(self):
        """(H, W, 2) float32 (delta row, delta column) pixels to where each pixel's surface point was
        in the previous frame (0 in an iteration's first frame)."""
        return self._flow("backward_flow", 2)

    def motion_vectors(self):
        """(H, W, 4) float32 in Isaac's layout: x, y pixels moved since the previous frame, x positive
        to the left, y positive upward, z and w 0."""
        return self._flow("motion_vectors", 4)

    # Camera and points ------------------------------------------------------
    def camera_params(self):
        """Camera: view and projection matrices, intrinsics K, resolution (camera_params_X.json)."""
        return camera_from_params(self._json("camera_params"))

    def pointcloud(self):
        """{"points" (N, 3) f4 world, "rgb" (N, 4) u1, "normals" (N, 4) f4, "semantic" (N,) u4,
        "instance" (N,) u4}: the labelled pixels (unlabelled too with pointcloud_include_unlabelled)."""
        out = {"points": self._npy("pointcloud")}
        for part in ("rgb", "normals", "semantic", "instance"):
            out[part] = self._npy("pointcloud_" + part)
        return out

    # LiDAR ------------------------------------------------------------------
    def lidar_sensors(self):
        """Names of the Lidar prims with a sweep in this frame, sorted (sweeps belong to the first
        camera's frames)."""
        return sorted(k[len("lidar_"):] for k, exts in self.files.items() if k.startswith("lidar_") and "npy" in exts)

    def _lidar_kind(self, sensor):
        if sensor is None:
            sensors = self.lidar_sensors()
            if not sensors:
                raise MissingAnnotation(f"{self.root}: frame {self.number} of {self.camera} has no LiDAR sweep; "
                                        f"the scene's writer did not enable it (writer.lidar: true), or the "
                                        f"sweeps are in the first camera's frames")
            sensor = sensors[0]
        return "lidar_" + sensor

    def lidar(self, sensor=None):
        """(N,) structured array of LIDAR_DTYPE: x, y, z (sensor frame, metres), range, intensity,
        ring, azimuth (degrees), time (seconds in the sweep), semantic_id, instance_id. `sensor`
        names the Lidar prim; the default is the first of lidar_sensors()."""
        points = self._npy(self._lidar_kind(sensor))
        return points.astype(LIDAR_DTYPE, copy=False)

    def lidar_info(self, sensor=None):
        """The sweep's JSON: "world_from_sensor" as a (4, 4) float64 array (scene units), "pattern",
        "semantic_labels" {id: {taxonomy: label}}, "instance_paths" {id: prim path}, ids as ints."""
        info = self._json(self._lidar_kind(sensor))
        info["world_from_sensor"] = np.array(info["world_from_sensor"], dtype=np.float64)
        info["semantic_labels"] = {int(k): v for k, v in info["semantic_labels"].items()}
        info["instance_paths"] = {int(k): v for k, v in info["instance_paths"].items()}
        return info

    def lidar_kitti(self, sensor=None):
        """(N, 4) float32 x, y, z, intensity from KITTI's .bin (writer.lidar_kitti: true)."""
        return np.fromfile(self.path(self._lidar_kind(sensor), "bin"), dtype="<f4").reshape(-1, 4)

    # Anything else ----------------------------------------------------------
    def load(self, kind, ext=None):
        """The frame's `kind` file as it is: .npy -> array, .png -> array, .json -> value."""
        path = self.path(kind, ext)
        if path.endswith(".npy"):
            return np.load(path, allow_pickle=False)
        if path.endswith(".png"):
            with Image.open(path) as image:
                return np.asarray(image)
        with open(path, encoding="utf-8") as f:
            return json.load(f)
