#!/usr/bin/python3
"""Generates the procedural textures under scenes/textures/ (small PNGs made
by this project; see third_party_notes/project-assets.md). Deterministic:
running it again rewrites the same files."""
import math
import os
import random

from PIL import Image

OUT = os.path.join(os.path.dirname(__file__), "..", "scenes", "textures")
SIZE = 128


def wood(x, y, rnd):
    rings = math.sin((x * 0.05 + 4 * math.sin(y * 0.03)) * 6.0 + rnd[(x // 8 + y // 32) % len(rnd)])
    t = 0.5 + 0.5 * rings
    return (int(140 + 60 * t), int(95 + 40 * t), int(50 + 20 * t))


def bamboo(x, y, rnd):
    stripe = 0.5 + 0.5 * math.sin(x * 0.4)
    node = 1.0 if (y % 42) < 3 else 0.0
    base = 0.75 - 0.25 * node
    return (int((170 + 50 * stripe) * base), int((150 + 40 * stripe) * base), int((80 + 20 * stripe) * base))


def boards(x, y, rnd):
    board = y // 21
    seam = (y % 21) < 1
    shade = rnd[board % len(rnd)] * 0.3 + 0.7
    grain = 0.9 + 0.1 * math.sin(x * 0.2 + board * 3.1)
    if seam:
        return (40, 30, 20)
    return (int(160 * shade * grain), int(110 * shade * grain), int(70 * shade * grain))


def checker(x, y, rnd):
    on = ((x // 16) + (y // 16)) % 2 == 0
    return (230, 230, 230) if on else (40, 40, 40)


def main():
    os.makedirs(OUT, exist_ok=True)
    rng = random.Random(1234)
    rnd = [rng.uniform(0, 6.28) for _ in range(32)]
    for name, fn in [("wood", wood), ("bamboo", bamboo), ("boards", boards), ("checker", checker)]:
        img = Image.new("RGB", (SIZE, SIZE))
        img.putdata([fn(x, y, rnd) for y in range(SIZE) for x in range(SIZE)])
        img.save(os.path.join(OUT, f"{name}.png"), optimize=True)


if __name__ == "__main__":
    main()
