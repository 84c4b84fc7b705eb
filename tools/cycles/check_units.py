#!/usr/bin/python3
"""Checks the stage -> Blender export numerically, end to end.

    tools/cycles/check_units.py [--sdgbehave build/release/app/sdgbehave] [--keep DIR]

Each check writes a tiny stage, exports it with stage_to_blender.py, renders
it with Cycles (cycles_render.py) and compares the radiance Cycles gives with
what sdgbehave's definition of the light predicts (lib/render/shaders.h):

- lights: a Lambert plane of albedo rho seen head-on by an orthographic
  camera 0.02 units wide must have radiance rho E / pi, with E the
  irradiance sdgbehave gives it (a distant light: its radiance value times
  cos; a sphere light: L pi r^2 / d^2; rect and disk lights: L A cos / d^2;
  a cylinder light seen broadside: L 2 r length / d^2); a plane under a
  uniform dome of radiance L: rho L;
- the lat-long dome: looking along chosen directions, the background must
  show the texel render/latlong.h maps them to (and the rasterizer is asked too);
- the camera, transforms, primitives and texture coordinates: a stage with
  every kind of xform op, aperture offsets, a non-square image, uv and
  triplanar textures, rendered by the rasterizer and by Cycles: the objects
  must cover the same pixels and the textures line up.

Prints one line per check with the measured and expected values; exits 1
if any is off by more than its tolerance. Takes about a minute.
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile

import numpy as np
import yaml
from PIL import Image

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
import compare  # noqa: E402

RHO = 0.5
results = []


def cycles(stage, folder, name, samples=256, resolution=None, extra=()):
    """Renders a stage dict with Cycles; returns linear radiance (H x W x 3)."""
    path = os.path.join(folder, name + ".yaml")
    with open(path, "w") as f:
        yaml.safe_dump(stage, f, sort_keys=False)
    script = os.path.join(folder, name + "_blender.py")
    cmd = [sys.executable, os.path.join(HERE, "stage_to_blender.py"), path, "-o", script, *extra]
    if resolution:
        cmd += ["--resolution", resolution]
    subprocess.run(cmd, check=True, capture_output=True)
    subprocess.run(["blender", "-b", "--factory-startup", "--python-exit-code", "1", "--python", script, "--python",
                    os.path.join(HERE, "cycles_render.py"), "--", "--samples", str(samples), "--out", folder,
                    "--name", name], check=True, capture_output=True)
    return np.load(os.path.join(folder, name + ".npy")).astype(np.float64)


def raster(sdgbehave, stage, folder, name):
    """Renders a stage dict with sdgbehave's rasterizer; returns the colour PNG's
    path and the distance to the image plane (+inf where nothing is hit)."""
    path = os.path.join(folder, name + ".yaml")
    stage = dict(stage, writer={"type": "BasicWriter", "rgb": True, "distance_to_image_plane": True})
    with open(path, "w") as f:
        yaml.safe_dump(stage, f, sort_keys=False)
    out = os.path.join(folder, name + "_raster")
    subprocess.run([sdgbehave, "run", path, "--frames", "1", "--out", out, "--overwrite"], check=True,
                   capture_output=True)
    return os.path.join(out, "rgb_0000.png"), np.load(os.path.join(out, "distance_to_image_plane_0000.npy"))


def record(name, measured, expected, tolerance):
    error = abs(measured - expected) / abs(expected)
    ok = error <= tolerance
    results.append(ok)
    print(f"{'ok  ' if ok else 'FAIL'} {name:<58} measured {measured:10.5g}  expected {expected:10.5g}  "
          f"({100 * (measured / expected - 1):+.2f} %, tolerance {100 * tolerance:.1f} %)")


def plane_stage(light, camera_extra=None):
    """A Lambert plane at z = 0, an orthographic camera at z = 1 looking down on
    a 0.02-unit patch, and one light."""
    camera = {"type": "Camera", "projection": "orthographic", "horizontalAperture": 0.2,
              "clippingRange": [0.01, 100], "translate": [0, 0, 1]}
    camera.update(camera_extra or {})
    return {"version": 1, "render": {"resolution": [8, 8]}, "capture": {"cameras": ["/World/Camera"]},
            "prims": {"/World": {}, "/World/Looks": {"type": "Scope"},
                      "/World/Looks/Matte": {"type": "Material", "inputs:diffuse_color_constant": [RHO, RHO, RHO],
                                             "inputs:reflection_roughness_constant": 1.0},
                      "/World/Plane": {"type": "Plane", "width": 50, "length": 50, "material": "/World/Looks/Matte"},
                      "/World/Light": light, "/World/Camera": camera}}


def light_checks(folder):
    d = 2.0
    checks = [
        ("DistantLight 3000, head-on: rho E / pi",
         {"type": "DistantLight", "inputs:intensity": 3000.0}, 3000.0),
        ("DistantLight 3000, 60 deg off the normal, angle 5 deg",
         {"type": "DistantLight", "inputs:intensity": 3000.0, "inputs:angle": 5.0, "rotateY": 60.0},
         3000.0 * math.cos(math.radians(60))),
        ("DistantLight 1000, exposure 1, colour (1, .5, .25) (red)",
         {"type": "DistantLight", "inputs:intensity": 1000.0, "inputs:exposure": 1.0,
          "inputs:color": [1.0, 0.5, 0.25]}, 2000.0),
        ("SphereLight r .05 at d 2: E = L pi r^2 / d^2",
         {"type": "SphereLight", "inputs:intensity": 1e5, "inputs:radius": 0.05, "translate": [0, 0, d]},
         1e5 * math.pi * 0.05 ** 2 / d ** 2),
        ("SphereLight r .05 treatAsPoint at d 2",
         {"type": "SphereLight", "inputs:intensity": 1e5, "inputs:radius": 0.05, "treatAsPoint": True,
          "translate": [0, 0, d]}, 1e5 * math.pi * 0.05 ** 2 / d ** 2),
        ("RectLight .2 x .1 at d 2, facing down: E = L A / d^2",
         {"type": "RectLight", "inputs:intensity": 1e5, "inputs:width": 0.2, "inputs:height": 0.1,
          "translate": [0, 0, d]}, 1e5 * 0.02 / d ** 2),
        ("RectLight .2 x .1 at d 2, tilted 45 deg: E = L A cos / d^2",
         {"type": "RectLight", "inputs:intensity": 1e5, "inputs:width": 0.2, "inputs:height": 0.1,
          "translate": [0, 0, d], "rotateX": 45.0}, 1e5 * 0.02 * math.cos(math.radians(45)) / d ** 2),
        ("RectLight .2 x .1 at d 2, normalize: E = (L / A) A / d^2",
         {"type": "RectLight", "inputs:intensity": 2e3, "inputs:width": 0.2, "inputs:height": 0.1,
          "inputs:normalize": True, "translate": [0, 0, d]}, 2e3 / d ** 2),
        ("DiskLight r .1 at d 2: E = L pi r^2 / d^2",
         {"type": "DiskLight", "inputs:intensity": 1e5, "inputs:radius": 0.1, "translate": [0, 0, d]},
         1e5 * math.pi * 0.01 / d ** 2),
        ("CylinderLight r .02 length .4 at d 2: E = L 2 r l / d^2",
         {"type": "CylinderLight", "inputs:intensity": 1e5, "inputs:radius": 0.02, "inputs:length": 0.4,
          "translate": [0, 0, d]}, 1e5 * 2 * 0.02 * 0.4 / d ** 2),
    ]
    for i, (name, light, irradiance) in enumerate(checks):
        image = cycles(plane_stage(light), folder, f"light{i}", extra=["--bsdf", "lambert"])
        # The red channel: the coloured check's colour is (1, .5, .25).
        record(name, image[:, :, 0].mean(), RHO * irradiance / math.pi, 0.01)
    dome = {"type": "DomeLight", "inputs:intensity": 800.0, "inputs:color": [1.0, 0.5, 0.25]}
    image = cycles(plane_stage(dome), folder, "dome_uniform", extra=["--bsdf", "lambert"])
    record("DomeLight 800, colour (1, .5, .25): rho L (red)", image[:, :, 0].mean(), RHO * 800.0, 0.01)
    record("DomeLight 800, colour (1, .5, .25): rho L (blue)", image[:, :, 2].mean(), RHO * 200.0, 0.01)


def raster_brdf_cos(base, roughness, cos_i):
    """f cos(theta_i) of the rasterizer's brdf() (shaders.h), viewed head-on."""
    n, v = np.array([0, 0, 1.0]), np.array([0, 0, 1.0])
    l = np.array([math.sin(math.acos(cos_i)), 0, cos_i])
    h = (l + v) / np.linalg.norm(l + v)
    nl, nv, nh, vh = max(n @ l, 0), max(n @ v, 1e-4), max(n @ h, 0), max(v @ h, 0)
    a = max(roughness ** 2, 1e-3)
    d = a * a / (math.pi * (nh * nh * (a * a - 1) + 1) ** 2)
    k = a / 2
    g = nl / (nl * (1 - k) + k) * nv / (nv * (1 - k) + k)
    f = 0.04 + 0.96 * (1 - vh) ** 5
    return (base / math.pi + d * g * f / max(4 * nl * nv, 1e-4)) * nl


def path_tracer_bsdf_cos(base, roughness, cos_i):
    """f cos(theta_i) of the path tracer's PbrBsdf::eval() (render/pathtrace/bsdf.cpp), viewed head-on."""
    wo = np.array([0, 0, 1.0])
    wi = np.array([math.sin(math.acos(cos_i)), 0, cos_i])
    # The diffuse base is not darkened by the coat (as Principled's); specular_level
    # 0.5, the default, gives F0 0.04 and F90 1.
    diffuse = base * wi[2] / math.pi
    h = (wo + wi) / np.linalg.norm(wo + wi)
    a = max(roughness ** 2, 1e-3)
    dd = (h[0] ** 2 + h[1] ** 2) / (a * a) + h[2] ** 2
    d = 1 / (math.pi * a * a * dd * dd)
    lam = lambda w: 0.5 * (math.sqrt(1 + a * a * (w[0] ** 2 + w[1] ** 2) / w[2] ** 2) - 1)
    g2 = 1 / (1 + lam(wo) + lam(wi))
    f = 0.04 + 0.96 * (1 - wo @ h) ** 5
    return diffuse + f * d * g2 / (4 * wo[2])


def bsdf_info(folder):
    """Not a pass/fail check: how far Cycles' Principled BSDF is from the two
    sdgbehave surface models, lit by a sun and seen head-on."""
    base, E = 0.73, 1000.0
    print("info BSDF, base 0.73 dielectric, sun 1000 W/m2, seen head-on: radiance of Cycles' Principled vs "
          "the rasterizer's brdf() and the path tracer's PbrBsdf")
    for roughness in (1.0, 0.5):
        for angle in (0.0, 45.0, 70.0):
            stage = plane_stage({"type": "DistantLight", "inputs:intensity": E, "inputs:angle": 0.1, "rotateY": angle})
            stage["prims"]["/World/Looks/Matte"].update({"inputs:diffuse_color_constant": [base] * 3,
                                                         "inputs:reflection_roughness_constant": roughness})
            got = cycles(stage, folder, f"bsdf_{roughness}_{int(angle)}", extra=["--bsdf", "principled"])[:, :, 0].mean()
            c = math.cos(math.radians(angle))
            ras, pt = E * raster_brdf_cos(base, roughness, c), E * path_tracer_bsdf_cos(base, roughness, c)
            print(f"info   roughness {roughness:.1f}, light {angle:4.0f} deg: Cycles {got:8.2f}   rasterizer {ras:8.2f} "
                  f"({100 * (got / ras - 1):+5.1f} %)   path tracer {pt:8.2f} ({100 * (got / pt - 1):+5.1f} %)")


def rotation_looking_along(d):
    """Camera rotation (columns: its x, y, z in the world) looking down -Z along d."""
    d = np.asarray(d, float) / np.linalg.norm(d)
    up = np.array([0, 0, 1.0]) if abs(d[2]) < 0.9 else np.array([0, 1.0, 0])
    x = np.cross(d, up)
    x /= np.linalg.norm(x)
    y = np.cross(x, d)
    return np.stack([x, y, -d], axis=1)


def dome_checks(folder, sdgbehave):
    """The lat-long texture: 8 x 4 blocks of distinct colours; look at block centres."""
    blocks_x, blocks_y, size = 8, 4, 8
    rng = np.random.default_rng(3)
    colors = rng.integers(20, 236, size=(blocks_y, blocks_x, 3)).astype(np.uint8)
    texture = np.kron(colors, np.ones((size, size, 1), np.uint8))
    png = os.path.join(folder, "latlong_blocks.png")
    Image.fromarray(texture).save(png)
    L = 1000.0
    for dome_rotate_z in (0.0, 30.0):
        frame = np.array([[math.cos(math.radians(dome_rotate_z)), -math.sin(math.radians(dome_rotate_z)), 0],
                          [math.sin(math.radians(dome_rotate_z)), math.cos(math.radians(dome_rotate_z)), 0],
                          [0, 0, 1]]) @ np.array([[1, 0, 0], [0, 0, -1], [0, 1, 0]])  # Z-up: +90 deg about X first
        for bx, by in ((1, 1), (2, 2), (5, 1), (6, 2), (3, 0), (0, 3)):
            u, v = (bx + 0.5) / blocks_x, (by + 0.5) / blocks_y
            # render/latlong.h's directionFromLatLong(): longitude (0.5 - u) 2pi from +Z toward +X, polar v pi from +Y.
            longitude, polar = (0.5 - u) * 2 * math.pi, v * math.pi
            local = np.array([math.sin(polar) * math.sin(longitude), math.cos(polar),
                              math.sin(polar) * math.cos(longitude)])
            world = frame @ local
            m = np.eye(4)
            m[:3, :3] = rotation_looking_along(world)
            stage = {"version": 1, "render": {"resolution": [4, 4]}, "capture": {"cameras": ["/World/Camera"]},
                     "prims": {"/World": {},
                               "/World/Dome": {"type": "DomeLight", "inputs:intensity": L, "inputs:texture:file": png,
                                               "rotateZ": dome_rotate_z},
                               # USD row-vector rows: the transpose of the column-vector matrix.
                               "/World/Camera": {"type": "Camera", "focalLength": 2000.0,
                                                 "transform": m.T.tolist()}}}
            expected = compare.srgb_to_linear(colors[by, bx] / 255.0) * L
            name = f"dome{int(dome_rotate_z)}_{bx}{by}"
            image = cycles(stage, folder, name, samples=16)
            got = image.reshape(-1, 3).mean(axis=0)
            record(f"lat-long block ({bx},{by}), dome rotateZ {dome_rotate_z:g}: Cycles (sum of rgb)",
                   got.sum(), expected.sum(), 0.02)
            if sdgbehave:
                radiance, _ = compare.png_to_radiance(raster(sdgbehave, stage, folder, name)[0])
                record(f"lat-long block ({bx},{by}), dome rotateZ {dome_rotate_z:g}: rasterizer (sum of rgb)",
                       radiance.reshape(-1, 3).mean(axis=0).sum(), expected.sum(), 0.03)


def geometry_check(folder, sdgbehave, orthographic=False):
    """Every kind of xform op, every procedural shape, OBJ and GLB files,
    aperture offsets, a non-square image, uv and triplanar textures; a
    perspective or an orthographic camera."""
    # An asymmetric texture: quadrants of different colours and a bar, so a
    # flip or a turn shows.
    t = np.zeros((64, 64, 3), np.uint8)
    t[:32, :32] = (230, 40, 40)
    t[:32, 32:] = (40, 230, 40)
    t[32:, :32] = (40, 40, 230)
    t[32:, 32:] = (230, 230, 40)
    t[4:12, 4:40] = (250, 250, 250)
    tex = os.path.join(folder, "quadrants.png")
    Image.fromarray(t).save(tex)
    stage = {"version": 1, "render": {"resolution": [200, 120]}, "capture": {"cameras": ["/World/Camera"]},
             "prims": {
                 "/World": {"translate": [0.1, -0.2, 0.0], "rotateZ": 10.0},
                 "/World/Looks": {"type": "Scope"},
                 "/World/Looks/Uv": {"type": "Material", "inputs:diffuse_texture": tex,
                                     "inputs:texture_scale": [2.0, 1.0], "inputs:texture_rotate": 30.0,
                                     "inputs:reflection_roughness_constant": 1.0},
                 "/World/Looks/Tri": {"type": "Material", "inputs:diffuse_texture": tex, "inputs:project_uvw": True,
                                      "inputs:texture_scale": [0.5, 0.5],
                                      "inputs:reflection_roughness_constant": 1.0},
                 "/World/Floor": {"type": "Plane", "width": 4.0, "length": 3.0, "material": "/World/Looks/Uv"},
                 "/World/Group": {"translate": [0.3, 0.2, 0.0], "orient": [0.9659258, 0.0, 0.0, 0.2588190],
                                  "scale": [1.0, 1.2, 1.0]},
                 "/World/Group/Box": {"type": "Cube", "size": 0.8, "translate": [-0.8, 0.3, 0.5],
                                      "rotateXYZ": [10.0, 20.0, 30.0], "translate:pivot": [0.1, 0.0, 0.0],
                                      "scale": [1.0, 0.7, 1.3], "material": "/World/Looks/Tri"},
                 "/World/Group/Ball": {"type": "Sphere", "radius": 0.35, "translate": [0.7, -0.4, 0.35],
                                       "primvars:displayColor": [0.8, 0.6, 0.2]},
                 "/World/Group/Can": {"type": "Cylinder", "radius": 0.2, "height": 0.7, "axis": "X",
                                      "transform": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0.2, -1.0, 0.2, 1]],
                                      "rotateZYX": [0.0, 0.0, 25.0]},
                 "/World/Group/Cone": {"type": "Cone", "radius": 0.25, "height": 0.6, "axis": "Y",
                                       "translate": [0.9, 0.7, 0.3], "rotateYXZ": [5.0, 80.0, 0.0]},
                 "/World/Group/Pill": {"type": "Capsule", "radius": 0.15, "height": 0.4, "translate": [-0.2, 0.9, 0.3],
                                       "rotateZXY": [90.0, 0.0, 45.0], "rotateXZY": [1.0, 2.0, 3.0],
                                       "rotateYZX": [4.0, 5.0, 6.0], "rotateX": 5.0, "rotateY": -5.0},
                 # Mesh files through Blender's importers: OBJ + MTL and GLB.
                 "/World/Crate": {"type": "Mesh", "asset": os.path.join(ROOT, "scenes", "props", "crate.obj"),
                                  "translate": [-1.4, -0.9, 0.0], "rotateZ": 20.0, "scale": [0.5, 0.5, 0.5]},
                 "/World/Drill": {"type": "Mesh", "asset": os.path.join(ROOT, "scenes", "props", "drill.glb"),
                                  "translate": [0.4, -1.5, 0.2], "rotateZ": -60.0, "scale": [3.0, 3.0, 3.0]},
                 "/World/Sun": {"type": "DistantLight", "inputs:intensity": 1500.0, "rotateXYZ": [40.0, 0.0, 30.0]},
                 "/World/Camera": {"type": "Camera", "focalLength": 20.0, "horizontalApertureOffset": 1.5,
                                   "verticalApertureOffset": -1.0, "clippingRange": [0.1, 100.0],
                                   "translate": [0.3, -4.0, 3.2], "rotateXYZ": [50.0, 0.0, 5.0]}}}
    name = "geometry"
    if orthographic:
        # 4.5 units across (apertures in tenths of a unit), offsets likewise.
        stage["prims"]["/World/Camera"].update({"projection": "orthographic", "horizontalAperture": 45.0,
                                                "horizontalApertureOffset": 3.0, "verticalApertureOffset": 2.0})
        name = "geometry_ortho"
    png, distance = raster(sdgbehave, stage, folder, name)
    ras = np.asarray(Image.open(png).convert("RGB")).astype(np.float64)
    cyc = cycles(stage, folder, name, samples=64, extra=["--bsdf", "principled"])
    cyc8 = compare.tone_map(cyc).astype(np.float64)
    # The rasterizer's shadows are black (no bounce light): its coverage comes
    # from the depth pass; Cycles' shadows get bounce light, never black.
    covered_r = np.isfinite(distance.reshape(ras.shape[:2]))
    covered_c = cyc.sum(axis=2) > 1e-6
    # Cycles' box filter anti-aliases edges (a pixel partly covered is not
    # black) while the rasterizer samples pixel centres, so the masks may
    # differ along edges by one pixel: count the pixels either covers that
    # lie more than one pixel from the other's coverage.
    def grown(mask):
        out = mask.copy()
        for dy in (-1, 0, 1):
            for dx in (-1, 0, 1):
                out |= np.roll(np.roll(mask, dy, axis=0), dx, axis=1)
        return out
    stray = ((covered_r & ~grown(covered_c)) | (covered_c & ~grown(covered_r))).sum()
    iou = (covered_r & covered_c).sum() / max((covered_r | covered_c).sum(), 1)
    print(f"     {name}: coverage intersection / union {iou:.4f} (edges differ by anti-aliasing)")
    record(f"{name}: pixels covered by one, > 1 pixel from the other's, + 1", stray + 1, 1, 0.0)
    # Texture alignment: the chromaticity of each covered pixel (the two
    # renderers shade differently, so colours are compared normalised).
    both = covered_r & covered_c & (ras.sum(axis=2) > 30)  # lit in both
    chroma = lambda a: a[both] / np.maximum(a[both].sum(axis=1, keepdims=True), 1e-9)
    agree = (np.abs(chroma(ras) - chroma(cyc8)).max(axis=1) < 0.1).mean()
    record(f"{name}: pixels whose chromaticity agrees within 0.1", agree, 1.0, 0.03)
    compare.side_by_side(os.path.join(folder, name + "_side_by_side.png"),
                         [("Cycles 64", cyc), ("rasterizer", png)], compare.EXPOSURE_SCALE)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sdgbehave", default=os.path.join(ROOT, "build", "release", "app", "sdgbehave"),
                        help="the binary, for the checks against the rasterizer ('' to skip them)")
    parser.add_argument("--keep", help="keep the stages and renders in this folder")
    parser.add_argument("--only", default="lights,dome,geometry,bsdf",
                        help="comma-separated: lights, dome, geometry, bsdf")
    args = parser.parse_args()
    only = set(args.only.split(","))
    sdgbehave = args.sdgbehave if args.sdgbehave and os.path.exists(args.sdgbehave) else None
    with tempfile.TemporaryDirectory() as tmp:
        folder = args.keep or tmp
        os.makedirs(folder, exist_ok=True)
        if "lights" in only:
            light_checks(folder)
        if "dome" in only:
            dome_checks(folder, sdgbehave)
        if "bsdf" in only:
            bsdf_info(folder)
        if "geometry" not in only:
            pass
        elif sdgbehave:
            geometry_check(folder, sdgbehave)
            geometry_check(folder, sdgbehave, orthographic=True)
        else:
            print("skipped: the checks against the rasterizer (no sdgbehave binary)")
    print(f"{sum(results)} of {len(results)} pass/fail checks pass")
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main())
