#!/usr/bin/python3
"""Writes a Blender Python script that rebuilds a stage saved by sdgbehave.

    sdgbehave run SCENE --frames 1 --save-stage stage.yaml --out DIR
    tools/cycles/stage_to_blender.py stage.yaml -o stage_blender.py [--resolution 256x256]
    blender -b --factory-startup --python stage_blender.py        # builds the scene (add a save to keep it)

The stage is read the way sdgbehave's renderer reads it (lib/render/
render_list.cpp): unauthored attributes take the schema's defaults
(schemas/scene.schema.json), xform ops compose in xformOpOrder as in
lib/stage/xform.cpp, visibility and material bindings are inherited as in
render_list.cpp, procedural shapes are the exact triangles of
lib/assets/primitives.cpp (primitives.py), and lights are converted from
USD's radiance (intensity * 2^exposure * color) to Cycles' units; README.md
derives each conversion. Everything resolved here is written into the
script as one JSON document, which blender_scene.py (appended to the
script) turns into Blender data, so the script runs on its own.

Runs with Debian's /usr/bin/python3: standard library and PyYAML only.
"""
import argparse
import json
import math
import os
import sys

import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
import primitives  # noqa: E402  (this folder)

GPRIMS = {"Mesh", "Cube", "Sphere", "Cylinder", "Cone", "Capsule", "Plane"}
LIGHTS = {"DistantLight", "SphereLight", "RectLight", "DiskLight", "CylinderLight", "DomeLight"}


# ---------------------------------------------------------------- matrices
# 4 x 4 matrices as lists of rows, column-vector convention (p' = M p), as
# sdgbehave's Eigen matrices: translation in the last column.

def identity():
    return [[1.0 if r == c else 0.0 for c in range(4)] for r in range(4)]


def mul(a, b):
    return [[sum(a[r][k] * b[k][c] for k in range(4)) for c in range(4)] for r in range(4)]


def from_rotation(r3):
    m = identity()
    for r in range(3):
        for c in range(3):
            m[r][c] = r3[r][c]
    return m


def axis_rotation(axis, degrees):
    """Rotation about X (0), Y (1) or Z (2) by degrees, right-handed (Eigen's AngleAxis)."""
    a = math.radians(degrees)
    c, s = math.cos(a), math.sin(a)
    if axis == 0:
        return [[1, 0, 0], [0, c, -s], [0, s, c]]
    if axis == 1:
        return [[c, 0, s], [0, 1, 0], [-s, 0, c]]
    return [[c, -s, 0], [s, c, 0], [0, 0, 1]]


def mul3(a, b):
    return [[sum(a[r][k] * b[k][c] for k in range(3)) for c in range(3)] for r in range(3)]


# Application order of the three-axis rotates (xform.cpp's kKinds).
EULER_ORDERS = {"rotateXYZ": (0, 1, 2), "rotateXZY": (0, 2, 1), "rotateYXZ": (1, 0, 2),
                "rotateYZX": (1, 2, 0), "rotateZXY": (2, 0, 1), "rotateZYX": (2, 1, 0)}


def op_matrix(kind, value):
    """One xform op as a matrix (XformOp::matrix())."""
    m = identity()
    if kind == "translate":
        for r in range(3):
            m[r][3] = float(value[r])
    elif kind == "scale":
        for r in range(3):
            m[r][r] = float(value[r])
    elif kind in ("rotateX", "rotateY", "rotateZ"):
        m = from_rotation(axis_rotation("XYZ".index(kind[-1]), float(value)))
    elif kind in EULER_ORDERS:
        # Fixed-axis rotations compose right to left: the first axis is rightmost.
        i, j, k = EULER_ORDERS[kind]
        deg = [float(x) for x in value]
        m = from_rotation(mul3(axis_rotation(k, deg[k]), mul3(axis_rotation(j, deg[j]), axis_rotation(i, deg[i]))))
    elif kind == "orient":
        w, x, y, z = (float(v) for v in value)
        n = math.sqrt(w * w + x * x + y * y + z * z)
        w, x, y, z = w / n, x / n, y / n, z / n
        m = from_rotation([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                           [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                           [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    elif kind == "transform":
        # USD's row-vector rows are our columns (value_reader.cpp).
        rows = [[float(v) for v in row] for row in value]
        m = [[rows[c][r] for c in range(4)] for r in range(4)]
    else:
        raise ValueError(f"unknown xform op {kind}")
    return m


XFORM_KINDS = {"translate", "scale", "rotateX", "rotateY", "rotateZ", "orient", "transform", *EULER_ORDERS}


def xform_ops(prim):
    """(kind, value) in xformOpOrder: the order the keys are written in."""
    ops = []
    for key, value in prim.items():
        name = key[len("xformOp:"):] if key.startswith("xformOp:") else key
        kind = name.split(":", 1)[0]
        if kind in XFORM_KINDS:
            ops.append((kind, value))
    return ops


def local_matrix(prim):
    m = identity()
    for kind, value in xform_ops(prim):
        m = mul(m, op_matrix(kind, value))  # M = op[0] * op[1] * ... (last op applies first)
    return m


def decompose(m):
    """Translation and rotation of a matrix, scale and shear dropped (xform.cpp's decompose)."""
    cols = [[m[r][c] for r in range(3)] for c in range(3)]
    dot = lambda a, b: sum(a[i] * b[i] for i in range(3))
    norm = lambda a: math.sqrt(dot(a, a))
    x, y, z = cols
    x = [v / norm(x) for v in x]
    y = [y[i] - x[i] * dot(x, y) for i in range(3)]
    y = [v / norm(y) for v in y]
    z = [z[i] - x[i] * dot(x, z) - y[i] * dot(y, z) for i in range(3)]
    z = [v / norm(z) for v in z]
    rot = [[x[r], y[r], z[r]] for r in range(3)]
    det = (rot[0][0] * (rot[1][1] * rot[2][2] - rot[1][2] * rot[2][1])
           - rot[0][1] * (rot[1][0] * rot[2][2] - rot[1][2] * rot[2][0])
           + rot[0][2] * (rot[1][0] * rot[2][1] - rot[1][1] * rot[2][0]))
    if det < 0:  # a mirror: keep the rotation proper
        for r in range(3):
            rot[r][2] = -rot[r][2]
    return [m[0][3], m[1][3], m[2][3]], rot


def rigid(translation, rot):
    m = from_rotation(rot)
    for r in range(3):
        m[r][3] = translation[r]
    return m


# ---------------------------------------------------------------- the stage

class Stage:
    """A saved stage (or any scene without references) with schema defaults filled in."""

    def __init__(self, path, schema_path, extra_roots):
        with open(path) as f:
            self.doc = yaml.safe_load(f)
        self.path = os.path.abspath(path)
        self.folder = os.path.dirname(self.path)
        with open(schema_path) as f:
            definitions = json.load(f)["definitions"]
        self.defaults = {}
        for name, spec in definitions.items():
            if name.startswith("prim") and name not in ("primReference",):
                self.defaults[name[4:]] = {k: v["default"] for k, v in spec.get("properties", {}).items()
                                           if isinstance(v, dict) and "default" in v}
        self.prims = self.doc.get("prims") or {}
        for p, prim in self.prims.items():
            if prim is None:
                self.prims[p] = {}
            if "reference" in self.prims[p]:
                sys.exit(f"{p}: has a reference; save the stage with `sdgbehave run --save-stage` or "
                         f"`sdgbehave flatten` first")
        self.roots = [self.folder] + [os.path.join(self.folder, r) for r in self.doc.get("asset_roots", [])]
        self.roots += [os.path.abspath(r) for r in extra_roots]
        self.order = self._stage_order()
        self.up_axis = str((self.doc.get("stage") or {}).get("upAxis", "Z"))

    def _stage_order(self):
        """Depth first, siblings in document order: sdgbehave's traversal order."""
        children = {}
        for p in self.prims:
            parent = p.rsplit("/", 1)[0] or "/"
            children.setdefault(parent, []).append(p)
        order = []

        def visit(p):
            for c in children.get(p, []):
                order.append(c)
                visit(c)
        visit("/")
        return order

    def type_of(self, p):
        return self.prims[p].get("type", "Xform")

    def attr(self, p, name):
        prim = self.prims[p]
        if name in prim:
            return prim[name]
        return self.defaults.get(self.type_of(p), {}).get(name)

    def ancestors(self, p):
        """p, its parent, ... up to the top-level prim."""
        out = []
        while p and p != "/":
            if p in self.prims:
                out.append(p)
            p = p.rsplit("/", 1)[0]
        return out

    def world(self, p):
        m = identity()
        for a in reversed(self.ancestors(p)):
            m = mul(m, local_matrix(self.prims[a]))
        return m

    def invisible(self, p):
        return any(self.prims[a].get("visibility") == "invisible" for a in self.ancestors(p))

    def bound_material(self, p):
        """The closest binding above a prim, unless an ancestor binds strongerThanDescendants."""
        closest = strongest = None
        for a in self.ancestors(p):
            binding = self.prims[a].get("material")
            if binding is None:
                continue
            path = binding if isinstance(binding, str) else binding.get("path")
            strength = "weakerThanDescendants" if isinstance(binding, str) else binding.get("strength", "")
            if path not in self.prims or self.type_of(path) != "Material":
                continue
            if closest is None:
                closest = path
            if a != p and strength == "strongerThanDescendants":
                strongest = path
        return strongest or closest

    def resolve(self, asset, what):
        """An asset path as sdgbehave resolves it: the scene's folder, asset_roots, --asset-root."""
        if not asset:
            return ""
        if os.path.isabs(asset):
            if os.path.exists(asset):
                return asset
        else:
            for root in self.roots:
                candidate = os.path.normpath(os.path.join(root, asset))
                if os.path.exists(candidate):
                    return candidate
        if asset.startswith("/Isaac/"):
            sys.exit(f"{what}: '{asset}' is an Isaac asset path; pass its folder with --asset-root")
        sys.exit(f"{what}: '{asset}' not found (searched {', '.join(self.roots)})")


def rows(m):
    return [[float(v) for v in row] for row in m]


def material_of(stage, p):
    """The material a gprim is shaded with, as render_list.cpp's materialOf() fills it."""
    m = stage.bound_material(p)
    if m is None:
        return {"from_prim": False, "base_color": [float(c) for c in stage.attr(p, "primvars:displayColor")],
                "roughness": 0.5, "metallic": 0.0}
    a = lambda name: stage.attr(m, name)
    out = {"from_prim": True, "path": m,
           "base_color": [float(c) for c in a("inputs:diffuse_color_constant")],
           "roughness": float(a("inputs:reflection_roughness_constant")),
           "metallic": float(a("inputs:metallic_constant")),
           "specular_level": float(a("inputs:specular_level") if a("inputs:specular_level") is not None else 0.5),
           "texture_scale": [float(v) for v in a("inputs:texture_scale")],
           "texture_rotate": float(a("inputs:texture_rotate")),
           "project_uvw": bool(a("inputs:project_uvw"))}
    maps = {"base_color": "inputs:diffuse_texture", "roughness": "inputs:reflectionroughness_texture",
            "metallic": "inputs:metallic_texture", "normal": "inputs:normalmap_texture"}
    if a("inputs:enable_ORM_texture"):
        maps["orm"] = "inputs:ORM_texture"
    out["maps"] = {k: stage.resolve(a(v), f"{m}.{v}") for k, v in maps.items() if a(v)}
    # OmniPBR's map influences: value = mix(constant, map, influence) (newer inputs; absent in older schemas).
    out["roughness_influence"] = min(float(a("inputs:reflection_roughness_texture_influence") or 0.0), 1.0)
    out["metallic_influence"] = min(float(a("inputs:metallic_texture_influence") or 0.0), 1.0)
    out["normal_scale"] = float(a("inputs:bump_factor") if a("inputs:bump_factor") is not None else 1.0)
    if a("inputs:enable_opacity"):
        out["opacity_constant"] = float(a("inputs:opacity_constant"))
        if a("inputs:enable_opacity_texture") and a("inputs:opacity_texture"):
            out["maps"]["opacity"] = stage.resolve(a("inputs:opacity_texture"), f"{m}.inputs:opacity_texture")
        threshold = float(a("inputs:opacity_threshold") or 0.0)
        # OmniPBR's threshold 0 means fractional opacity, which sdgbehave cuts at one half.
        out["opacity_cutoff"] = threshold if threshold > 0 else 0.5
    return out


def radiance_of(stage, p):
    """USD radiance: intensity * 2^exposure * color (render_list.cpp's lightOf())."""
    scale = float(stage.attr(p, "inputs:intensity")) * 2.0 ** float(stage.attr(p, "inputs:exposure"))
    return [float(c) * scale for c in stage.attr(p, "inputs:color")]


def power_and_color(rgb, factor):
    """Blender lights take a scalar power and a colour: split factor * rgb into the two."""
    peak = max(rgb)
    if peak <= 0:
        return 0.0, [1.0, 1.0, 1.0]
    return factor * peak, [c / peak for c in rgb]


def emitting_area(stage, p, kind):
    """The area inputs:normalize divides the radiance by (render_list.cpp); 0: none."""
    a = lambda name: float(stage.attr(p, name))
    if kind == "RectLight":
        return a("inputs:width") * a("inputs:height")
    if kind == "DiskLight":
        return math.pi * a("inputs:radius") ** 2
    if kind == "SphereLight":
        return 4 * math.pi * a("inputs:radius") ** 2
    if kind == "CylinderLight":
        return 2 * math.pi * a("inputs:radius") * a("inputs:length")
    return 0.0  # a distant light's intensity is its irradiance already; a dome has no area


def light_of(stage, p, notes):
    kind = stage.type_of(p)
    translation, rot = decompose(stage.world(p))
    L = radiance_of(stage, p)
    # inputs:normalize: the radiance over the emitting area, as sdgbehave reads it.
    area = emitting_area(stage, p, kind) if stage.attr(p, "inputs:normalize") else 0.0
    if area > 0:
        L = [c / area for c in L]
    out = {"path": p, "matrix": rows(rigid(translation, rot))}
    # Both renderers of sdgbehave scale a light's diffuse and specular response
    # by these; a Cycles light has no such multipliers (only on/off ray
    # visibility), so the export leaves them out and says so.
    for name in ("inputs:diffuse", "inputs:specular"):
        if stage.attr(p, name) != 1.0:
            notes.append(f"{p}: {name} is {stage.attr(p, name)}; Cycles has no such multiplier, the export ignores it")
    if kind == "DistantLight":
        # sdgbehave: the radiance value is the irradiance at normal incidence.
        # Cycles' sun strength is irradiance in W/m^2: the same number.
        energy, color = power_and_color(L, 1.0)
        out.update(type="SUN", energy=energy, color=color, angle=math.radians(float(stage.attr(p, "inputs:angle"))))
    elif kind == "SphereLight":
        # sdgbehave: E = L * pi r^2 / d^2. Cycles' point light of power P: E = P / (4 pi d^2),
        # so P = 4 pi^2 r^2 L (its surface radiance is then P / (4 pi * pi r^2) = L).
        r = float(stage.attr(p, "inputs:radius"))
        energy, color = power_and_color(L, 4 * math.pi ** 2 * r * r)
        # treatAsPoint keeps the power of the radius (render_list.cpp) but has no size.
        size = 0.0 if stage.attr(p, "treatAsPoint") else r
        out.update(type="POINT", energy=energy, color=color, radius=size)
    elif kind in ("RectLight", "DiskLight"):
        # sdgbehave: E = L * A * cos(theta_light) / d^2, one-sided toward local -Z.
        # Cycles' area light of power P has radiance P / (4 A) (measured: README.md), so P = 4 A L.
        if kind == "RectLight":
            w, h = float(stage.attr(p, "inputs:width")), float(stage.attr(p, "inputs:height"))
            area = w * h
            out.update(shape="RECTANGLE", size=w, size_y=h)
            if stage.attr(p, "inputs:texture:file"):
                notes.append(f"{p}: inputs:texture:file is ignored (sdgbehave's renderer ignores it too)")
        else:
            r = float(stage.attr(p, "inputs:radius"))
            area = math.pi * r * r
            out.update(shape="DISK", size=2 * r, size_y=2 * r)
        energy, color = power_and_color(L, 4 * area)
        out.update(type="AREA", energy=energy, color=color)
    elif kind == "CylinderLight":
        # Blender has no cylinder light: an emissive tube (no caps) of radiance L,
        # which is USD's definition. sdgbehave approximates its irradiance
        # (L * 2 r length / d^2, whatever the angle), so the two differ off-axis.
        r, length = float(stage.attr(p, "inputs:radius")), float(stage.attr(p, "inputs:length"))
        out.update(type="EMISSIVE_MESH", radiance=L, mesh=primitives.cylinder_light_side(r, length))
    else:  # DomeLight
        texture = stage.attr(p, "inputs:texture:file")
        fmt = stage.attr(p, "inputs:texture:format")
        if texture and fmt not in ("automatic", "latlong"):
            notes.append(f"{p}: texture format {fmt} is exported as lat-long")
        # The dome's frame (render_list.cpp): on a Z-up stage its +Y pole is
        # first turned +90 degrees about X to +Z, then the prim's rotation.
        frame = rot
        if stage.up_axis == "Z":
            frame = mul3(rot, axis_rotation(0, 90.0))
        out.update(type="DOME", radiance=L, texture=stage.resolve(texture, f"{p}.inputs:texture:file") if texture else "",
                   frame=frame)
    return out


def camera_of(stage, p):
    translation, rot = decompose(stage.world(p))  # scale removed, as cameraOf() does
    a = lambda name: stage.attr(p, name)
    clip = a("clippingRange")
    return {"path": p, "matrix": rows(rigid(translation, rot)),
            "focal_length": float(a("focalLength")), "horizontal_aperture": float(a("horizontalAperture")),
            "vertical_aperture": float(a("verticalAperture")),
            "horizontal_aperture_offset": float(a("horizontalApertureOffset")),
            "vertical_aperture_offset": float(a("verticalApertureOffset")),
            "near": float(clip[0]), "far": float(clip[1]), "orthographic": a("projection") == "orthographic"}


def describe(stage, camera_path, resolution):
    notes = []
    doc = stage.doc
    cameras = [p for p in stage.order if stage.type_of(p) == "Camera"]
    wanted = (doc.get("capture") or {}).get("cameras") or cameras
    camera_path = camera_path or (wanted[0] if wanted else None)
    if camera_path not in cameras:
        sys.exit(f"no camera {camera_path!r} in the stage (cameras: {', '.join(cameras) or 'none'})")
    if resolution is None:
        resolution = (doc.get("render") or {}).get("resolution", [512, 512])
    meshes, objects, lights = {}, [], []
    for p in stage.order:
        kind = stage.type_of(p)
        if kind in GPRIMS:
            if stage.invisible(p):
                continue
            obj = {"path": p, "matrix": rows(stage.world(p)), "material": material_of(stage, p)}
            if kind == "Mesh":
                obj["file"] = stage.resolve(stage.attr(p, "asset"), f"{p}.asset")
                obj["submesh"] = stage.attr(p, "submesh") or ""
            else:
                attrs = {k: stage.attr(p, k) for k in ("size", "radius", "height", "width", "length", "axis")}
                key = json.dumps([kind] + [attrs[k] for k in sorted(attrs) if attrs[k] is not None])
                if key not in meshes:
                    meshes[key] = primitives.mesh_for(kind, attrs)
                obj["mesh"] = key
            objects.append(obj)
        elif kind in LIGHTS and not stage.invisible(p):
            lights.append(light_of(stage, p, notes))
    return {"source": stage.path, "resolution": [int(resolution[0]), int(resolution[1])],
            "camera": camera_of(stage, camera_path), "meshes": meshes, "objects": objects, "lights": lights,
            "notes": notes}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("stage", help="a stage saved by `sdgbehave run --save-stage` (or `sdgbehave flatten`)")
    parser.add_argument("-o", "--out", required=True, help="the Blender script to write")
    parser.add_argument("--camera", help="camera prim (default: the first of capture.cameras, else the first camera)")
    parser.add_argument("--resolution", help="WxH (default: the stage's render.resolution)")
    parser.add_argument("--asset-root", action="append", default=[], help="also search this folder for assets")
    parser.add_argument("--schema", default=os.path.join(HERE, "..", "..", "schemas", "scene.schema.json"),
                        help="the scene JSON Schema, for attribute defaults (default: the repository's)")
    parser.add_argument("--bsdf", choices=["principled", "lambert"], default="principled",
                        help="surfaces as Principled BSDFs (default) or as pure Lambert (base colour x (1 - metallic), "
                             "untextured), for checking light units")
    args = parser.parse_args()
    resolution = [int(v) for v in args.resolution.lower().split("x")] if args.resolution else None
    stage = Stage(args.stage, args.schema, args.asset_root)
    scene = describe(stage, args.camera, resolution)
    scene["bsdf"] = args.bsdf
    for note in scene["notes"]:
        print(f"stage_to_blender: note: {note}", file=sys.stderr)
    with open(os.path.join(HERE, "blender_scene.py")) as f:
        builder = f.read()
    with open(args.out, "w") as f:
        f.write(f"# Generated by tools/cycles/stage_to_blender.py from {stage.path}; do not edit.\n")
        f.write(f"# Run: blender -b --factory-startup --python-exit-code 1 --python {os.path.basename(args.out)}\n")
        f.write(f"SCENE_JSON = {json.dumps(json.dumps(scene, separators=(',', ':')))}\n\n")
        f.write(builder)
        f.write("\n\nbuild_scene(json.loads(SCENE_JSON))\n")
    print(f"stage_to_blender: {len(scene['objects'])} objects, {len(scene['lights'])} lights, "
          f"camera {scene['camera']['path']}, {scene['resolution'][0]}x{scene['resolution'][1]} -> {args.out}",
          file=sys.stderr)


if __name__ == "__main__":
    main()
