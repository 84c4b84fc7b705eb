"""isaacsim.replicator.behavior.behaviors: Isaac's six behaviors, each standing for sdgbehave's built-in of
that name (_isaac_behavior/stand_in_class.py)."""
import importlib as _importlib

from _isaac_behavior.stand_in_class import STAND_INS as _STAND_INS

__all__ = []
for _file, (_class_name, _namespace) in _STAND_INS.items():
    globals()[_class_name] = getattr(_importlib.import_module(f"{__name__}.{_file}"), _class_name)
    __all__.append(_class_name)
__all__.sort()
