#!/usr/bin/python3
"""sdgbehave.data's PyTorch side on a small generated dataset:

- TorchDataset items are torchvision detection targets: boxes float32 XYXY
  (torchvision's masks_to_boxes of the masks, far edges exclusive), labels
  int64 from 1 naming the classes, masks uint8 (N, H, W), a semantic map;
- collate batches frames with different numbers of boxes through a
  DataLoader;
- a tiny segmenter (three conv layers) trained for a few steps on the
  64x64 frames lowers its loss, deterministically (same losses twice).

Exits 77 (skipped) without torch/torchvision (Debian python3-torch,
python3-torchvision).

usage: check_data_torch.py SDGBEHAVE_BINARY SOURCE_DIR (PYTHONPATH holds python/)"""
import os
import subprocess
import sys
import tempfile

try:
    import torch
    import torchvision
except ImportError as e:
    print(f"skipped: {e} (install python3-torch and python3-torchvision)")
    sys.exit(77)

from checklib import check, finish
from sdgbehave.data import TorchDataset, collate

STEPS = 30


def train(dataset):
    """Losses of STEPS full-batch steps of a three-layer conv segmenter."""
    torch.manual_seed(0)
    images, targets = collate([dataset[i] for i in range(len(dataset))])
    semantic = torch.stack([t["semantic"] for t in targets])
    model = torch.nn.Sequential(
        torch.nn.Conv2d(3, 16, 3, padding=1), torch.nn.ReLU(),
        torch.nn.Conv2d(16, 16, 3, padding=1), torch.nn.ReLU(),
        torch.nn.Conv2d(16, len(dataset.class_names), 1))
    optimiser = torch.optim.Adam(model.parameters(), lr=0.02)
    losses = []
    for _ in range(STEPS):
        optimiser.zero_grad()
        loss = torch.nn.functional.cross_entropy(model(images), semantic)
        loss.backward()
        optimiser.step()
        losses.append(loss.item())
    return losses


def main():
    binary, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    torch.set_num_threads(1)
    with tempfile.TemporaryDirectory(prefix="sdg_torch_") as work:
        out = os.path.join(work, "data")
        subprocess.run([binary, "run", os.path.join(source, "tests/data/writer/annotators.yaml"), "--out", out,
                        "--resolution", "64x64", "--frames", "4", "--quiet"], check=True, capture_output=True)
        dataset = TorchDataset(out)
        check(dataset.class_names == ["__background__", "cover", "crate", "floor"], f"classes {dataset.class_names}")
        check(len(dataset) == 4, f"length {len(dataset)}")
        image, target = dataset[0]
        check(image.dtype == torch.float32 and image.shape == (3, 64, 64) and 0 <= image.min() and image.max() <= 1,
              f"image {image.dtype} {tuple(image.shape)}")
        boxes, labels, masks = target["boxes"], target["labels"], target["masks"]
        check(boxes.dtype == torch.float32 and boxes.shape == (len(labels), 4), f"boxes {boxes.dtype} {boxes.shape}")
        check(labels.dtype == torch.int64 and bool((labels >= 1).all()), f"labels {labels}")
        check(masks.dtype == torch.uint8 and masks.shape == (len(labels), 64, 64), f"masks {masks.shape}")
        check(sorted(dataset.class_names[i] for i in labels.tolist()) == ["cover", "crate", "crate", "floor"],
              f"label names {[dataset.class_names[i] for i in labels.tolist()]}")
        # torchvision's own box of each mask, whose far edges are the last pixel.
        from_masks = torchvision.ops.masks_to_boxes(masks)
        check(torch.equal(from_masks + torch.tensor([0, 0, 1, 1]), boxes), f"boxes {boxes} vs masks {from_masks}")
        check(target["semantic"].dtype == torch.int64 and target["semantic"].shape == (64, 64), "semantic map")
        check(int(target["image_id"]) == 0 and target["camera"] == "Camera", "image_id, camera")
        only_crates = TorchDataset(out, classes=["crate"], masks=False, semantic=False, verify=False)
        _, crates = only_crates[0]
        check(crates["labels"].tolist() == [1, 1] and "masks" not in crates and "semantic" not in crates,
              f"classes=['crate'] keeps the crates only: {crates}")

        loader = torch.utils.data.DataLoader(dataset, batch_size=2, collate_fn=collate)
        batches = list(loader)
        check(len(batches) == 2, f"{len(batches)} batches")
        images, targets = batches[0]
        check(images.shape == (2, 3, 64, 64) and len(targets) == 2, f"batch {tuple(images.shape)}, {len(targets)}")
        ragged = collate([dataset[0], (torch.zeros(3, 32, 32), dataset[1][1])])
        check(isinstance(ragged[0], list) and len(ragged[0]) == 2, "images of two sizes stay a list")

        losses = train(dataset)
        print(f"loss {losses[0]:.4f} -> {losses[-1]:.4f} in {STEPS} steps")
        check(losses[-1] < 0.5 * losses[0], f"the loss did not fall by half: {losses[0]:.4f} -> {losses[-1]:.4f}")
        check(train(dataset) == losses, "training twice gave other losses")
    return finish("ok: TorchDataset targets, collate, and a tiny segmenter learns")


if __name__ == "__main__":
    sys.exit(main())
