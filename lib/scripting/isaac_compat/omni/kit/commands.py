"""omni.kit.commands: the commands Isaac's behaviors and the tutorial's driver programs execute."""
import _isaac_compat
from _isaac_compat import module_getattr as _module_getattr, unsupported as _unsupported

__getattr__ = _module_getattr(__name__)

# The MDL materials sdgbehave's Material prim renders (its inputs are OmniPBR's).
_MDL_MATERIALS = ("OmniPBR.mdl",)

# CreateMeshPrimWithDefaultXform's shapes as sdgbehave's shape prims, sized
# as Kit makes them in a metre stage (a 1 m plane, a 1 m cube, ...).
_MESH_SHAPES = {
    "Plane": ("Plane", {"width": 1.0, "length": 1.0}),
    "Cube": ("Cube", {"size": 1.0}),
    "Sphere": ("Sphere", {"radius": 0.5}),
    "Cylinder": ("Cylinder", {"radius": 0.5, "height": 1.0}),
    "Cone": ("Cone", {"radius": 0.5, "height": 1.0}),
    "Capsule": ("Capsule", {"radius": 0.25, "height": 0.5}),
}


def _stage(what):
    _isaac_compat.driver_for(f"omni.kit.commands.execute({what!r})", "only a driver program (sdgbehave exec) runs it")
    return _isaac_compat.driver_stage()


def _default_xform(prim):
    """Kit's default ops on a new prim: translate, orient, scale."""
    from pxr import Gf, UsdGeom
    xformable = UsdGeom.Xformable(prim)
    names = [op.GetOpName() for op in xformable.GetOrderedXformOps()]
    if "xformOp:translate" not in names:
        xformable.AddTranslateOp().Set(Gf.Vec3d(0, 0, 0))
    if "xformOp:orient" not in names:
        xformable.AddOrientOp().Set(Gf.Quatd(1, 0, 0, 0))
    if "xformOp:scale" not in names:
        xformable.AddScaleOp().Set(Gf.Vec3d(1, 1, 1))


def _create_mesh_prim(prim_type="Cube", prim_path=None, select_new_prim=False, above_ground=False, **_kwargs):
    stage = _stage("CreateMeshPrimWithDefaultXform")
    shape = _MESH_SHAPES.get(str(prim_type))
    if shape is None:
        raise _unsupported(f"CreateMeshPrimWithDefaultXform prim_type={prim_type!r}",
                           f"the shapes are {', '.join(_MESH_SHAPES)}")
    path = str(prim_path) if prim_path else stage._s.next_free_path("/" + str(prim_type))
    prim = stage.DefinePrim(path, shape[0])
    for name, value in shape[1].items():
        prim.GetAttribute(name).Set(value)
    _default_xform(prim)
    return True, path


def _create_prim(prim_type="Xform", prim_path=None, select_new_prim=False, attributes=None, **_kwargs):
    stage = _stage("CreatePrim")
    path = str(prim_path) if prim_path else stage._s.next_free_path("/" + str(prim_type))
    prim = stage.DefinePrim(path, str(prim_type))
    if prim._h.is_xformable:
        _default_xform(prim)
    for name, value in (attributes or {}).items():
        prim.GetAttribute(str(name)).Set(value)
    return True, path


def _delete_prims(paths=(), destructive=False, **_kwargs):
    stage = _stage("DeletePrims")
    for path in paths:
        stage.RemovePrim(str(path))
    return True, None


def _move_prim(path_from, path_to, keep_world_transform=False, destructive=False, **_kwargs):
    """Renames or reparents a prim (its subtree, bindings into it following); the local transform is kept."""
    if keep_world_transform:
        raise _unsupported("MovePrim(keep_world_transform=True)", "the prim keeps its local transform")
    _stage("MovePrim")
    _isaac_compat.driver.move_prim(str(path_from), str(path_to))
    return True, None


def _apply_scripting_api(paths=(), **_kwargs):
    from pxr import Sdf
    stage = _stage("ApplyScriptingAPICommand")
    for path in paths:
        prim = stage.GetPrimAtPath(str(path))
        if prim and not prim.HasAttribute("omni:scripting:scripts"):
            prim.CreateAttribute("omni:scripting:scripts", Sdf.ValueTypeNames.AssetArray).Set(Sdf.AssetPathArray([]))
    return True, None


def _create_mdl_material_prim(mtl_url, mtl_name, mtl_path, select_new_prim=False, **_kwargs):
    """A Material prim at mtl_path with OmniPBR's inputs at their defaults
    (a behavior's under /Behaviors/<BEHAVIOR_NS>/, removed on stop)."""
    if str(mtl_url).rsplit("/", 1)[-1] not in _MDL_MATERIALS:
        raise _unsupported(f"omni.kit.commands.execute('CreateMdlMaterialPrim', mtl_url={mtl_url!r})",
                           "sdgbehave's Material renders OmniPBR.mdl only")
    behavior = _isaac_compat.current
    if behavior is not None:
        behavior.stage.DefinePrim(str(mtl_path), "Material")
    else:
        _stage("CreateMdlMaterialPrim").DefinePrim(str(mtl_path), "Material")
    return True, None


_COMMANDS = {
    "CreateMeshPrimWithDefaultXform": _create_mesh_prim,
    "CreateMeshPrim": _create_mesh_prim,
    "CreatePrim": _create_prim,
    "CreatePrimWithDefaultXform": _create_prim,
    "DeletePrims": _delete_prims,
    "MovePrim": _move_prim,
    "ApplyScriptingAPICommand": _apply_scripting_api,
    "CreateMdlMaterialPrim": _create_mdl_material_prim,
}


def execute(name, **kwargs):
    if name == "LockSpecsCommand":
        # Locking is a UI matter in Kit; sdgbehave's describe shows a variable's
        # `lock` from VARIABLES_TO_EXPOSE. Nothing to do on the stage.
        return True, None
    command = _COMMANDS.get(name)
    if command is None:
        raise _unsupported(f"omni.kit.commands.execute({name!r})",
                           f"the commands it runs are LockSpecsCommand, {', '.join(_COMMANDS)}")
    return command(**kwargs)
