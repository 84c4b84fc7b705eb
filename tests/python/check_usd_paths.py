#!/usr/bin/python3
"""USD files as people have them, run through the CLI from another working directory.

  check_usd_paths.py BIN REPO

- Paths: a .usdz whose root layer sits in a folder of the package (`x.usdz_FILES/scene.usda`) and
  names its texture `0/logo.png` from that folder, and whose prop is a package nested in the
  package with its own texture, is given by a relative path with folders from another working
  directory: validate, inspect, flatten, render and run exit 0, no path is doubled, the frame shows
  the textures. The same package mounted by a YAML `reference:` and used as a Mesh `asset:`.
- Git LFS pointers (tests/data/usd/lfs: a clone without `git lfs`): a sublayer, a payload, a YAML
  reference's sublayer, a mesh asset and a texture that are pointers exit 2 named as such at the
  line that names them, each error printed once.
- The corpus's Blender package (../shared/usd-corpus/usd-unity-sdk/test-roughness.usdz, textures
  `0/*.tga` inside) validates and renders with its textures, when the corpus is present.
"""
import io
import os
import re
import shutil
import subprocess
import sys
import tempfile
import zipfile

import numpy as np
from PIL import Image

from checklib import check, finish


def sdg(binary, *args, cwd):
    return subprocess.run([binary, *args], capture_output=True, text=True, cwd=cwd, timeout=300)


def png(rgb):
    out = io.BytesIO()
    Image.new("RGB", (8, 8), rgb).save(out, format="PNG")
    return out.getvalue()


def usdz(entries):
    """A package: stored entries in order, as USD writes them."""
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_STORED) as z:
        for name, data in entries:
            z.writestr(name, data)
    return out.getvalue()


def textured_quad(name, texture, z):
    return f'''
    def Mesh "{name}"
    {{
        point3f[] points = [(-1, -1, {z}), (1, -1, {z}), (1, 1, {z}), (-1, 1, {z})]
        int[] faceVertexCounts = [4]
        int[] faceVertexIndices = [0, 1, 2, 3]
        texCoord2f[] primvars:st = [(0, 0), (1, 0), (1, 1), (0, 1)] (interpolation = "faceVarying")
        uniform token subdivisionScheme = "none"
        rel material:binding = <Looks/Mat>
        def Scope "Looks"
        {{
            def Material "Mat"
            {{
                token outputs:surface.connect = <Surface.outputs:surface>
                def Shader "Surface"
                {{
                    uniform token info:id = "UsdPreviewSurface"
                    color3f inputs:diffuseColor.connect = <../Tex.outputs:rgb>
                    token outputs:surface
                }}
                def Shader "Tex"
                {{
                    uniform token info:id = "UsdUVTexture"
                    asset inputs:file = @{texture}@
                    float3 outputs:rgb
                }}
            }}
        }}
    }}
'''


def make_package(folder):
    """x.usdz: the root layer in x.usdz_FILES/, its texture 0/logo.png beside it (green); a prop
    referenced from parts/inner.usdz, a package in the package, textured from its own folder (blue)."""
    inner_layer = '#usda 1.0\n(\n    defaultPrim = "Prop"\n    upAxis = "Z"\n    metersPerUnit = 1\n)\n' \
                  'def Xform "Prop"\n{' + textured_quad("Card", "maps/blue.png", 0) + '}\n'
    inner = usdz([("geo/prop.usda", inner_layer), ("geo/maps/blue.png", png((20, 40, 230)))])
    root = '#usda 1.0\n(\n    defaultPrim = "World"\n    upAxis = "Z"\n    metersPerUnit = 1\n)\n' \
           'def Xform "World"\n{' + textured_quad("Floor", "0/logo.png", 0) + '''
    def Xform "Prop" (
        prepend references = @../parts/inner.usdz@
    )
    {
        double3 xformOp:translate = (0, 0, 0.5)
        float3 xformOp:scale = (0.4, 0.4, 1)
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:scale"]
    }
    def Camera "Cam"
    {
        double3 xformOp:translate = (0, 0, 4)
        uniform token[] xformOpOrder = ["xformOp:translate"]
    }
    def DomeLight "Sky"
    {
        float inputs:intensity = 1000
    }
}
'''
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "x.usdz")
    with open(path, "wb") as f:
        f.write(usdz([("x.usdz_FILES/scene.usda", root), ("x.usdz_FILES/0/logo.png", png((30, 220, 40))),
                      ("parts/inner.usdz", inner)]))
    return path


def shows_green_and_blue(path, what):
    rgb = np.asarray(Image.open(path).convert("RGB")).astype(int).reshape(-1, 3)
    green = ((rgb[:, 1] > 100) & (rgb[:, 1] > 2 * rgb[:, 0]) & (rgb[:, 1] > 2 * rgb[:, 2])).mean()
    blue = ((rgb[:, 2] > 100) & (rgb[:, 2] > 2 * rgb[:, 0]) & (rgb[:, 2] > 2 * rgb[:, 1])).mean()
    check(green > 0.05 and blue > 0.02, f"{what}: the textures do not show (green {green:.3f}, blue {blue:.3f})")


def check_paths(binary, tmp):
    work = os.path.join(tmp, "work")
    other = os.path.join(tmp, "elsewhere")
    os.makedirs(other)
    make_package(os.path.join(work, "a", "b"))
    rel = os.path.relpath(os.path.join(work, "a", "b", "x.usdz"), other)  # ../work/a/b/x.usdz
    check(rel.count("/") >= 3, f"the path given should hold folders: {rel}")
    for args in (["validate", rel], ["inspect", rel], ["flatten", rel, "-o", "flat.yaml"],
                 ["render", rel, "--resolution", "64x64", "-o", "pic.png"],
                 ["run", rel, "--frames", "1", "--resolution", "64x64", "--out", "ds"]):
        p = sdg(binary, *args, cwd=other)
        check(p.returncode == 0, f"{args[0]} {rel} from another folder: exit {p.returncode}: {p.stderr[-600:]}")
        check("a/b/a/b" not in p.stderr and "not found" not in p.stderr, f"{args[0]} {rel}: {p.stderr[-600:]}")
    if os.path.exists(os.path.join(other, "pic.png")):
        shows_green_and_blue(os.path.join(other, "pic.png"), f"render {rel}")
    if os.path.exists(os.path.join(other, "ds", "rgb_0000.png")):
        shows_green_and_blue(os.path.join(other, "ds", "rgb_0000.png"), f"run {rel}")
    # The flattened scene names the same files from wherever it is read.
    if os.path.exists(os.path.join(other, "flat.yaml")):
        p = sdg(binary, "validate", os.path.join("elsewhere", "flat.yaml"), cwd=tmp)
        check(p.returncode == 0, f"validate the flattened package from {tmp}: exit {p.returncode}: {p.stderr[-600:]}")

    # A YAML scene in another folder mounting the package and using it as a mesh asset.
    scenes = os.path.join(work, "scenes")
    os.makedirs(scenes)
    with open(os.path.join(scenes, "mount.yaml"), "w") as f:
        f.write("version: 1\nrender: {resolution: [64, 64]}\ncapture: {cameras: [/World/Cam], frames: 1}\n"
                "writer: {type: BasicWriter, rgb: true}\nprims:\n  /World: {type: Xform}\n"
                "  /World/Pkg: {reference: ../a/b/x.usdz}\n"
                "  /World/Card: {type: Mesh, asset: '../a/b/x.usdz', translate: [3.0, 0.0, 0.0]}\n"
                "  /World/Cam: {type: Camera, translate: [0.0, 0.0, 6.0]}\n"
                "  /World/Sky: {type: DomeLight, inputs:intensity: 1000.0}\n")
    scene = os.path.relpath(os.path.join(scenes, "mount.yaml"), other)
    for args in (["validate", scene], ["run", scene, "--out", "ds_yaml"]):
        p = sdg(binary, *args, cwd=other)
        check(p.returncode == 0, f"{args[0]} {scene} from another folder: exit {p.returncode}: {p.stderr[-600:]}")


def error_lines(stderr):
    return [line for line in stderr.splitlines() if "error" in line.lower()]


def check_lfs(binary, repo, tmp):
    data = os.path.join(repo, "tests", "data", "usd", "lfs")
    elsewhere = os.path.join(tmp, "lfs_cwd")
    os.makedirs(elsewhere)
    rel = os.path.relpath(data, elsewhere)
    pointer = r"\S*/lfs/geometry\.usd"
    lfs = r"is a Git LFS pointer, not a USD layer: run git lfs pull"
    cases = [
        ("sublayer.usda", rf"{re.escape(rel)}/sublayer\.usda:6:9: error: sublayer @\./geometry\.usd@: {pointer} {lfs}"),
        ("payload.usda", rf"{re.escape(rel)}/payload\.usda:10:27: error: payload @\./geometry\.usd@: {pointer} {lfs}"),
        ("mount.yaml", rf"{re.escape(rel)}/mount\.yaml:6:16: error: .*sublayer\.usda:6:9: sublayer @\./geometry\.usd@: "
                       rf"{pointer} {lfs}"),
        ("mesh.yaml", r"mesh 'geometry\.usd'.*geometry\.usd is a Git LFS pointer, not a mesh: run git lfs pull"),
        ("texture.usda", r"texture\.usda:39:17: error: .*wood\.png is a Git LFS pointer, not an image: run git lfs pull"),
    ]
    for command in ("validate", "inspect", "run"):
        for scene, pattern in cases:
            args = [command, os.path.join(rel, scene)] + (["--out", "ds_" + scene] if command == "run" else [])
            p = sdg(binary, *args, cwd=elsewhere)
            check(p.returncode == 2, f"{command} {scene}: exit {p.returncode}, expected 2: {p.stderr[-600:]}")
            found = [line for line in p.stderr.splitlines() if re.search(pattern, line)]
            check(len(found) == 1, f"{command} {scene}: expected one line matching {pattern!r}, "
                                   f"found {len(found)}:\n{p.stderr[-1200:]}")
            lines = error_lines(p.stderr)
            check(len(lines) == len(set(lines)), f"{command} {scene}: an error printed twice:\n{p.stderr[-1200:]}")


def check_corpus(binary, repo, tmp):
    package = os.path.normpath(os.path.join(repo, "..", "shared", "usd-corpus", "usd-unity-sdk",
                                            "test-roughness.usdz"))
    if not os.path.exists(package):
        print(f"note: {package} absent; the corpus check is skipped")
        return
    rel = os.path.relpath(package, tmp)
    p = sdg(binary, "validate", rel, cwd=tmp)
    check(p.returncode == 0, f"validate {rel}: exit {p.returncode}: {p.stderr[-600:]}")
    p = sdg(binary, "render", rel, "--resolution", "96x96", "-o", "roughness.png", cwd=tmp)
    check(p.returncode == 0 and "texture" not in p.stderr,
          f"render {rel}: exit {p.returncode}: {p.stderr[-600:]}")


def main():
    binary, repo = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    with tempfile.TemporaryDirectory() as tmp:
        check_paths(binary, tmp)
        check_lfs(binary, repo, tmp)
        check_corpus(binary, repo, tmp)
    return finish("usd paths: ok")


if __name__ == "__main__":
    sys.exit(main())
