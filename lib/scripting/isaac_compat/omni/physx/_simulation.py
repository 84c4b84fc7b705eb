"""omni.physx's simulation interface over sdgbehave's ODE world (physics/physics_world.h, the world the
built-in volumeStackRandomizer stacks with).

The world is made on the first `simulate` after a reset: every prim with UsdPhysics.CollisionAPI applied
and `physics:collisionEnabled` on that is not part of a rigid body becomes a static box (Cube prims only:
Isaac's collision walls). Before each step the rigid bodies are synchronised with the stage: a prim with
UsdPhysics.RigidBodyAPI applied and `physics:rigidBodyEnabled` on joins at its current world pose (its
collider: the prim's own geometry, a mesh file loaded as the built-in loads it), one switched off or
removed leaves. `fetch_results` writes each body's pose into its prim's translate and orient ops.
Gravity is 9.81 m/s^2 down the stage's Z axis, in stage units; damping is PhysxRigidBodyAPI's of the
first body (ODE damps the whole world alike); friction is the `physics:dynamicFriction` of the
material bound with the 'physics' purpose to the first body. Bodies are visited in path order, so a run
is the same whatever Python's hashing."""
import _isaac_compat
import _sdgbehave
from pxr import _physics_schemas

_RIGID = "PhysicsRigidBodyAPI"
_COLLISION = "PhysicsCollisionAPI"


def _flag(handle, name, default):
    value = handle.get_attribute(name) if handle.has_attribute(name) else None
    return default if value is None else bool(value)


def _world_pose(handle):
    """(translation, 3x3 rotation (column vectors), scale) of a prim's world matrix."""
    m = handle.get_world_matrix()
    cols = [[m[r][c] for r in range(3)] for c in range(3)]
    scale = [sum(x * x for x in col) ** 0.5 for col in cols]
    rotation = [[cols[c][r] / scale[c] for c in range(3)] for r in range(3)]
    return (m[0][3], m[1][3], m[2][3]), rotation, scale


def _quat(r):
    """(w, x, y, z) of a rotation matrix (column-vector convention), Shepperd's method."""
    t = r[0][0] + r[1][1] + r[2][2]
    if t > 0:
        s = (t + 1.0) ** 0.5 * 2
        return (0.25 * s, (r[2][1] - r[1][2]) / s, (r[0][2] - r[2][0]) / s, (r[1][0] - r[0][1]) / s)
    if r[0][0] > r[1][1] and r[0][0] > r[2][2]:
        s = (1.0 + r[0][0] - r[1][1] - r[2][2]) ** 0.5 * 2
        return ((r[2][1] - r[1][2]) / s, 0.25 * s, (r[0][1] + r[1][0]) / s, (r[0][2] + r[2][0]) / s)
    if r[1][1] > r[2][2]:
        s = (1.0 + r[1][1] - r[0][0] - r[2][2]) ** 0.5 * 2
        return ((r[0][2] - r[2][0]) / s, (r[0][1] + r[1][0]) / s, 0.25 * s, (r[1][2] + r[2][1]) / s)
    s = (1.0 + r[2][2] - r[0][0] - r[1][1]) ** 0.5 * 2
    return ((r[1][0] - r[0][1]) / s, (r[0][2] + r[2][0]) / s, (r[1][2] + r[2][1]) / s, 0.25 * s)


class _Simulation:
    def __init__(self):
        self.reset()

    def reset(self):
        self._world = None
        self._dt = None
        self._statics = []   # static collider paths the world was made with
        self._bodies = {}    # prim path -> body id
        self._forces = []

    def _stage(self):
        b = _isaac_compat.current
        if b is None:
            raise RuntimeError("omni.physx: simulate called outside a behavior; sdgbehave's stage belongs to the "
                               f"running behavior ({_isaac_compat.DOCS})")
        return b.stage._s

    def _inside_body(self, path, bodies):
        return any(path == b or path.startswith(b + "/") for b in bodies)

    def _make_world(self, stage, dt):
        rigid = sorted(_physics_schemas.applied_paths(_RIGID))
        first = next((stage.get_prim(p) for p in rigid if stage.get_prim(p) is not None), None)
        linear = angular = None
        if first is not None:
            if first.has_attribute("physxRigidBody:linearDamping"):
                linear = first.get_attribute("physxRigidBody:linearDamping")
            if first.has_attribute("physxRigidBody:angularDamping"):
                angular = first.get_attribute("physxRigidBody:angularDamping")
        gravity = 9.81 / stage.meters_per_unit
        self._world = _sdgbehave.PhysicsWorld(dt, (0.0, 0.0, -gravity), 0.0 if linear is None else linear,
                                              0.05 if angular is None else angular)
        self._dt = dt
        for path in sorted(_physics_schemas.applied_paths(_COLLISION)):
            h = stage.get_prim(path)
            if h is None or not _flag(h, "physics:collisionEnabled", True) or self._inside_body(path, rigid):
                continue
            if h.type_name != "Cube":
                raise _isaac_compat.unsupported(f"omni.physx: the static collider {path} ({h.type_name})",
                                                "sdgbehave's layer simulates static Cube colliders only")
            size = h.get_attribute("size") if h.has_attribute("size") else 2.0
            center, rotation, scale = _world_pose(h)
            self._world.add_static_box([size / 2 * s for s in scale], center, rotation)
            self._statics.append(path)
        if first is not None:
            self._set_friction(stage, first.path)

    def _set_friction(self, stage, body_path):
        material = _physics_schemas.physics_material_of(body_path)
        m = stage.get_prim(material) if material else None
        if m is not None and m.has_attribute("physics:dynamicFriction"):
            self._world.set_friction(m.get_attribute("physics:dynamicFriction"))

    def _sync_bodies(self, stage):
        rigid = _physics_schemas.applied_paths(_RIGID)
        for path in [p for p in sorted(self._bodies) if p not in rigid or stage.get_prim(p) is None]:
            self._world.remove_body(self._bodies.pop(path))  # removed from the stage: it leaves
        for path in sorted(rigid):
            h = stage.get_prim(path)
            enabled = h is not None and _flag(h, "physics:rigidBodyEnabled", True)
            if enabled and path not in self._bodies:
                collider = h.collider()
                if collider is None:
                    raise _isaac_compat.unsupported(f"omni.physx: the rigid body {path} ({h.type_name})",
                                                    "sdgbehave's layer simulates bodies that are geometry prims")
                position, rotation, scale = _world_pose(h)
                if any(abs(s - 1.0) > 1e-9 for s in scale):
                    raise _isaac_compat.unsupported(f"omni.physx: the scaled rigid body {path} (scale {scale})",
                                                    "the layer's bodies keep their geometry's size")
                self._bodies[path] = self._world.add_body(collider, position, _quat(rotation), path)
            elif not enabled and path in self._bodies:
                self._world.remove_body(self._bodies.pop(path))

    def simulate(self, elapsed_time, current_time=0.0):
        stage = self._stage()
        if self._world is not None and (elapsed_time != self._dt or
                                        any(stage.get_prim(p) is None for p in self._statics)):
            self.reset()  # a new step size, or the walls it was made with are gone: a new world
        if self._world is None:
            self._make_world(stage, float(elapsed_time))
        self._sync_bodies(stage)
        for path, force, point in self._forces:
            if path in self._bodies:
                self._world.add_force_at_point(self._bodies[path], force, point)
        self._forces = []
        self._world.step()

    def fetch_results(self):
        if self._world is None:
            return
        stage = self._stage()
        for path in sorted(self._bodies):
            h = stage.get_prim(path)
            if h is None:
                continue
            position, (w, x, y, z) = self._world.pose(self._bodies[path])
            h.set_world_location(position)
            h.set_world_rotation([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                                  [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                                  [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])

    def apply_force_at_pos(self, stage_id, body_id, force, pos, mode="force"):
        from pxr import PhysicsSchemaTools
        path = str(PhysicsSchemaTools.intToSdfPath(body_id))
        self._forces.append((path, tuple(float(v) for v in force), tuple(float(v) for v in pos)))


SIMULATION = _Simulation()
