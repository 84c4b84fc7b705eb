"""PLY meshes (BOP object models): vertices, their other properties and triangles, into numpy.

Reads ascii and binary (little or big endian) PLY with a `vertex` element
of scalar properties and a `face` element whose list property
(`vertex_indices` or `vertex_index`) holds the corners; other elements are
skipped when they come after these (as in every BOP model)."""
import numpy as np

from .folder import DatasetError

_TYPES = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2", "int16": "i2",
          "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
          "float": "f4", "float32": "f4", "double": "f8", "float64": "f8"}


def _header(f, path):
    if f.readline().strip() != b"ply":
        raise DatasetError(f"{path}: not a PLY file")
    fmt, elements = None, []
    while True:
        line = f.readline()
        if not line:
            raise DatasetError(f"{path}: the PLY header has no end_header")
        words = line.decode("ascii", "replace").split()
        if not words or words[0] in ("comment", "obj_info"):
            continue
        if words[0] == "end_header":
            return fmt, elements
        if words[0] == "format":
            fmt = words[1]
        elif words[0] == "element":
            elements.append({"name": words[1], "count": int(words[2]), "props": []})
        elif words[0] == "property" and elements:
            if words[1] == "list":
                elements[-1]["props"].append((words[4], _TYPES[words[2]], _TYPES[words[3]]))
            else:
                elements[-1]["props"].append((words[2], _TYPES[words[1]], None))


def _ascii_element(words, offset, element):
    props, count = element["props"], element["count"]
    if all(p[2] is None for p in props):
        width = len(props)
        table = np.array(words[offset:offset + count * width], dtype=np.float64).reshape(count, width)
        return {name: table[:, i] for i, (name, _, _) in enumerate(props)}, offset + count * width
    if len(props) != 1:
        raise ValueError(f"element {element['name']} mixes a list with other properties")
    rows = []
    for _ in range(count):
        n = int(words[offset])
        rows.append([int(w) for w in words[offset + 1:offset + 1 + n]])
        offset += 1 + n
    return {props[0][0]: rows}, offset


def _binary_element(body, offset, element, order):
    props, count = element["props"], element["count"]
    if all(p[2] is None for p in props):
        dtype = np.dtype([(name, order + t) for name, t, _ in props])
        table = np.frombuffer(body, dtype=dtype, count=count, offset=offset)
        return {name: table[name] for name, _, _ in props}, offset + count * dtype.itemsize
    if len(props) != 1:
        raise ValueError(f"element {element['name']} mixes a list with other properties")
    name, length_type, index_type = props[0]
    length_dtype, index_dtype = np.dtype(order + length_type), np.dtype(order + index_type)
    triangles = np.dtype([("n", length_dtype), ("corners", index_dtype, (3,))])
    if len(body) - offset >= count * triangles.itemsize:
        # Triangles only (every BOP model): one read, checked by the counts.
        table = np.frombuffer(body, dtype=triangles, count=count, offset=offset)
        if np.all(table["n"] == 3):
            return {name: table["corners"]}, offset + count * triangles.itemsize
    rows = []
    for _ in range(count):
        n = int(np.frombuffer(body, dtype=length_dtype, count=1, offset=offset)[0])
        offset += length_dtype.itemsize
        rows.append(np.frombuffer(body, dtype=index_dtype, count=n, offset=offset))
        offset += n * index_dtype.itemsize
    return {name: rows}, offset


def read_ply(path):
    """{"vertices": (N, 3) float64, "faces": (M, 3) int64 (triangles; polygons are fanned),
    "properties": {name: (N,) array} for every vertex property}."""
    with open(path, "rb") as f:
        fmt, elements = _header(f, path)
        body = f.read()
    if fmt not in ("ascii", "binary_little_endian", "binary_big_endian"):
        raise DatasetError(f"{path}: unknown PLY format {fmt!r}")
    words = body.split() if fmt == "ascii" else None
    properties, faces, offset = {}, np.zeros((0, 3), dtype=np.int64), 0
    try:
        for element in elements:
            if fmt == "ascii":
                columns, offset = _ascii_element(words, offset, element)
            else:
                columns, offset = _binary_element(body, offset, element, "<" if fmt == "binary_little_endian" else ">")
            if element["name"] == "vertex":
                properties = {k: np.asarray(v) for k, v in columns.items()}
            elif element["name"] == "face":
                corners = columns.get("vertex_indices", columns.get("vertex_index", []))
                if isinstance(corners, np.ndarray):
                    faces = corners.astype(np.int64).reshape(-1, 3)
                    break
                faces = np.array([(p[0], p[i], p[i + 1]) for p in corners for i in range(1, len(p) - 1)],
                                 dtype=np.int64).reshape(-1, 3)
                break
    except (ValueError, IndexError) as e:
        raise DatasetError(f"{path}: corrupt PLY body: {e}") from None
    if not all(axis in properties for axis in "xyz"):
        raise DatasetError(f"{path}: no vertex x, y, z")
    vertices = np.stack([properties[a].astype(np.float64) for a in "xyz"], axis=1)
    return {"vertices": vertices, "faces": faces, "properties": properties}
