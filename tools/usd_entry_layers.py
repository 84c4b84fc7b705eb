"""Which USD files under a folder are entry layers: the files a user would open.

A multi-layer asset is one entry layer plus layers it reaches through
subLayers, references and payloads; running such a dependency on its own says
little (it is often an `over`, or a variant without its context). The rule, in
order of strength:

1. A file named on the command line is an entry.
2. A folder's INVENTORY.md (the table of ../shared/usd-corpus) decides for the
   files it lists: a row whose role cell says **entry** is an entry, any other
   listed file is a dependency.
3. Any other USD file is an entry unless another USD file under the same folder
   names it as an asset path (`@...@` in a text layer; a token of a crate
   layer, whose token table is read here, LZ4 included). Asset paths resolve
   from the naming layer's folder, as USD anchors them; `a.usdz[b.usda]` names
   the package a.usdz.

Used by tools/usd_corpus.py. Standard library only.
"""
import os
import re
import struct

USD_EXTENSIONS = (".usd", ".usda", ".usdc", ".usdz")

# `| `path` | **entry** | ...`: the inventory's first two cells.
_INVENTORY_ROW = re.compile(r"^\|\s*`([^`]+)`[^|]*\|\s*([^|]*)\|")
_ASCII_ASSET = re.compile(rb"@([^@\n]+)@")


def is_usd(path):
    return path.lower().endswith(USD_EXTENSIONS)


def read_inventory(folder):
    """{absolute path: True (entry) / False (dependency)} from folder/INVENTORY.md; {} when absent."""
    roles = {}
    try:
        with open(os.path.join(folder, "INVENTORY.md"), encoding="utf-8") as f:
            lines = f.read().splitlines()
    except OSError:
        return roles
    for line in lines:
        m = _INVENTORY_ROW.match(line)
        if m and is_usd(m.group(1)):
            roles[os.path.normpath(os.path.join(folder, m.group(1)))] = "**entry**" in m.group(2)
    return roles


def _lz4_length(src, i, length):
    """A literal or match length: 15 in the token means more bytes follow, each added, until one below 255."""
    if length == 15:
        while i < len(src):
            length += src[i]
            i += 1
            if src[i - 1] != 255:
                break
    return length, i


def _lz4_block(src, limit):
    """One LZ4 block (the format USD's TfFastCompression writes), at most `limit` bytes out."""
    out = bytearray()
    i, n = 0, len(src)
    while i < n:
        token = src[i]
        i += 1
        length, i = _lz4_length(src, i, token >> 4)
        out += src[i:i + length]
        i += length
        if i >= n or len(out) > limit:
            break
        offset = src[i] | (src[i + 1] << 8)
        i += 2
        match, i = _lz4_length(src, i, token & 15)
        match += 4
        start = len(out) - offset
        if offset == 0 or start < 0:
            raise ValueError("bad LZ4 match offset")
        if offset >= match:
            out += out[start:start + match]
        else:  # overlapping copy: byte by byte
            for k in range(match):
                out.append(out[start + k])
    return bytes(out[:limit])


def _fast_decompress(data, limit):
    """TfFastCompression: a chunk count byte, then one LZ4 block (count 0) or int32-sized chunks."""
    chunks = data[0]
    if chunks == 0:
        return _lz4_block(data[1:], limit)
    out, i = bytearray(), 1
    for _ in range(chunks):
        (size,) = struct.unpack_from("<i", data, i)
        i += 4
        out += _lz4_block(data[i:i + size], limit - len(out))
        i += size
    return bytes(out)


def crate_tokens(data):
    """The token strings of a crate layer (PXR-USDC), or [] when it cannot be read."""
    try:
        if data[:8] != b"PXR-USDC":
            return []
        major, minor = data[8], data[9]
        (toc,) = struct.unpack_from("<q", data, 16)
        (sections,) = struct.unpack_from("<Q", data, toc)
        for k in range(min(sections, 64)):
            name, start, _size = struct.unpack_from("<16sqq", data, toc + 8 + 32 * k)
            if name.rstrip(b"\0") != b"TOKENS":
                continue
            (count,) = struct.unpack_from("<Q", data, start)
            if (major, minor) < (0, 4):
                (size,) = struct.unpack_from("<Q", data, start + 8)
                text = data[start + 16:start + 16 + size]
            else:
                plain, packed = struct.unpack_from("<QQ", data, start + 8)
                text = _fast_decompress(data[start + 24:start + 24 + packed], plain)
            return [t.decode("utf-8", "replace") for t in text.split(b"\0")[:count]]
    except (struct.error, IndexError, ValueError):
        pass
    return []


def named_assets(path):
    """Absolute paths of the USD files a layer names as assets (anchored at its folder)."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError:
        return set()
    if data.startswith(b"PXR-USDC"):
        names = crate_tokens(data)
    elif data.startswith(b"PK"):
        names = []  # a package's layers name files inside it
    else:
        names = [m.decode("utf-8", "replace") for m in _ASCII_ASSET.findall(data)]
    out = set()
    for name in names:
        name = name.split("[", 1)[0].strip()  # a.usdz[inner.usda] names the package
        if not is_usd(name):
            continue
        out.add(os.path.normpath(os.path.join(os.path.dirname(path), name)))
    return out


def usd_files(folder):
    found = []
    for root, dirs, files in os.walk(folder):
        dirs.sort()
        found += [os.path.join(root, f) for f in sorted(files) if is_usd(f)]
    return found


def entry_layers(folder, all_layers=False):
    """(entries, dependencies): absolute paths of the USD files under `folder`, each sorted."""
    folder = os.path.abspath(folder)
    files = [os.path.normpath(f) for f in usd_files(folder)]
    if all_layers:
        return files, []
    roles = read_inventory(folder)
    named = set()
    for f in files:
        named |= named_assets(f)
    entries, deps = [], []
    for f in files:
        entry = roles[f] if f in roles else f not in named
        (entries if entry else deps).append(f)
    return entries, deps
