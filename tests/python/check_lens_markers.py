#!/usr/bin/python3
"""Calibrated lenses against OpenCV (issue 43's "done when"): small spheres
at known points seen through an OpenCV-pinhole camera with strong radial,
tangential and thin-prism distortion and through an OpenCV-fisheye camera
with a 190 degree field of view land where cv2.projectPoints /
cv2.fisheye.projectPoints put their centres, within 0.5 px:
- in the rasterizer's instance ids (the centroid of each marker's pixels),
  whose distance_to_camera at the marker is its distance less its radius,
  and whose loose boxes (coverage masks through the lens) equal the tight
  ones with no occlusion;
- in the CPU path tracer's colour (the brightness-weighted centroid around
  each marker; the markers are lit by a point light at the eye, so the lit
  side faces the camera symmetrically).
The GPU path tracer, which does not follow lenses yet, is refused (exit 2).
The fisheye's markers beyond 90 degrees from the axis (which OpenCV's
fisheye.projectPoints, dividing by Z, cannot take) are checked against the
same model evaluated here with the angle from atan2. The scene also
round-trips through export-usd with its lens attributes.

usage: check_lens_markers.py SDGBEHAVE    (numpy, PIL, cv2: exit 77 without cv2)"""
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

from checklib import check, finish

try:
    import cv2
except ImportError as e:
    print(f"skipped: OpenCV's Python bindings (Debian's python3-opencv) are not importable: {e}")
    sys.exit(77)

CENTROID_PX = 0.5       # the bound; a 3-4 px marker's centroid is within ~0.1 px of its centre's image
DEPTH_RELATIVE = 0.02   # the marker's nearest pixel sees its front within 2 % of distance - radius
WIDTH, HEIGHT = 160, 120

PINHOLE = {"fx": 110.0, "fy": 105.0, "cx": 81.0, "cy": 58.5, "k1": -0.3, "k2": 0.09, "k3": -0.01,
           "k4": 0.02, "k5": 0.0, "k6": 0.0, "p1": 0.004, "p2": -0.003, "s1": 0.002, "s2": 0.0, "s3": -0.002, "s4": 0.0}
FISHEYE = {"fx": 32.0, "fy": 32.0, "cx": 79.5, "cy": 59.5, "k1": 0.01, "k2": -0.002, "k3": 0.0, "k4": 0.0}


def direction(theta_deg, phi_deg):
    """USD camera frame (y up, looking down -z): theta from the axis, phi from +x toward the image's down."""
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    return np.array([math.sin(t) * math.cos(p), -math.sin(t) * math.sin(p), -math.cos(t)])


# (direction, distance); markers are spheres whose angular radius is `ANGULAR` radians.
PINHOLE_MARKERS = [(direction(0, 0), 3.0), (direction(20, 30), 3.0), (direction(30, 150), 2.5),
                   (direction(30, 240), 3.5), (direction(38, 330), 3.0), (direction(15, 200), 2.0)]
FISHEYE_MARKERS = [(direction(0, 0), 2.0), (direction(40, 20), 2.0), (direction(65, 120), 2.5),
                   (direction(80, 200), 2.0), (direction(70, 300), 3.0), (direction(93, 0), 2.0),
                   (direction(94, 180), 2.5)]
ANGULAR = {"opencvPinhole": 0.03, "opencvFisheye": 0.08}


def scene_text(model, params, markers):
    lines = ["version: 1", f"render: {{resolution: [{WIDTH}, {HEIGHT}], samples: 4, max_bounces: 1}}",
             "capture: {cameras: [/World/Camera], frames: 1, seed: 1, contact_sheet: false}",
             "writer: {type: BasicWriter, rgb: true, instance_id_segmentation: true,"
             " colorize_instance_id_segmentation: false, distance_to_camera: true, camera_params: true,"
             " bounding_box_2d_tight: true, bounding_box_2d_loose: true, occlusion: true}",
             "prims:", "  /World: {}",
             "  /World/Lamp: {type: SphereLight, treatAsPoint: true, inputs:intensity: 30000}",
             "  /World/Camera:", "    type: Camera", "    clippingRange: [0.1, 100]",
             f"    omni:lensdistortion:model: {model}",
             f"    omni:lensdistortion:{model}:imageSize: [{WIDTH}, {HEIGHT}]"]
    lines += [f"    omni:lensdistortion:{model}:{k}: {v}" for k, v in params.items()]
    for i, (d, distance) in enumerate(markers):
        p = d * distance
        radius = distance * math.sin(ANGULAR[model])
        lines.append(f"  /World/Marker{i}: {{type: Sphere, radius: {radius:.6f}, translate: [{p[0]:.6f}, {p[1]:.6f}, {p[2]:.6f}],"
                     f" primvars:displayColor: [1, 1, 1], semantics: {{class: marker{i}}}}}")
    return "\n".join(lines) + "\n"


def opencv_points(markers):
    """Marker centres in OpenCV's camera frame (y down, looking down +z)."""
    return np.array([[d[0] * s, -d[1] * s, -d[2] * s] for d, s in markers], dtype=np.float64)


def expected_pinhole(markers):
    k = np.array([[PINHOLE["fx"], 0, PINHOLE["cx"]], [0, PINHOLE["fy"], PINHOLE["cy"]], [0, 0, 1]])
    dist = np.array([PINHOLE[n] for n in ("k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6", "s1", "s2", "s3", "s4")])
    pts, _ = cv2.projectPoints(opencv_points(markers).reshape(-1, 1, 3), np.zeros(3), np.zeros(3), k, dist)
    return pts.reshape(-1, 2)


def expected_fisheye(markers):
    k = np.array([[FISHEYE["fx"], 0, FISHEYE["cx"]], [0, FISHEYE["fy"], FISHEYE["cy"]], [0, 0, 1]])
    d = np.array([FISHEYE[n] for n in ("k1", "k2", "k3", "k4")])
    points = opencv_points(markers)
    front = points[:, 2] > 0
    out = np.zeros((len(points), 2))
    pts, _ = cv2.fisheye.projectPoints(points[front].reshape(-1, 1, 3), np.zeros(3), np.zeros(3), k, d)
    out[front] = pts.reshape(-1, 2)
    # Behind the image plane: OpenCV's model with theta = atan2(r, z).
    for i in np.flatnonzero(~front):
        x, y, z = points[i]
        r = math.hypot(x, y)
        t = math.atan2(r, z)
        td = t * (1 + d[0] * t**2 + d[1] * t**4 + d[2] * t**6 + d[3] * t**8)
        out[i] = [FISHEYE["fx"] * td * x / r + FISHEYE["cx"], FISHEYE["fy"] * td * y / r + FISHEYE["cy"]]
    return out


def run(binary, scene, out, *extra):
    p = subprocess.run([binary, "run", scene, "--out", out, "--overwrite", *extra], capture_output=True, text=True)
    check(p.returncode == 0, f"run {scene} {' '.join(extra)}: exit {p.returncode}: {p.stderr.strip()[-600:]}")
    return p.returncode == 0


def check_ids(name, out, markers, expected):
    ids = np.asarray(Image.open(f"{out}/instance_id_segmentation_0000.png")).astype(np.int64)
    mapping = {v: int(k) for k, v in json.load(open(f"{out}/instance_id_segmentation_mapping_0000.json")).items()}
    distance = np.load(f"{out}/distance_to_camera_0000.npy")
    for i, (d, s) in enumerate(markers):
        path = f"/World/Marker{i}"
        ys, xs = np.nonzero(ids == mapping.get(path, -1))
        check(len(xs) >= 3, f"{name}: {path} covers {len(xs)} pixels in the instance ids")
        if len(xs) < 3:
            continue
        centroid = np.array([xs.mean(), ys.mean()])
        error = np.linalg.norm(centroid - expected[i])
        check(error <= CENTROID_PX, f"{name}: {path}'s ids centroid {centroid.round(3)} is {error:.3f} px from "
                                    f"OpenCV's {expected[i].round(3)}")
        near = distance[int(round(expected[i][1])), int(round(expected[i][0]))]
        front = s * (1 - math.sin(ANGULAR[name]))
        check(abs(near - front) <= DEPTH_RELATIVE * front,
              f"{name}: distance_to_camera at {path} is {near:.4f}, expected about {front:.4f}")


def check_boxes(name, out):
    """Nothing hides a marker, so the loose boxes (from each entity's own
    coverage mask, resampled through the lens like the ids) equal the tight
    ones (from the ids), and every occlusion ratio is 0."""
    tight = np.load(f"{out}/bounding_box_2d_tight_0000.npy")
    loose = np.load(f"{out}/bounding_box_2d_loose_0000.npy")
    corners = ["semanticId", "x_min", "y_min", "x_max", "y_max"]
    check(len(tight) == len(loose) and all((tight[c] == loose[c]).all() for c in corners),
          f"{name}: loose boxes {loose[corners].tolist()} differ from tight ones {tight[corners].tolist()}")
    occlusion = np.load(f"{out}/occlusion_0000.npy")
    check((occlusion["occlusionRatio"] == 0).all(), f"{name}: occlusion {occlusion.tolist()}")


def check_colour(name, out, expected):
    rgb = np.asarray(Image.open(f"{out}/rgb_0000.png"))[..., :3].astype(np.float64)
    luminance = rgb @ np.array([0.2126, 0.7152, 0.0722])
    for i, e in enumerate(expected):
        x0, y0 = int(round(e[0])), int(round(e[1]))
        window = luminance[max(0, y0 - 6):y0 + 7, max(0, x0 - 6):x0 + 7]
        ys, xs = np.mgrid[max(0, y0 - 6):y0 + 7, max(0, x0 - 6):x0 + 7]
        ys, xs = ys[:window.shape[0], :window.shape[1]], xs[:window.shape[0], :window.shape[1]]
        total = window.sum()
        check(total > 0, f"{name} path-traced: marker {i} is dark")
        if total <= 0:
            continue
        centroid = np.array([(xs * window).sum() / total, (ys * window).sum() / total])
        error = np.linalg.norm(centroid - e)
        check(error <= CENTROID_PX, f"{name} path-traced: marker {i}'s centroid {centroid.round(3)} is {error:.3f} px "
                                    f"from OpenCV's {e.round(3)}")


def main():
    binary = os.path.abspath(sys.argv[1])
    with tempfile.TemporaryDirectory() as tmp:
        for name, params, markers, expected in (
                ("opencvPinhole", PINHOLE, PINHOLE_MARKERS, expected_pinhole(PINHOLE_MARKERS)),
                ("opencvFisheye", FISHEYE, FISHEYE_MARKERS, expected_fisheye(FISHEYE_MARKERS))):
            scene = f"{tmp}/{name}.yaml"
            with open(scene, "w") as f:
                f.write(scene_text(name, params, markers))
            if run(binary, scene, f"{tmp}/{name}-raster"):
                check_ids(name, f"{tmp}/{name}-raster", markers, expected)
                check_boxes(name, f"{tmp}/{name}-raster")
                cam = json.load(open(f"{tmp}/{name}-raster/camera_params_0000.json"))
                check(cam["cameraModel"] == name and cam["cameraLensDistortion"]["fx"] == params["fx"],
                      f"{name}: camera_params names the model and its coefficients: {cam.get('cameraLensDistortion')}")
            if run(binary, scene, f"{tmp}/{name}-traced", "--render-mode", "pathtraced", "--set",
                   "render.pathtracer=cpu"):
                check_colour(name, f"{tmp}/{name}-traced", expected)
            # The GPU tracer does not follow lenses yet: asked for, it is refused (exit 2), never pinhole colour.
            p = subprocess.run([binary, "run", scene, "--out", f"{tmp}/{name}-gpu", "--render-mode", "pathtraced",
                                "--set", "render.pathtracer=gpu"], capture_output=True, text=True)
            check(p.returncode == 2 and ("calibrated lens" in p.stderr or "no GPU path tracer" in p.stderr),
                  f"{name}: render.pathtracer gpu: exit {p.returncode}: {p.stderr.strip()[-300:]}")
            # export-usd writes the lens back and the stage renders the same ids.
            usd = f"{tmp}/{name}.usda"
            p = subprocess.run([binary, "export-usd", scene, "-o", usd], capture_output=True, text=True)
            check(p.returncode == 0, f"export-usd {name}: {p.stderr.strip()[-400:]}")
            if p.returncode == 0:
                text = open(usd).read()
                schema = {"opencvPinhole": "OmniLensDistortionOpenCvPinholeAPI",
                          "opencvFisheye": "OmniLensDistortionOpenCvFisheyeAPI"}[name]
                check(schema in text and f"omni:lensdistortion:{name}:fx" in text,
                      f"export-usd {name}: the schema and the attributes are written")
                if run(binary, usd, f"{tmp}/{name}-usd"):
                    a = open(f"{tmp}/{name}-raster/instance_id_segmentation_0000.png", "rb").read()
                    b = open(f"{tmp}/{name}-usd/instance_id_segmentation_0000.png", "rb").read()
                    check(a == b, f"{name}: the exported stage renders other instance ids than the scene")
    return finish("lens markers land where OpenCV projects them")


if __name__ == "__main__":
    sys.exit(main())
