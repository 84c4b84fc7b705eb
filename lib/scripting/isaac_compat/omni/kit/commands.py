"""omni.kit.commands: the commands the behavior extension executes."""
import _isaac_compat
from _isaac_compat import module_getattr as _module_getattr, unsupported as _unsupported

__getattr__ = _module_getattr(__name__)

# The MDL materials sdgbehave's Material prim renders (its inputs are OmniPBR's).
_MDL_MATERIALS = ("OmniPBR.mdl",)


def _create_mdl_material_prim(mtl_url, mtl_name, mtl_path, select_new_prim=False, **_kwargs):
    """A Material prim at mtl_path (under /Behaviors/<BEHAVIOR_NS>/, removed on
    stop) with OmniPBR's inputs at their defaults."""
    if str(mtl_url).rsplit("/", 1)[-1] not in _MDL_MATERIALS:
        raise _unsupported(f"omni.kit.commands.execute('CreateMdlMaterialPrim', mtl_url={mtl_url!r})",
                           "sdgbehave's Material renders OmniPBR.mdl only")
    behavior = _isaac_compat.current
    if behavior is None:
        raise _unsupported("omni.kit.commands.execute('CreateMdlMaterialPrim') outside a behavior's hook")
    behavior.stage.DefinePrim(str(mtl_path), "Material")
    return True, None


def execute(name, **kwargs):
    if name == "LockSpecsCommand":
        # Locking is a UI matter in Kit; sdgbehave's describe shows a variable's
        # `lock` from VARIABLES_TO_EXPOSE. Nothing to do on the stage.
        return True, None
    if name == "CreateMdlMaterialPrim":
        return _create_mdl_material_prim(**kwargs)
    raise _unsupported(f"omni.kit.commands.execute({name!r})")
