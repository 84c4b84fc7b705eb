# Renders the scene built by a stage_to_blender.py script with Cycles and
# writes linear radiance as .npy (float32, H x W x 3, rows top first) plus
# the render's timing as JSON. Runs inside Blender, after the scene script:
#
#   blender -b --factory-startup --python stage_blender.py --python tools/cycles/cycles_render.py -- \
#       --samples 1024 --out DIR [--name cycles_1024] [--denoise]
#
# The time is taken inside Blender around bpy.ops.render.render() alone:
# scene sync, BVH build and path tracing, not Blender's start-up nor the
# writing of files. render_cycles.sh runs one process per sample count and
# also takes the whole process's wall time.
import argparse
import json
import os
import sys
import time

import bpy
import numpy as np


def options():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="cycles_render.py")
    parser.add_argument("--samples", type=int, required=True)
    parser.add_argument("--out", required=True, help="folder for NAME.npy, NAME.exr and NAME.json")
    parser.add_argument("--name", help="file stem (default: cycles_SAMPLES, with _oidn when denoised)")
    parser.add_argument("--denoise", action="store_true", help="OpenImageDenoise, when this Blender has it")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--threads", type=int, default=0, help="0: one per core")
    return parser.parse_args(argv)


def oidn_available():
    import _cycles  # Cycles' Python module, present in every Blender with Cycles
    return bool(getattr(_cycles, "with_openimagedenoise", False))


def main():
    args = options()
    scene = bpy.context.scene
    cy = scene.cycles
    cy.samples = args.samples
    cy.seed = args.seed
    if args.denoise:
        if not oidn_available():
            sys.exit("cycles_render.py: this Blender was built without OpenImageDenoise")
        cy.use_denoising = True
        cy.denoiser = "OPENIMAGEDENOISE"
    else:
        cy.use_denoising = False
    scene.render.threads_mode = "FIXED" if args.threads else "AUTO"
    if args.threads:
        scene.render.threads = args.threads
    name = args.name or f"cycles_{args.samples}" + ("_oidn" if args.denoise else "")
    os.makedirs(args.out, exist_ok=True)

    start = time.perf_counter()
    bpy.ops.render.render()
    seconds = time.perf_counter() - start

    # Full-float EXR of the render result, scene-linear (no view transform is
    # applied to EXR), then read back as numpy.
    exr = os.path.join(args.out, name + ".exr")
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_depth = "32"
    settings.exr_codec = "ZIP"
    bpy.data.images["Render Result"].save_render(exr)
    image = bpy.data.images.load(exr, check_existing=False)
    w, h = image.size
    pixels = np.empty(w * h * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    rgb = pixels.reshape(h, w, 4)[::-1, :, :3]  # Blender's rows run bottom to top
    np.save(os.path.join(args.out, name + ".npy"), np.ascontiguousarray(rgb, dtype=np.float32))
    bpy.data.images.remove(image)

    record = {"name": name, "renderer": "cycles", "samples": args.samples, "denoised": args.denoise,
              "seconds_render": seconds, "resolution": [w, h], "blender": bpy.app.version_string,
              "device": cy.device, "threads": scene.render.threads, "seed": args.seed,
              "max_bounces": cy.max_bounces, "pixel_filter": f"{cy.pixel_filter_type} {cy.filter_width}",
              "oidn_available": oidn_available()}
    with open(os.path.join(args.out, name + ".json"), "w") as f:
        json.dump(record, f, indent=2)
    print(f"cycles_render: {name}: {w}x{h}, {args.samples} samples, {seconds:.3f} s")


main()
