"""Classes standing for sdgbehave's built-in behaviors under Isaac's names
(not an Isaac module). inspect.getfile(cls) is a path named like Isaac's
script file that exists nowhere, so attaching it to a prim runs the
built-in, as a stage listing Isaac's missing file does
(docs/isaac-scripts.md)."""
from ..global_variables import EXTENSION_NAME


def stand_in(class_name, namespace, module_name, events=False):
    attrs = {
        "__module__": module_name,
        "__doc__": f"sdgbehave's built-in {namespace} under Isaac's name; `sdgbehave describe {namespace}` "
                   f"lists its variables.",
        "BEHAVIOR_NS": namespace,
    }
    if events:
        attrs["EVENT_NAME_IN"] = f"{EXTENSION_NAME}.{namespace}.in"
        attrs["EVENT_NAME_OUT"] = f"{EXTENSION_NAME}.{namespace}.out"
    return type(class_name, (), attrs)
