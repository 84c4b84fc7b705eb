"""omni.physx: the simulation interface (get_physx_simulation_interface: simulate, fetch_results,
apply_force_at_pos) over sdgbehave's ODE world (omni/physx/_simulation.py), and the `/physics/resetOnStop`
setting's name (bindings._physx.SETTING_RESET_ON_STOP, on by default as in Isaac Sim). Every other name
raises a located error (see docs/isaac-scripts.md)."""
import carb.settings as _settings
from _isaac_compat import module_getattr as _module_getattr

from . import bindings  # noqa: F401  (scripts reach omni.physx.bindings._physx after `import omni.physx`)

__getattr__ = _module_getattr(__name__)

if _settings.get_settings().get(bindings._physx.SETTING_RESET_ON_STOP) is None:
    _settings.get_settings().set(bindings._physx.SETTING_RESET_ON_STOP, True)


def get_physx_simulation_interface():
    from ._simulation import SIMULATION
    return SIMULATION
