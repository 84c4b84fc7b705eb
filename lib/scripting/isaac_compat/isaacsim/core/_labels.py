"""What both of Isaac's semantics modules do, over sdgbehave's per-prim
labels (taxonomy -> labels; the `class` taxonomy drives segmentation and
boxes). Not an Isaac module."""
import _isaac_compat


def prim_of(prim):
    """A Usd.Prim, or the prim at a path of the stage in use."""
    if isinstance(prim, str) or type(prim).__name__ == "Path":
        from omni.usd import get_context
        stage = get_context().get_stage()
        found = stage.GetPrimAtPath(str(prim)) if stage is not None else None
        if not found:
            raise ValueError(f"no prim at {prim}")
        return found
    return prim


def prims(prim, include_descendants):
    from pxr import Usd
    prim = prim_of(prim)
    return list(Usd.PrimRange(prim)) if include_descendants else [prim]


def labels(prim):
    return {k: list(v) for k, v in prim_of(prim)._h.semantics.items()}


def set_labels(prim, taxonomy, values):
    prim_of(prim)._h.set_semantic_labels(list(values), str(taxonomy))


def add(prim, taxonomy, values, overwrite):
    values = [values] if isinstance(values, str) else list(values)
    current = [] if overwrite else labels(prim).get(taxonomy, [])
    set_labels(prim, taxonomy, current + [v for v in values if v not in current])


def remove(prim, taxonomy=None, values=None, include_descendants=False):
    for p in prims(prim, include_descendants):
        for t, current in labels(p).items():
            if taxonomy is not None and t != taxonomy:
                continue
            kept = [] if values is None else [v for v in current if v not in values]
            set_labels(p, t, kept)
