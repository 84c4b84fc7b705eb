#!/usr/bin/python3
"""Every scene in scenes/examples/ runs end to end (small frames), and the
writer examples produce their layouts: several cameras under
<camera>/<annotator>/ or, with use_common_output_dir, <annotator>/<camera>_;
COCO next to the BasicWriter files."""
import glob
import json
import os
import subprocess
import sys
import tempfile

from PIL import Image


def run(binary, scene, out, *extra):
    result = subprocess.run([binary, "run", scene, "--out", out, "--frames", "2", "--resolution", "64x48", *extra],
                            capture_output=True, text=True)
    return result


def main():
    binary, examples = sys.argv[1:3]
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in sorted(glob.glob(f"{examples}/*.yaml")):
            out = f"{tmp}/{os.path.basename(scene)}"
            result = run(binary, scene, out)
            if result.returncode != 0:
                failures.append(f"{scene}: exit {result.returncode}\n{result.stderr}")
            elif not os.path.exists(f"{out}/metadata.txt") or not os.path.exists(f"{out}/run_summary.json"):
                failures.append(f"{scene}: metadata.txt or run_summary.json missing")
        multi = f"{tmp}/writer_multi_camera.yaml"
        for camera in ("Left", "Right"):
            image = f"{multi}/{camera}/rgb/rgb_0001.png"
            if not os.path.exists(image) or Image.open(image).size != (64, 48):
                failures.append(f"missing or wrong size: {image}")
            if not os.path.exists(f"{multi}/{camera}/bounding_box_2d_tight/bounding_box_2d_tight_0000.npy"):
                failures.append(f"{camera}: no bounding boxes in the legacy layout")
        common = f"{tmp}/common"
        run(binary, f"{examples}/writer_multi_camera.yaml", common, "--set", "writer.use_common_output_dir=true")
        for path in ("rgb/Left_rgb_0000.png", "rgb/Right_rgb_0001.png", "camera_params/Left_camera_params_0000.json"):
            if not os.path.exists(f"{common}/{path}"):
                failures.append(f"use_common_output_dir: missing {path}")
        coco = json.load(open(f"{tmp}/writer_coco.yaml/coco_instances.json"))
        if len(coco["images"]) != 2 or not coco["annotations"]:
            failures.append("writer_coco: unexpected COCO content")
        if not os.path.exists(f"{tmp}/writer_depth_and_normals.yaml/distance_to_camera_0000.png"):
            failures.append("writer_depth_and_normals: no colorized depth")
    if failures:
        print("\n".join(failures))
        return 1
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
