"""omni.physics.core: the physics stage update interface, whose reset_simulation releases the
simulation's world (omni.physx's ODE world: the next simulate makes a new one); the stage keeps the poses
written, as Isaac's stage does with /physics/resetOnStop off. Other names raise a located error
(see docs/isaac-scripts.md)."""
from _isaac_compat import Located as _Located, module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)


class IPhysicsStageUpdate(_Located):
    __slots__ = ()

    def reset_simulation(self):
        from omni.physx._simulation import SIMULATION
        SIMULATION.reset()


_INTERFACE = IPhysicsStageUpdate()


def get_physics_stage_update_interface():
    return _INTERFACE
