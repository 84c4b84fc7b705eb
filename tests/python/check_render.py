#!/usr/bin/python3
"""`sdgbehave render` writes a PNG that PIL and numpy read: the requested
size, RGBA, opaque, not a flat image."""
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

from checklib import failures, finish


def main():
    binary, scene = sys.argv[1:3]
    with tempfile.TemporaryDirectory() as tmp:
        out = f"{tmp}/look.png"
        subprocess.run([binary, "render", scene, "--out", out, "--resolution", "160x120", "--subframes", "2"],
                       check=True, capture_output=True)
        image = Image.open(out)
        pixels = np.asarray(image)
    if image.mode != "RGBA" or pixels.shape != (120, 160, 4):
        failures.append(f"mode {image.mode}, shape {pixels.shape}")
    if (pixels[..., 3] != 255).any():
        failures.append("alpha is not 255 everywhere")
    if pixels[..., :3].std() < 5:
        failures.append("the image is nearly flat")
    return finish(f"ok: {pixels.shape}, mean {pixels[..., :3].mean():.1f}")


if __name__ == "__main__":
    sys.exit(main())
