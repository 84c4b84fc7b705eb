"""A torch.utils.data.Dataset over an sdgbehave dataset, with torchvision's detection targets,
and a collate function for batches of frames with different numbers of boxes.

torch is imported only by this module, so `sdgbehave.data` reads datasets
into numpy without it."""
import numpy as np
import torch

from .dataset import Dataset
from .folder import DatasetError


class TorchDataset(torch.utils.data.Dataset):
    """Item i is (image, target) for the dataset's frame i:

    image: float32 tensor (3, H, W) in [0, 1];
    target: {"boxes": float32 (N, 4) XYXY pixels, far edges exclusive (tight boxes by default,
    `boxes="loose"` for the full extents); "labels": int64 (N,) class indices from 1, 0 being
    the background (`class_names[i]` is the name of index i);
    "masks": uint8 (N, H, W) each box's instance mask (when the dataset has
    instance_segmentation; `masks=False` leaves them out); "semantic": int64 (H, W) class index
    per pixel, 0 background and unlabelled (when it has semantic_segmentation; `semantic=False`
    leaves it out); "image_id": int64 the run's frame number; "camera": the render product;
    with `lidar=True`, "lidar": {sensor: {"points": float32 (N, 3) sensor frame, "intensity":
    float32 (N,), "labels": int64 (N,) class indices as above, "instance": int64 (N,) instance ids}}
    for the frame's LiDAR sweeps (empty for frames without)}.

    `classes` fixes the class list (names of `taxonomy`, default the dataset's sorted labels);
    entities whose label is not in it are dropped. `transforms(image, target)` runs last.
    Other arguments are Dataset's (`verify`, `camera`)."""

    def __init__(self, root, boxes="tight", masks=True, semantic=True, classes=None, taxonomy="class",
                 transforms=None, verify=True, camera=None, lidar=False):
        if boxes not in ("tight", "loose"):
            raise ValueError(f"boxes: expected 'tight' or 'loose', found {boxes!r}")
        self.dataset = Dataset(root, verify=verify, camera=camera)
        self.boxes, self.masks, self.semantic, self.lidar = boxes, masks, semantic, lidar
        self.taxonomy, self.transforms = taxonomy, transforms
        self.classes = list(classes) if classes is not None else self.dataset.classes(taxonomy)
        # 0 is the background, as torchvision's detection models expect.
        self.class_names = ["__background__"] + self.classes
        self._index = {name: i + 1 for i, name in enumerate(self.classes)}
        kind = "bounding_box_2d_" + boxes
        if self.dataset and not self.dataset[0].has(kind):
            raise DatasetError(f"{self.dataset.root}: the frames have no {kind} (writer.{kind}: true)")

    def __len__(self):
        return len(self.dataset)

    def _class_index(self, labels):
        """The class index of a {taxonomy: label} dict; 0 when it is not a class of the list."""
        return self._index.get(labels.get(self.taxonomy, ""), 0)

    def __getitem__(self, index):
        frame = self.dataset[index]
        image = torch.from_numpy(frame.rgb()).permute(2, 0, 1).float().div_(255.0)
        found = frame.bounding_box_2d_tight() if self.boxes == "tight" else frame.bounding_box_2d_loose()
        labels = np.array([self._class_index(found.labels.get(int(i), {})) for i in found.semantic_ids],
                          dtype=np.int64)
        keep = labels > 0
        target = {"boxes": torch.from_numpy(found.xyxy_float()[keep].reshape(-1, 4)),
                  "labels": torch.from_numpy(labels[keep]),
                  "image_id": torch.tensor(frame.number, dtype=torch.int64),
                  "camera": frame.camera}
        height, width = image.shape[1:]
        if self.masks and frame.has("instance_segmentation"):
            instances = frame.instance_segmentation()
            id_of = {path: ident for ident, path in instances.paths.items()}
            paths = [p for p, k in zip(found.prim_paths, keep) if k]
            masks = np.zeros((len(paths), height, width), dtype=np.uint8)
            for n, path in enumerate(paths):
                if path in id_of:
                    masks[n] = instances.ids == id_of[path]
            target["masks"] = torch.from_numpy(masks)
        if self.semantic and frame.has("semantic_segmentation"):
            semantic = frame.semantic_segmentation()
            lookup = {ident: self._class_index(labels) for ident, labels in semantic.labels.items()}
            present, inverse = np.unique(semantic.ids, return_inverse=True)
            classes = np.array([lookup.get(int(i), 0) for i in present], dtype=np.int64)
            target["semantic"] = torch.from_numpy(classes[inverse].reshape(semantic.ids.shape))
        if self.lidar:
            target["lidar"] = {sensor: self._lidar_target(frame, sensor) for sensor in frame.lidar_sensors()}
        if self.transforms is not None:
            image, target = self.transforms(image, target)
        return image, target


    def _lidar_target(self, frame, sensor):
        points = frame.lidar(sensor)
        labels = frame.lidar_info(sensor)["semantic_labels"]
        lookup = {ident: self._class_index(names) for ident, names in labels.items()}
        classes = np.array([lookup.get(int(i), 0) for i in points["semantic_id"]], dtype=np.int64)
        xyz = np.stack([points["x"], points["y"], points["z"]], axis=1).astype(np.float32)
        return {"points": torch.from_numpy(xyz), "intensity": torch.from_numpy(points["intensity"].copy()),
                "labels": torch.from_numpy(classes),
                "instance": torch.from_numpy(points["instance_id"].astype(np.int64))}


def collate(batch):
    """(images, targets) of a list of (image, target): images stacked into one (B, 3, H, W) tensor
    when they share a size (a list otherwise), targets a list of B dicts, since frames have
    different numbers of boxes. Pass it as DataLoader's collate_fn."""
    images = [image for image, _ in batch]
    targets = [target for _, target in batch]
    if images and all(i.shape == images[0].shape for i in images):
        return torch.stack(images), targets
    return images, targets
