"""BOP datasets (the 6D pose benchmark's scenewise format, as the BOP toolkit reads it) into numpy.

Layout: <root>/camera.json, <root>/models/models_info.json and
obj_XXXXXX.ply, and per split and scene <root>/<split>/<scene_id:06d>/ with
scene_camera.json, scene_gt.json, scene_gt_info.json and the image folders
rgb/ (or gray/), depth/, mask/ and mask_visib/ (<im_id:06d>[_<gt_id:06d>].png
or .jpg/.tif). Poses map model points (mm) into OpenCV camera axes (mm);
depth images times depth_scale are millimetres."""
import json
import os
import re

import numpy as np
from PIL import Image

from .folder import DatasetError, read_json
from .ply import read_ply

_SCENE = re.compile(r"^[0-9]{6}$")
_IMAGE_EXTS = (".png", ".jpg", ".jpeg", ".tif", ".tiff")


def _image(folder, stem):
    for ext in _IMAGE_EXTS:
        path = os.path.join(folder, stem + ext)
        if os.path.isfile(path):
            with Image.open(path) as image:
                return np.asarray(image)
    raise DatasetError(f"{folder}/{stem}: no image ({', '.join(_IMAGE_EXTS)})")


class BopImage:
    """One image of a BOP scene: its camera, its annotated object instances and its images.

    K (3, 3), depth_scale (depth image x depth_scale = mm), R_w2c (3, 3) and t_w2c (3,) mm when the
    scene records the camera pose (else None); objects: one dict per annotated instance, in gt
    order: obj_id, R_m2c (3, 3), t_m2c (3,) mm, and where scene_gt_info.json has them bbox_obj,
    bbox_visib ([x, y, width, height]), px_count_all, px_count_valid, px_count_visib, visib_fract."""

    def __init__(self, folder, image_id, camera, gts, infos):
        self.folder, self.image_id = folder, image_id
        self.K = np.array(camera["cam_K"], dtype=np.float64).reshape(3, 3)
        self.depth_scale = float(camera.get("depth_scale", 1.0))
        self.R_w2c = np.array(camera["cam_R_w2c"], dtype=np.float64).reshape(3, 3) if "cam_R_w2c" in camera else None
        self.t_w2c = np.array(camera["cam_t_w2c"], dtype=np.float64).reshape(3) if "cam_t_w2c" in camera else None
        self.objects = []
        for n, gt in enumerate(gts):
            entry = {"obj_id": int(gt["obj_id"]),
                     "R_m2c": np.array(gt["cam_R_m2c"], dtype=np.float64).reshape(3, 3),
                     "t_m2c": np.array(gt["cam_t_m2c"], dtype=np.float64).reshape(3)}
            if n < len(infos):
                entry.update(infos[n])
            self.objects.append(entry)

    def __repr__(self):
        return f"BopImage({self.image_id}, {len(self.objects)} objects)"

    def rgb(self):
        """(H, W, 3) uint8 (gray/ images as (H, W))."""
        folder = os.path.join(self.folder, "rgb")
        if not os.path.isdir(folder):
            folder = os.path.join(self.folder, "gray")
        image = _image(folder, f"{self.image_id:06d}")
        return image[..., :3] if image.ndim == 3 else image

    def depth(self):
        """(H, W) float32 millimetres (0 where the depth image has no value)."""
        raw = _image(os.path.join(self.folder, "depth"), f"{self.image_id:06d}")
        return raw.astype(np.float32) * np.float32(self.depth_scale)

    def mask(self, gt_index):
        """(H, W) bool silhouette of annotated instance `gt_index`, occluders ignored."""
        return _image(os.path.join(self.folder, "mask"), f"{self.image_id:06d}_{gt_index:06d}") > 0

    def mask_visib(self, gt_index):
        """(H, W) bool visible part of annotated instance `gt_index`."""
        return _image(os.path.join(self.folder, "mask_visib"), f"{self.image_id:06d}_{gt_index:06d}") > 0

    def project(self, points_model, gt_index):
        """(N, 3) model points (mm) of instance `gt_index` -> (N, 2) pixel coordinates in cam_K's
        convention and (N,) depths (mm): s [u, v, 1] = K (R_m2c p + t_m2c). BOP's cam_K (the BOP
        toolkit's renderers, sdgbehave's BopWriter) puts pixel (i, j) at [i, i+1] x [j, j+1], its
        centre at (i + 0.5, j + 0.5)."""
        o = self.objects[gt_index]
        camera = np.asarray(points_model, dtype=np.float64) @ o["R_m2c"].T + o["t_m2c"]
        uv = camera @ self.K.T
        return uv[:, :2] / uv[:, 2:3], camera[:, 2]


class BopScene:
    """The images of one scene folder (<split>/<scene_id:06d>), by image id ascending."""

    def __init__(self, folder):
        self.folder = folder
        cameras = read_json(os.path.join(folder, "scene_camera.json"), "the BOP scene's cameras")
        gts = read_json(os.path.join(folder, "scene_gt.json"), "the BOP scene's poses")
        info_path = os.path.join(folder, "scene_gt_info.json")
        infos = read_json(info_path, "the BOP scene's pose information") if os.path.isfile(info_path) else {}
        self.image_ids = sorted(int(k) for k in cameras)
        self._images = [BopImage(folder, i, cameras[str(i)], gts.get(str(i), []), infos.get(str(i), []))
                        for i in self.image_ids]

    def __len__(self):
        return len(self._images)

    def __getitem__(self, index):
        return self._images[index]

    def __iter__(self):
        return iter(self._images)

    def __repr__(self):
        return f"BopScene({self.folder!r}, {len(self)} images)"


class BopDataset:
    """A BOP dataset folder: camera.json, the models and the scenes of each split.

    splits: the split folders (those holding six-digit scene folders), sorted; scene_ids(split);
    scene(split, scene_id) -> BopScene; scenes(split) the BopScenes in id order; camera: camera.json;
    models_info: {obj_id: {diameter, min_x, ..., size_z, symmetries_*}}; model_path(obj_id) and
    model(obj_id), the PLY read into numpy."""

    def __init__(self, root, models="models"):
        self.root = os.fspath(root)
        if not os.path.isdir(self.root):
            raise DatasetError(f"{self.root}: not a folder")
        camera = os.path.join(self.root, "camera.json")
        self.camera = read_json(camera, "the BOP camera") if os.path.isfile(camera) else None
        self.models_folder = os.path.join(self.root, models)
        info = os.path.join(self.models_folder, "models_info.json")
        infos = read_json(info, "the BOP models' information") if os.path.isfile(info) else {}
        self.models_info = {int(k): v for k, v in infos.items()}
        self.splits = sorted(name for name in os.listdir(self.root) if self._scene_folders(name))
        if not self.splits:
            raise DatasetError(f"{self.root}: not a BOP dataset: no <split>/<scene_id:06d>/scene_gt.json")

    def _scene_folders(self, split):
        folder = os.path.join(self.root, split)
        if not os.path.isdir(folder):
            return []
        return sorted(n for n in os.listdir(folder)
                      if _SCENE.match(n) and os.path.isfile(os.path.join(folder, n, "scene_gt.json")))

    def scene_ids(self, split):
        return [int(n) for n in self._scene_folders(split)]

    def scene(self, split, scene_id):
        folder = os.path.join(self.root, split, f"{scene_id:06d}")
        if not os.path.isdir(folder):
            raise DatasetError(f"{folder}: no such scene (the split has {self.scene_ids(split)})")
        return BopScene(folder)

    def scenes(self, split):
        return [self.scene(split, i) for i in self.scene_ids(split)]

    def model_path(self, obj_id):
        return os.path.join(self.models_folder, f"obj_{obj_id:06d}.ply")

    def model(self, obj_id):
        """The object's model (mm): {"vertices" (N, 3), "faces" (M, 3), "properties"} (read_ply)."""
        return read_ply(self.model_path(obj_id))
