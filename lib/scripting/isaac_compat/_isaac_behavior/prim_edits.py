"""Transforms, assets, materials, colliders, rigid bodies and simulation
steps on prims (Isaac Sim's scene_utils, written for sdgbehave's layer: the
same functions and arguments, over the layer's pxr and omni modules)."""
import carb
import carb.settings
import omni.kit.app
import omni.kit.commands
import omni.physics.core
import omni.physx
import omni.usd
from pxr import Gf, PhysxSchema, Sdf, Usd, UsdGeom, UsdPhysics, UsdShade

_ORIENT, _TRANSFORM, _ROTATE = "xformOp:orient", "xformOp:transform", "xformOp:rotate"

# rotateABC op -> (the axes Gf.Rotation.Decompose takes, which result goes to A, B, C).
_DECOMPOSITION = {
    "XYZ": ((Gf.Vec3d.ZAxis, Gf.Vec3d.YAxis, Gf.Vec3d.XAxis), (2, 1, 0)),
    "XZY": ((Gf.Vec3d.YAxis, Gf.Vec3d.ZAxis, Gf.Vec3d.XAxis), (2, 0, 1)),
    "YXZ": ((Gf.Vec3d.ZAxis, Gf.Vec3d.XAxis, Gf.Vec3d.YAxis), (1, 2, 0)),
    "YZX": ((Gf.Vec3d.XAxis, Gf.Vec3d.ZAxis, Gf.Vec3d.YAxis), (0, 2, 1)),
    "ZXY": ((Gf.Vec3d.YAxis, Gf.Vec3d.XAxis, Gf.Vec3d.ZAxis), (1, 0, 2)),
    "ZYX": ((Gf.Vec3d.XAxis, Gf.Vec3d.YAxis, Gf.Vec3d.ZAxis), (0, 1, 2)),
}


def get_world_location(prim, xform_cache=None):
    return (xform_cache or UsdGeom.XformCache()).GetLocalToWorldTransform(prim).ExtractTranslation()


def get_world_rotation(prim, xform_cache=None):
    matrix = (xform_cache or UsdGeom.XformCache()).GetLocalToWorldTransform(prim)
    return Gf.Transform(matrix).GetRotation()


def _ops(prim):
    return UsdGeom.Xformable(prim).GetOrderedXformOps()


def get_rotation_op_and_value(prim):
    """The prim's first rotation op and its value (a transform op's rotation); a new identity orient op when it
    has none."""
    for op in _ops(prim):
        name = op.GetOpName()
        if name.startswith(_ROTATE) or name == _ORIENT:
            return name, op.Get()
        if name == _TRANSFORM:
            return name, Gf.Transform(op.Get()).GetRotation()
    identity = Gf.Quatd(1.0, 0.0, 0.0, 0.0)
    UsdGeom.Xformable(prim).AddXformOp(UsdGeom.XformOp.TypeOrient, UsdGeom.XformOp.PrecisionDouble).Set(identity)
    return _ORIENT, identity


def set_rotation_op_and_value(prim, rotation_op, rotation_val):
    for op in _ops(prim):
        if op.GetOpName() != rotation_op:
            continue
        if rotation_op == _TRANSFORM:
            transform = Gf.Transform(op.Get())
            transform.SetRotation(rotation_val)
            op.Set(transform.GetMatrix())
        else:
            op.Set(rotation_val)
        return


def decompose_rotation(rotation, rotation_order):
    """Euler angles (degrees) of `rotation` for a rotate<order> op; one angle for a single-axis order."""
    single = rotation_order in ("X", "Y", "Z")
    axes, slots = _DECOMPOSITION.get("XYZ" if single else rotation_order, (None, None))
    if axes is None:
        raise ValueError(f"Unsupported rotation_order: {rotation_order!r}")
    angles = rotation.Decompose(*(axis() for axis in axes))
    vector = Gf.Vec3f(angles[slots[0]], angles[slots[1]], angles[slots[2]])
    return vector["XYZ".index(rotation_order)] if single else vector


def set_rotation_with_ops(prim, rotation):
    """Writes `rotation` into the prim's first rotation op in its own form; a new orient op when it has none."""
    for op in _ops(prim):
        name = op.GetOpName()
        if name == _ORIENT:
            quat = rotation.GetQuat()
            op.Set(Gf.Quatf(quat) if op.GetTypeName() == Sdf.ValueTypeNames.Quatf else Gf.Quatd(quat))
            return
        if name.startswith(_ROTATE):
            try:
                op.Set(decompose_rotation(rotation, name[len(_ROTATE):]))
            except ValueError as error:
                carb.log_warn(f"[{prim.GetPath()}] {error}")
            return
        if name == _TRANSFORM:
            transform = Gf.Transform(op.Get())
            transform.SetRotation(rotation)
            op.Set(transform.GetMatrix())
            return
    UsdGeom.Xformable(prim).AddXformOp(UsdGeom.XformOp.TypeOrient, UsdGeom.XformOp.PrecisionDouble).Set(
        Gf.Quatd(rotation.GetQuat()))


def calculate_look_at_rotation(eye, target_location, up_axis, epsilon=1e-5):
    """The rotation that aims a prim at eye toward target_location (USD cameras look down -Z)."""
    direction = target_location - eye
    if direction.GetCross(up_axis).GetLength() < epsilon:
        # Looking along the up axis: nudge the eye off it so the rotation is defined.
        nudge = next(axis for i, axis in enumerate((Gf.Vec3d(1, 0, 0), Gf.Vec3d(0, 1, 0), Gf.Vec3d(0, 0, 1)))
                     if i == 2 or abs(up_axis[i]) < epsilon)
        eye = eye + nudge * epsilon
    return Gf.Matrix4d().SetLookAt(eye, target_location, up_axis).GetInverse().ExtractRotation()


def _listed_order(prim):
    """The prim's xformOpOrder as a list, and its attribute (falsy when it has none)."""
    attr = prim.GetAttribute("xformOpOrder")
    return (list(attr.Get() or []) if attr else []), attr


def _write_op(prim, name, value, add):
    """`value` into the prim's op `name` (the first op of that kind for the one-of-a-kind ops), made with
    `add` when the prim has none, and the op listed in xformOpOrder."""
    kind = name.split(":")[1]
    op = next((o for o in _ops(prim) if (o.GetOpName() if kind.startswith("rotate") else o.GetOpType()) ==
               (name if kind.startswith("rotate") else kind)), None)
    (op or add()).Set(value)
    order, attr = _listed_order(prim)
    if name not in order:
        (attr or prim.CreateAttribute("xformOpOrder", Sdf.ValueTypeNames.TokenArray)).Set(order + [name])


def set_location(prim, location):
    _write_op(prim, "xformOp:translate", location, UsdGeom.Xformable(prim).AddTranslateOp)


def set_orientation(prim, orientation):
    """An orient op at the orientation; an existing op keeps its own precision."""
    if not isinstance(orientation, (Gf.Quatf, Gf.Quatd)):
        raise TypeError("Orientation must be Gf.Quatf or Gf.Quatd")
    if _ORIENT in _listed_order(prim)[0]:
        kind = Gf.Quatf if prim.GetAttribute(_ORIENT).GetTypeName() == Sdf.ValueTypeNames.Quatf else Gf.Quatd
        orientation = kind(orientation)
    precision = UsdGeom.XformOp.PrecisionFloat if isinstance(orientation, Gf.Quatf) else \
        UsdGeom.XformOp.PrecisionDouble
    _write_op(prim, _ORIENT, orientation, lambda: UsdGeom.Xformable(prim).AddOrientOp(precision=precision))


def set_rotation(prim, rotation):
    """A rotateXYZ op at the rotation (Euler degrees, or a Gf.Rotation decomposed as USD does)."""
    if isinstance(rotation, Gf.Rotation):
        rotation = decompose_rotation(rotation, "XYZ")
    elif not isinstance(rotation, (Gf.Vec3f, Gf.Vec3d)):
        raise TypeError("Rotation must be Gf.Vec3f, Gf.Vec3d, or Gf.Rotation")
    _write_op(prim, "xformOp:rotateXYZ", Gf.Vec3f(rotation), UsdGeom.Xformable(prim).AddRotateXYZOp)


def set_scale(prim, scale):
    _write_op(prim, "xformOp:scale", scale, UsdGeom.Xformable(prim).AddScaleOp)


def set_transform_matrix(prim, transform):
    _write_op(prim, _TRANSFORM, transform, UsdGeom.Xformable(prim).AddTransformOp)


def set_transform_attributes(prim, location=None, orientation=None, rotation=None, scale=None, transform=None):
    for value, setter in ((transform, set_transform_matrix), (location, set_location),
                          (orientation, set_orientation), (rotation, set_rotation), (scale, set_scale)):
        if value is not None:
            setter(prim, value)


def create_asset(stage, asset_url, prim_path):
    prim = stage.DefinePrim(prim_path, "Xform")
    prim.GetReferences().AddReference(asset_url)
    return prim


def create_physics_material(stage, prim_path, restitution, static_friction, dynamic_friction):
    material = UsdShade.Material.Define(stage, prim_path)
    api = UsdPhysics.MaterialAPI.Apply(material.GetPrim())
    api.CreateRestitutionAttr().Set(restitution)
    api.CreateStaticFrictionAttr().Set(static_friction)
    api.CreateDynamicFrictionAttr().Set(dynamic_friction)
    return material


def create_mdl_material(mtl_url, mtl_name, mtl_path):
    omni.kit.commands.execute("CreateMdlMaterialPrim", mtl_url=mtl_url, mtl_name=mtl_name, mtl_path=mtl_path)
    prim = omni.usd.get_context().get_stage().GetPrimAtPath(mtl_path)
    shader = UsdShade.Shader(omni.usd.get_shader_from_material(prim, get_prim=True))
    for name, kind in (("diffuse_texture", Sdf.ValueTypeNames.Asset), ("project_uvw", Sdf.ValueTypeNames.Bool),
                       ("texture_scale", Sdf.ValueTypeNames.Float2), ("texture_rotate", Sdf.ValueTypeNames.Float)):
        shader.CreateInput(name, kind)
    return UsdShade.Material(prim)


def add_colliders(prim, approximation_type="convexHull", physics_scene=None):
    for p in Usd.PrimRange(prim):
        if p.IsA(UsdGeom.Gprim):
            api = UsdPhysics.CollisionAPI(p) if p.HasAPI(UsdPhysics.CollisionAPI) else UsdPhysics.CollisionAPI.Apply(p)
            api.CreateCollisionEnabledAttr(True)
            if physics_scene:
                api.GetSimulationOwnerRel().AddTarget(physics_scene.GetPath())
        if p.IsA(UsdGeom.Mesh):
            api = UsdPhysics.MeshCollisionAPI(p) if p.HasAPI(UsdPhysics.MeshCollisionAPI) \
                else UsdPhysics.MeshCollisionAPI.Apply(p)
            api.CreateApproximationAttr().Set(approximation_type)


def disable_colliders(prim, include_descendants=True):
    for p in (Usd.PrimRange(prim) if include_descendants else [prim]):
        if p.HasAPI(UsdPhysics.CollisionAPI):
            UsdPhysics.CollisionAPI(p).CreateCollisionEnabledAttr(False)


def add_rigid_body_dynamics(prim, physics_scene=None, disable_gravity=False, angular_damping=None,
                            linear_damping=None):
    body = UsdPhysics.RigidBodyAPI(prim) if prim.HasAPI(UsdPhysics.RigidBodyAPI) \
        else UsdPhysics.RigidBodyAPI.Apply(prim)
    body.CreateRigidBodyEnabledAttr(True)
    if physics_scene:
        body.GetSimulationOwnerRel().AddTarget(physics_scene.GetPath())
    physx = PhysxSchema.PhysxRigidBodyAPI(prim) if prim.HasAPI(PhysxSchema.PhysxRigidBodyAPI) \
        else PhysxSchema.PhysxRigidBodyAPI.Apply(prim)
    physx.GetDisableGravityAttr().Set(disable_gravity)
    if angular_damping is not None:
        physx.CreateAngularDampingAttr().Set(angular_damping)
    if linear_damping is not None:
        physx.CreateLinearDampingAttr().Set(linear_damping)


def disable_rigid_body_dynamics(prim, include_descendants=True):
    for p in (Usd.PrimRange(prim) if include_descendants else [prim]):
        if p.HasAPI(UsdPhysics.RigidBodyAPI):
            UsdPhysics.RigidBodyAPI(p).CreateRigidBodyEnabledAttr(False)


def create_collision_walls(stage, prim, prim_path, height, thickness=0.4, physics_scene=None,
                           physics_material=None, bbox_cache=None, visible=False):
    """Six box colliders (floor, ceiling, four sides) around the prim's bounds, `height` high above its top."""
    bbox_cache = bbox_cache or UsdGeom.BBoxCache(Usd.TimeCode.Default(), includedPurposes=[UsdGeom.Tokens.default_])
    bound = bbox_cache.ComputeWorldBound(prim)
    frame = bound.GetMatrix()
    scale = Gf.Transform(frame).GetScale()
    box = bound.GetRange()
    size = [box.GetSize()[i] * scale[i] for i in range(3)]
    middle = box.GetMidpoint()
    top = [middle[i] * scale[i] for i in range(3)]
    top[2] += size[2] / 2.0  # the top face's centre: the walls stand on it
    walls = []
    for name, axis, side in (("floor", 2, -1), ("ceiling", 2, 1), ("left_wall", 0, -1), ("right_wall", 0, 1),
                             ("back_wall", 1, -1), ("front_wall", 1, 1)):
        extent = [size[0], size[1], height]  # a side wall spans the volume's height
        extent[axis] = thickness
        centre = [top[0], top[1], top[2] + height / 2.0]
        if axis == 2:  # floor below the top face, ceiling above the volume
            centre[2] = top[2] - thickness / 2.0 if side < 0 else top[2] + height + thickness / 2.0
        else:
            centre[axis] += side * (size[axis] + thickness) / 2.0
        walls.append((name, tuple(centre), tuple(extent)))
    root = stage.DefinePrim(omni.usd.get_stage_next_free_path(stage, f"{prim_path}/CollisionWalls", False), "Xform")
    UsdGeom.Xformable(root).AddTransformOp().Set(frame.RemoveScaleShear())
    made = []
    for name, position, extent in walls:
        wall = stage.DefinePrim(f"{root.GetPath()}/{name}", "Cube")
        set_transform_attributes(wall, location=position, scale=tuple(e / 2.0 for e in extent))
        add_colliders(wall, physics_scene=physics_scene)
        if not visible:
            UsdGeom.Imageable(wall).MakeInvisible()
        if physics_material is not None:
            UsdShade.MaterialBindingAPI.Apply(wall).Bind(physics_material, UsdShade.Tokens.weakerThanDescendants,
                                                         "physics")
        made.append(wall)
    return made


async def run_simulation_async(sim_steps, physx_dt, render=True):
    simulation = omni.physx.get_physx_simulation_interface()
    for _ in range(sim_steps):
        simulation.simulate(physx_dt, 0)
        simulation.fetch_results()
        if render:
            await omni.kit.app.get_app().next_update_async()


async def apply_forces_and_simulate_async(stage_id, body_ids, forces, positions, sim_steps, physx_dt, render=True):
    simulation = omni.physx.get_physx_simulation_interface()
    for body, force, position in zip(body_ids, forces, positions):
        simulation.apply_force_at_pos(stage_id, body, carb.Float3(*force), carb.Float3(*position))
    await run_simulation_async(sim_steps, physx_dt, render)


def disable_simulation_reset_on_stop():
    carb.settings.get_settings().set(omni.physx.bindings._physx.SETTING_RESET_ON_STOP, False)


def reset_simulation_and_enable_reset_on_stop():
    settings = carb.settings.get_settings()
    if settings.get(omni.physx.bindings._physx.SETTING_RESET_ON_STOP):
        carb.log_warn("Expected 'omni.physx.bindings._physx.SETTING_RESET_ON_STOP' to be False, skipping "
                      "reset_simulation")
        return
    omni.physics.core.get_physics_stage_update_interface().reset_simulation()
    settings.set(omni.physx.bindings._physx.SETTING_RESET_ON_STOP, True)
