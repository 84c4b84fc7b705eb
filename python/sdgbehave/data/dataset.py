"""A finished sdgbehave dataset folder: its frames in order, read into numpy."""
import json
import os

from .bop import BopDataset
from .folder import DatasetError, frame_files, read_run
from .frame import Frame


class Dataset:
    """The frames of a finished dataset (`sdgbehave run --out DIR`, sharded runs after
    `sdgbehave merge`), in frame order and, within a frame, in render product (camera) order.

    Opening checks the folder as `sdgbehave verify` does (manifest, every file's size and SHA-256,
    the run complete, shards run with the same inputs) and raises DatasetError naming every
    problem; `verify=False` skips the hashing (files still present with their listed sizes).

    `camera` keeps one render product (by name); the default keeps every one."""

    def __init__(self, root, verify=True, camera=None):
        self.root = os.fspath(root)
        self.run, entries = read_run(self.root, verify=verify)
        self.cameras = [str(p) for p in self.run["products"]]
        if camera is not None and camera not in self.cameras:
            raise DatasetError(f"{self.root}: no render product {camera!r}; it has {', '.join(self.cameras)}")
        several = len(self.cameras) > 1
        self._frames = []
        for (number, product), files in sorted(entries.items()):
            name = self.cameras[product]
            if camera is None or name == camera:
                self._frames.append(Frame(self.root, number, name, frame_files(files, number, name, several)))
        self._classes = {}

    def __len__(self):
        return len(self._frames)

    def __getitem__(self, index):
        return self._frames[index]

    def __iter__(self):
        return iter(self._frames)

    def __repr__(self):
        return f"Dataset({self.root!r}, {len(self)} frames, cameras={self.cameras})"

    @property
    def seed(self):
        return int(self.run["seed"])

    @property
    def resolution(self):
        """(width, height) of every image."""
        return tuple(int(v) for v in self.run["resolution"])

    def frame(self, number, camera=None):
        """The Frame with this run frame number (of `camera`, default the first)."""
        camera = camera or self.cameras[0]
        for f in self._frames:
            if f.number == number and f.camera == camera:
                return f
        raise KeyError(f"{self.root}: no frame {number} of {camera}")

    def classes(self, taxonomy="class"):
        """Every label of `taxonomy` in the dataset, sorted: what a model's class list is built from.
        Read from the frames' semantic and box label files (each read once, then cached)."""
        if taxonomy not in self._classes:
            names = set()
            for f in self._frames:
                for kind in ("semantic_segmentation_labels", "bounding_box_2d_tight_labels",
                             "bounding_box_2d_loose_labels", "bounding_box_3d_labels",
                             "instance_segmentation_semantics_mapping"):
                    if f.has(kind):
                        with open(f.path(kind, "json"), encoding="utf-8") as file:
                            names.update(v[taxonomy] for v in json.load(file).values() if taxonomy in v)
            names -= {"BACKGROUND", "UNLABELLED"}
            self._classes[taxonomy] = sorted(names)
        return list(self._classes[taxonomy])

    def bop(self):
        """The run's BopWriter output (camera.json, models/, <split>/<scene_id>/) as a BopDataset."""
        return BopDataset(self.root)

    def coco(self):
        """The COCO file as a dict (a CocoWriter run), else MissingAnnotation-like DatasetError."""
        name = self.run.get("coco_file") or ""
        if not name:
            raise DatasetError(f"{self.root}: the run had no CocoWriter")
        with open(os.path.join(self.root, name), encoding="utf-8") as f:
            return json.load(f)
