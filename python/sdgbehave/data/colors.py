"""Colourised segmentation back to ids.

Colourised masks (the BasicWriter's default) paint id i in Replicator's
colour for i (0 transparent black, 1 opaque black, then a hash of i to a
hue), and their JSON is keyed by colour text "(R, G, B, A)". The hash is
reproduced here exactly (64-bit integer steps, double-precision colour), so
each colour maps back to its id and a colourised mask reads like a raw one."""
import numpy as np

_MASK64 = np.uint64(0xFFFFFFFFFFFFFFFF)


def id_colors(count):
    """(count, 4) uint8: the colour of ids 0 .. count-1."""
    ids = np.arange(count, dtype=np.uint64)
    h = ids.copy()
    with np.errstate(over="ignore"):
        h ^= h >> np.uint64(16)
        h = (h * np.uint64(0x85EBCA6B)) & _MASK64
        h ^= h >> np.uint64(13)
        h = (h * np.uint64(0xC2B2AE35)) & _MASK64
        h ^= h >> np.uint64(16)
    idf = ids.astype(np.float64)
    hue = np.fmod(idf * (1.0 / 1.618033988749895), 1.0)
    hue = np.fmod(hue + 0.1 * (h & np.uint64(0xFFFF)).astype(np.float64) / 65536.0, 1.0)
    sat = 0.7 + 0.3 * ((h >> np.uint64(16)) & np.uint64(0xFF)).astype(np.float64) / 255.0
    val = 0.8 + 0.2 * ((h >> np.uint64(8)) & np.uint64(0xFF)).astype(np.float64) / 255.0
    whole = np.floor(hue * 6.0)
    sector = whole.astype(np.int64) % 6
    f = hue * 6.0 - whole
    p, q, t = val * (1 - sat), val * (1 - sat * f), val * (1 - sat * (1 - f))
    r = np.choose(sector, [val, q, p, p, t, val])
    g = np.choose(sector, [t, val, val, q, p, p])
    b = np.choose(sector, [p, p, t, val, val, q])
    colors = np.stack([r, g, b, np.ones_like(r)], axis=1) * 255.0
    colors = colors.astype(np.uint8)  # truncation, as the C++ cast
    colors[0:1] = (0, 0, 0, 0)
    colors[1:2] = (0, 0, 0, 255)
    return colors


def color_key(rgba):
    return "({}, {}, {}, {})".format(*(int(c) for c in rgba))


def parse_color_key(key):
    """"(R, G, B, A)" -> (R, G, B, A); ValueError for anything else."""
    parts = key.strip().lstrip("(").rstrip(")").split(",")
    if len(parts) != 4:
        raise ValueError(f"not a colour key: {key!r}")
    return tuple(int(p) for p in parts)


_table = id_colors(1 << 12)


def ids_of_colors(colors):
    """{(R, G, B, A): id} for each colour, the smallest id painted that colour; KeyError naming a
    colour no id up to 2^24 has."""
    global _table
    wanted = set(colors)
    found = {}
    while True:
        packed = _table.view(np.uint32).reshape(-1)
        for color in wanted - set(found):
            hits = np.flatnonzero(packed == np.array(color, dtype=np.uint8).view(np.uint32)[0])
            if hits.size:
                found[color] = int(hits[0])
        if len(found) == len(wanted) or len(_table) >= (1 << 24):
            break
        _table = id_colors(len(_table) * 4)
    if len(found) != len(wanted):
        raise KeyError(f"no id up to 2^24 has the colour {sorted(wanted - set(found))[0]}")
    return found


def decode_mask(rgba, keys):
    """A colourised (H, W, 4) mask and the colour keys of its JSON -> ((H, W) uint32 ids,
    {colour key: id}). Pixels of a colour not among the keys get id 0."""
    colors = {parse_color_key(k): k for k in keys}
    id_of = ids_of_colors(list(colors))
    packed = np.ascontiguousarray(rgba).view(np.uint32)[..., 0]
    present, inverse = np.unique(packed, return_inverse=True)
    by_packed = {int(np.array(c, dtype=np.uint8).view(np.uint32)[0]): i for c, i in id_of.items()}
    lookup = np.array([by_packed.get(int(v), 0) for v in present], dtype=np.uint32)
    return lookup[inverse].reshape(packed.shape), {colors[c]: i for c, i in id_of.items()}
