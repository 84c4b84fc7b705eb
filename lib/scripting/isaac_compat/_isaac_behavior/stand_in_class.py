"""Classes standing for sdgbehave's built-in behaviors under Isaac's names
(not an Isaac module). inspect.getfile(cls) is a path named like Isaac's
script file that exists nowhere, so attaching it to a prim runs the
built-in, as a stage listing Isaac's missing file does
(docs/isaac-scripts.md)."""
from _isaac_behavior.names import EXTENSION_NAME

# Isaac's module file -> (class name, the built-in it stands for).
STAND_INS = {
    "light_randomizer": ("LightRandomizer", "lightRandomizer"),
    "location_randomizer": ("LocationRandomizer", "locationRandomizer"),
    "look_at_behavior": ("LookAtBehavior", "lookAtBehavior"),
    "rotation_randomizer": ("RotationRandomizer", "rotationRandomizer"),
    "texture_randomizer": ("TextureRandomizer", "textureRandomizer"),
    "volume_stack_randomizer": ("VolumeStackRandomizer", "volumeStackRandomizer"),
}
# Behaviors driven by events answer on these.
_EVENT_DRIVEN = {"volumeStackRandomizer"}


def stand_in(class_name, namespace, module_name):
    attrs = {
        "__module__": module_name,
        "__doc__": f"sdgbehave's built-in {namespace} under Isaac's name; `sdgbehave describe {namespace}` "
                   f"lists its variables.",
        "BEHAVIOR_NS": namespace,
    }
    if namespace in _EVENT_DRIVEN:
        attrs["EVENT_NAME_IN"] = f"{EXTENSION_NAME}.{namespace}.in"
        attrs["EVENT_NAME_OUT"] = f"{EXTENSION_NAME}.{namespace}.out"
    return type(class_name, (), attrs)
