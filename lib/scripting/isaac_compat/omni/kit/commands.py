"""omni.kit.commands: the commands the behavior extension executes."""
from _isaac_compat import module_getattr as _module_getattr, unsupported as _unsupported

__getattr__ = _module_getattr(__name__)


def execute(name, **kwargs):
    if name == "LockSpecsCommand":
        # Locking is a UI matter in Kit; sdgbehave's describe shows a variable's
        # `lock` from VARIABLES_TO_EXPOSE. Nothing to do on the stage.
        return True, None
    raise _unsupported(f"omni.kit.commands.execute({name!r})")
