"""omni.physics.core: the physics stage update interface, whose reset_simulation releases the
simulation's state. sdgbehave's layer holds no simulation state between calls yet (omni.physx's
simulation interface is not mapped), so there is nothing to release; the stage keeps what scripts wrote,
as Isaac's stage does with /physics/resetOnStop off. Other names raise a located error
(see docs/isaac-scripts.md)."""
from _isaac_compat import Located as _Located, module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)


class IPhysicsStageUpdate(_Located):
    __slots__ = ()

    def reset_simulation(self):
        return None


_INTERFACE = IPhysicsStageUpdate()


def get_physics_stage_update_interface():
    return _INTERFACE
