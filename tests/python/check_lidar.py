#!/usr/bin/python3
"""LiDAR sweeps end to end (scenes/examples/lidar.yaml at 64 x 48, 2
frames): lidar_Lidar_X.npy loads with numpy as the documented structured
array, its points lie at their range in the sensor frame and carry the
labels of the JSON beside it (the crate's class among them); KITTI's .bin
loads as N x 4 float32 equal to the array's x, y, z, intensity;
sdgbehave.data reads all three; the dataset is byte-identical with
--threads 1 and 2 and as two shards merged; and the scene exported as a
USD stage (its Lidar prim by the same attribute names) sweeps the same bytes;
lidar_keep_misses keeps every ray; TorchDataset(lidar=True) gives each
point's class index (where torch is installed)."""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

from checklib import check, dataset_hashes, finish
from sdgbehave.data import Dataset

FIELDS = ["x", "y", "z", "range", "intensity", "ring", "azimuth", "time", "semantic_id", "instance_id"]


def run(binary, scene, out, *flags):
    p = subprocess.run([binary, "run", scene, "--out", out, "--frames", "2", "--resolution", "64x48", *flags],
                       capture_output=True, text=True)
    check(p.returncode == 0, f"run {flags} exited {p.returncode}: {p.stderr.strip()[-400:]}")


def main():
    binary, root = sys.argv[1:3]
    scene = os.path.join(root, "scenes", "examples", "lidar.yaml")
    with tempfile.TemporaryDirectory() as tmp:
        one, two, shards = f"{tmp}/one", f"{tmp}/two", f"{tmp}/shards"
        run(binary, scene, one, "--threads", "1")
        run(binary, scene, two, "--threads", "2")
        for i in range(2):
            run(binary, scene, shards, "--shard", f"{i}/2", "--threads", "2")
        p = subprocess.run([binary, "merge", shards], capture_output=True, text=True)
        check(p.returncode == 0, f"merge: {p.stderr[-300:]}")
        reference = dataset_hashes(one)
        check(reference == dataset_hashes(two), "--threads 1 and 2 differ")
        check(reference == dataset_hashes(shards), "two shards merged differ from one run")

        points = np.load(f"{one}/lidar_Lidar_0001.npy")
        check(list(points.dtype.names) == FIELDS, f"fields {points.dtype.names}")
        check(len(points) > 3000, f"only {len(points)} points of 16 x 900")
        xyz = np.stack([points["x"], points["y"], points["z"]], axis=1).astype(np.float64)
        check(np.allclose(np.linalg.norm(xyz, axis=1), points["range"], atol=1e-4), "points not at their range")
        elevation = np.degrees(np.arcsin(points["z"] / points["range"]))
        check(np.allclose(elevation, -15 + 2 * points["ring"].astype(np.float64), atol=1e-2), "rings off VLP-16's")
        check(points["time"].min() >= 0 and points["time"].max() < 0.1, "time offsets outside the 0.1 s sweep")
        check(((points["intensity"] >= 0) & (points["intensity"] <= 1)).all(), "intensity outside [0, 1]")
        info = json.load(open(f"{one}/lidar_Lidar_0001.json"))
        labels = {int(k): v for k, v in info["semantic_labels"].items()}
        classes = {v.get("class") for v in labels.values()}
        check({"crate", "floor", "wall"} <= classes, f"classes {classes}")
        check(set(np.unique(points["semantic_id"]).tolist()) <= set(labels), "ids without labels")
        crate = [k for k, v in info["instance_paths"].items() if v == "/World/Crate"]
        check(len(crate) == 1 and (points["instance_id"] == int(crate[0])).sum() > 20, "few points on the crate")
        pose = np.array(info["world_from_sensor"])
        check(np.allclose(pose[:3, 3], [0, 0, 1]), f"pose {pose[:3, 3]}")
        kitti = np.fromfile(f"{one}/lidar_Lidar_0001.bin", dtype=np.float32).reshape(-1, 4)
        check(kitti.shape == (len(points), 4), f"KITTI shape {kitti.shape}")
        check(np.array_equal(kitti, np.stack([points[f] for f in ("x", "y", "z", "intensity")], axis=1)),
              "KITTI rows differ from the array's")

        usd, again = f"{tmp}/scene.usda", f"{tmp}/usd"
        p = subprocess.run([binary, "export-usd", scene, "--out", usd], capture_output=True, text=True)
        check(p.returncode == 0, f"export-usd: {p.stderr[-300:]}")
        run(binary, usd, again)
        for name in ("lidar_Lidar_0001.npy", "lidar_Lidar_0001.json"):
            check(open(f"{again}/{name}", "rb").read() == open(f"{one}/{name}", "rb").read(),
                  f"{name} from the exported USD stage differs")

        kept = f"{tmp}/kept"
        run(binary, scene, kept, "--set", "writer.lidar_keep_misses=true")
        rays = np.load(f"{kept}/lidar_Lidar_0001.npy")
        check(len(rays) == 16 * 900, f"kept {len(rays)} rows of 16 x 900 rays")
        hits = rays[rays["range"] > 0]
        check(np.array_equal(hits, points), "the kept sweep's hits differ from the sweep")
        misses = rays[rays["range"] == 0]
        check(len(misses) > 0 and (misses["semantic_id"] == 0).all() and (misses["x"] == 0).all(),
              "misses not kept as range 0, id 0 rows")

        frame = Dataset(one)[1]
        check(frame.lidar_sensors() == ["Lidar"], f"sensors {frame.lidar_sensors()}")
        check(np.array_equal(frame.lidar(), points), "sdgbehave.data's lidar() differs")
        check(np.array_equal(frame.lidar_kitti(), kitti), "sdgbehave.data's lidar_kitti() differs")
        check(frame.lidar_info()["world_from_sensor"].shape == (4, 4), "lidar_info pose")
        try:
            from sdgbehave.data import TorchDataset
        except ImportError:
            TorchDataset = None
        if TorchDataset is not None:
            run(binary, scene, f"{tmp}/boxes", "--set", "writer.bounding_box_2d_tight=true")
            torch_data = TorchDataset(f"{tmp}/boxes", lidar=True, masks=False, semantic=False)
            target = torch_data[1][1]["lidar"]["Lidar"]
            names = [torch_data.class_names[int(i)] for i in target["labels"]]
            check(target["points"].shape == (len(points), 3) and "crate" in names,
                  f"TorchDataset lidar target {target['points'].shape}, classes {set(names)}")
    return finish("ok: LiDAR sweeps read back, identical across threads and shards")


if __name__ == "__main__":
    sys.exit(main())
