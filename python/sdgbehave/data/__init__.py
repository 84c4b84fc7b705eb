"""Read sdgbehave datasets into numpy, and into PyTorch.

    from sdgbehave.data import Dataset
    dataset = Dataset("out/warehouse")        # checked as `sdgbehave verify` checks it
    frame = dataset[0]
    frame.rgb(), frame.semantic_segmentation(), frame.bounding_box_2d_tight(), frame.camera_params()

    from sdgbehave.data import TorchDataset, collate   # imports torch
    loader = torch.utils.data.DataLoader(TorchDataset("out/warehouse"), batch_size=4, collate_fn=collate)

docs/datasets-python.md documents every call."""
from .bop import BopDataset, BopImage, BopScene
from .dataset import Dataset
from .folder import DatasetError
from .frame import Frame, MissingAnnotation
from .ply import read_ply
from .records import Boxes2D, Boxes3D, Camera, Segmentation

__all__ = ["Dataset", "DatasetError", "Frame", "MissingAnnotation", "Boxes2D", "Boxes3D", "Camera", "Segmentation",
           "BopDataset", "BopScene", "BopImage", "read_ply", "TorchDataset", "collate"]


def __getattr__(name):
    # torch is imported only when its part is asked for.
    if name in ("TorchDataset", "collate"):
        from . import torch_dataset
        return getattr(torch_dataset, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
