"""isaacsim.core.experimental.utils.semantics: semantic labels (LabelsAPI)
on prims or prim paths, over sdgbehave's labels."""
from _isaac_compat import module_getattr as _module_getattr
from isaacsim.core import _labels

__getattr__ = _module_getattr(__name__)


def add_labels(prim, *, labels, taxonomy="class"):
    """Adds labels to the prim's `taxonomy` (keeping those it has)."""
    _labels.add(prim, taxonomy, labels, overwrite=False)


def get_labels(prim, *, include_descendants=False):
    out = {}
    for p in _labels.prims(prim, include_descendants):
        for t, values in _labels.labels(p).items():
            out.setdefault(t, [])
            out[t] += [v for v in values if v not in out[t]]
    return out


def remove_labels(prim, *, labels, taxonomy=None, include_descendants=False):
    values = [labels] if isinstance(labels, str) else list(labels)
    _labels.remove(prim, taxonomy=taxonomy, values=values, include_descendants=include_descendants)


def remove_all_labels(prim, *, remove_taxonomies=False, include_descendants=False):
    _labels.remove(prim, include_descendants=include_descendants)
