#!/usr/bin/python3
"""Generates tests/data/images/*.png (run with Debian's /usr/bin/python3 and
python3-pil). Deterministic."""
import os
import struct
import zlib

from PIL import Image

OUT = os.path.join(os.path.dirname(__file__), "..", "tests", "data", "images")


def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def main():
    os.makedirs(OUT, exist_ok=True)
    split = Image.new("RGB", (64, 64))
    split.putdata([(220, 30, 30) if x < 32 else (30, 30, 220) for y in range(64) for x in range(64)])
    split.save(os.path.join(OUT, "split.png"))
    sky = Image.new("RGB", (64, 32))
    sky.putdata([(30, 60, 230) if y < 16 else (40, 200, 40) for y in range(32) for x in range(64)])
    sky.save(os.path.join(OUT, "sky.png"))
    Image.new("I;16", (8, 8), 40000).save(os.path.join(OUT, "grey16.png"))
    palette = Image.new("P", (8, 8))
    palette.putpalette([255, 0, 0, 0, 255, 0])
    palette.putdata([(x + y) % 2 for y in range(8) for x in range(8)])
    palette.save(os.path.join(OUT, "palette.png"))
    Image.new("LA", (8, 8), (128, 200)).save(os.path.join(OUT, "grey_alpha.png"))
    # A tiny file whose header claims 100000 x 100000 pixels.
    header = struct.pack(">IIBBBBB", 100000, 100000, 8, 2, 0, 0, 0)
    with open(os.path.join(OUT, "huge_header.png"), "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(b"\0" * 10)) + chunk(b"IEND", b""))


if __name__ == "__main__":
    main()
