"""isaacsim.core.utils.semantics: semantic labels on prims (the older
SemanticsAPI calls and the LabelsAPI ones), over sdgbehave's labels."""
from _isaac_compat import module_getattr as _module_getattr
from isaacsim.core import _labels

__getattr__ = _module_getattr(__name__)


def add_update_semantics(prim, semantic_label, type_label="class", suffix=""):
    """Sets the prim's `type_label` label to `semantic_label` (replacing it)."""
    if semantic_label is not None:
        _labels.set_labels(prim, type_label, [str(semantic_label)])


def remove_all_semantics(prim, recursive=False):
    _labels.remove(prim, include_descendants=recursive)


def get_semantics(prim):
    """{taxonomy: (taxonomy, label)} for each taxonomy's first label, as SemanticsAPI instances read."""
    return {t: (t, v[0]) for t, v in _labels.labels(prim).items() if v}


def add_labels(prim, labels, instance_name="class", overwrite=True):
    _labels.add(prim, instance_name, labels, overwrite)


def get_labels(prim):
    return _labels.labels(prim)


def remove_labels(prim, instance_name=None, include_descendants=False):
    _labels.remove(prim, taxonomy=instance_name, include_descendants=include_descendants)
