#!/usr/bin/python3
"""Hostile USD input, run the way users run it: every file of
tests/data/usd/hostile (a negative face count, which used to crash with a
segmentation fault, indices outside the points, NaN and infinite points,
primvars too short for their interpolation, GeomSubset faces that do not
exist) makes `validate`, `inspect` and `run` exit 2 with the message at the
attribute's file:line:col, once; and a 1 MB .usdz whose entry inflates to
1 GiB is refused by all three quickly and within a few hundred MB.

  check_usd_hostile.py BIN REPO
"""
import os
import subprocess
import sys
import tempfile
import time
import zlib

from checklib import check, finish

# file -> (line:col of the attribute, the message after the location)
EXPECTED = {
    "negative_count.usda": ("13:9", "/World/Bad.faceVertexCounts: expected each face to have at least 3 vertices, "
                                    "found -1 for face 1"),
    "two_vertex_face.usda": ("13:9", "/World/Bad.faceVertexCounts: expected each face to have at least 3 vertices, "
                                     "found 2 for face 1"),
    "counts_sum.usda": ("14:9", "/World/Bad.faceVertexIndices: expected 8 indices (the sum of faceVertexCounts), "
                                "found 4"),
    "index_outside.usda": ("14:9", "/World/Bad.faceVertexIndices: expected each index to be one of the 5 points "
                                   "(0 to 4), found 7 at [5]"),
    "nan_points.usda": ("12:9", "/World/Bad.points: expected finite coordinates, found (1, nan, 0) at [2]"),
    "inf_points.usda": ("12:9", "/World/Bad.points: expected finite coordinates, found (1, -1, inf) at [1] "
                                "(2 of 4 points are)"),
    "normals_short.usda": ("15:9", "/World/Bad.normals: vertex needs 5 items (one per point), found 3"),
    "st_facevarying_short.usda": ("15:9", "/World/Bad.primvars:st: faceVarying needs 7 items (one per face-vertex), "
                                          "found 4"),
    "st_indices_outside.usda": ("18:9", "/World/Bad.primvars:st:indices: expected each index to be one of the 4 "
                                        "values (0 to 3), found 9 at [2]"),
    "display_color_uniform_short.usda": ("15:9", "/World/Bad.primvars:displayColor: uniform needs 2 items "
                                                 "(one per face), found 1"),
    "display_opacity_bad_interpolation.usda": ("15:9", "/World/Bad.primvars:displayOpacity: expected interpolation "
                                                       "constant, uniform, vertex, varying or faceVarying, found "
                                                       "'perFace'"),
    "subset_outside.usda": ("20:13", "/World/Bad/Top.indices: expected faces of /World/Bad (0 to 1), found 5 at [1]"),
}

MiB = 1 << 20


def sdg(binary, args, timeout=120):
    """Exit code, stderr + stdout, wall seconds and peak memory (MiB) of one command."""
    start = time.monotonic()
    with tempfile.TemporaryFile() as out:
        proc = subprocess.Popen([binary, *args], stdout=out, stderr=subprocess.STDOUT)
        deadline = start + timeout
        while True:
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            if time.monotonic() > deadline:
                proc.kill()
                pid, status, usage = os.wait4(proc.pid, 0)
                break
            time.sleep(0.01)
        out.seek(0)
        text = out.read().decode(errors="replace")
    code = os.waitstatus_to_exitcode(status)
    return code, text, time.monotonic() - start, usage.ru_maxrss / 1024


def commands(path, tmp):
    return [["validate", path], ["inspect", path],
            ["run", path, "--frames", "1", "--out", os.path.join(tmp, "out")]]


def zip_bomb(path, mib=1024):
    """A .usdz whose one entry, bomb.usdc, is `mib` MiB of zeros deflated
    (about 1 KB per MiB): each MiB deflated after a full flush repeats, so
    one MiB is compressed and the rest copied. Headers written by hand,
    sizes and CRC honest."""
    def le(n, width):
        return n.to_bytes(width, "little")
    comp = zlib.compressobj(9, zlib.DEFLATED, -15)
    block = bytes(MiB)
    first = comp.compress(block) + comp.flush(zlib.Z_FULL_FLUSH)
    second = comp.compress(block) + comp.flush(zlib.Z_FULL_FLUSH)
    third = comp.compress(block) + comp.flush(zlib.Z_FULL_FLUSH)
    check(second == third, "zip bomb: the deflate blocks after a full flush are not periodic")
    stream = first + second * (mib - 1) + comp.flush(zlib.Z_FINISH)
    check(zlib.decompressobj(-15).decompress(stream[:len(first) + len(second)]) == bytes(2 * MiB),
          "zip bomb: the repeated deflate block does not inflate to zeros")
    crc = 0
    for _ in range(mib):  # honest, though the size check refuses it before any CRC is met
        crc = zlib.crc32(block, crc)
    name = b"bomb.usdc"
    fields = le(20, 2) + le(0, 2) + le(8, 2) + le(0, 2) + le(0x21, 2) + le(crc, 4) + le(len(stream), 4) + \
        le(mib * MiB, 4) + le(len(name), 2) + le(0, 2)
    local = le(0x04034b50, 4) + fields + name
    central = le(0x02014b50, 4) + le(20, 2) + fields + le(0, 2) * 3 + le(0, 4) + le(0, 4) + name
    end = le(0x06054b50, 4) + le(0, 2) * 2 + le(1, 2) * 2 + le(len(central), 4) + \
        le(len(local) + len(stream), 4) + le(0, 2)
    with open(path, "wb") as f:
        f.write(local + stream + central + end)


def main():
    binary, repo = sys.argv[1], sys.argv[2]
    hostile = os.path.join(repo, "tests", "data", "usd", "hostile")
    files = sorted(f for f in os.listdir(hostile) if f.endswith(".usda"))
    check(sorted(EXPECTED) == files, f"{hostile} holds {files}; this check expects {sorted(EXPECTED)}")
    with tempfile.TemporaryDirectory() as tmp:
        for name in files:
            path = os.path.join(hostile, name)
            where, message = EXPECTED.get(name, ("?", "?"))
            located = f"{path}:{where}: error: {message}"
            for args in commands(path, tmp):
                code, text, _, _ = sdg(binary, args)
                what = f"{args[0]} {name}"
                check(code == 2, f"{what}: exit {code}, expected 2 (139 is the crash this guards against):\n{text}")
                check(located in text, f"{what}: expected\n  {located}\nin:\n{text}")
                check(text.count(message) == 1, f"{what}: the message is said {text.count(message)} times:\n{text}")

        # The zip bomb: 1 GiB in a 1 MB package, refused from the header.
        bomb = os.path.join(tmp, "bomb.usdz")
        zip_bomb(bomb)
        size = os.path.getsize(bomb)
        check(size < 2 * MiB, f"the zip bomb is {size} bytes, expected about 1 MB")
        for args in commands(bomb, tmp):
            code, text, seconds, peak = sdg(binary, args)
            what = f"{args[0]} bomb.usdz"
            print(f"{what}: exit {code} in {seconds:.2f} s, peak {peak:.0f} MiB")
            check(code == 2, f"{what}: exit {code}, expected 2:\n{text}")
            check("entry 'bomb.usdc' inflates to 1073741824 bytes, more than the limit of 268435456" in text,
                  f"{what}: expected the size check's message:\n{text}")
            check(peak < 300, f"{what}: peak memory {peak:.0f} MiB, expected under 300")
    return finish("usd hostile input: every file exits 2 located, the zip bomb is refused from its header")


if __name__ == "__main__":
    sys.exit(main())
