"""Exposed variables on prims, attaching behavior scripts, and driving
event-controlled behaviors (Isaac Sim's behavior_utils, written for
sdgbehave's layer)."""
import carb
import carb.eventdispatcher
import omni.kit.app
import omni.kit.commands
from pxr import Sdf

from ..global_variables import EXPOSED_VARS_CHANGED_EVENT

_SCRIPTS_ATTR = "omni:scripting:scripts"


def _full_name(exposed_attr_ns, behavior_ns, attr_name):
    return f"{exposed_attr_ns}:{behavior_ns}:{attr_name}"


def _valid(prim):
    return prim is not None and prim.IsValid()


def _notify_changed():
    carb.eventdispatcher.get_eventdispatcher().dispatch_event(event_name=EXPOSED_VARS_CHANGED_EVENT, payload={})


def create_exposed_variable(prim, full_attr_name, attr_type, default_value, doc=None):
    """The attribute, made with its default when the prim does not have it yet."""
    attr = prim.GetAttribute(full_attr_name)
    if not attr:
        attr = prim.CreateAttribute(full_attr_name, attr_type)
        attr.Set(default_value)
        if doc:
            attr.SetDocumentation(doc)
    return attr


def create_exposed_variables(prim, exposed_attr_ns, behavior_ns, variables_to_expose):
    for record in variables_to_expose:
        create_exposed_variable(prim, _full_name(exposed_attr_ns, behavior_ns, record["attr_name"]),
                                record["attr_type"], record["default_value"], record.get("doc"))
    _notify_changed()


async def lock_exposed_variables(attr_paths):
    """Locking is a UI matter in Kit: nothing changes on the stage."""
    await omni.kit.app.get_app().next_update_async()
    omni.kit.commands.execute("LockSpecsCommand", spec_paths=attr_paths)


def check_if_exposed_variables_should_be_removed(prim, script_file_path):
    """True when the prim no longer lists the script (so its variables can go)."""
    if not _valid(prim):
        return False
    attr = prim.GetAttribute(_SCRIPTS_ATTR)
    listed = attr.Get() if attr else None
    return not listed or all(asset.path != script_file_path for asset in listed)


def remove_exposed_variable(prim, full_attr_name, remove_from_fabric=True):
    if not _valid(prim):
        carb.log_warn(f"cannot remove exposed variable {full_attr_name}: the prim is not valid")
        return
    if prim.GetAttribute(full_attr_name):
        prim.RemoveProperty(full_attr_name)
    else:
        carb.log_warn(f"Attribute {full_attr_name} not found on {prim.GetPath()}")


def remove_exposed_variables(prim, exposed_attr_ns, behavior_ns, variables_to_expose):
    for record in variables_to_expose:
        remove_exposed_variable(prim, _full_name(exposed_attr_ns, behavior_ns, record["attr_name"]))
    _notify_changed()


def get_exposed_variable(prim, full_attr_name):
    if not _valid(prim):
        carb.log_warn(f"cannot read exposed variable {full_attr_name}: the prim is not valid")
        return None
    attr = prim.GetAttribute(full_attr_name)
    return attr.Get() if attr else None


def set_exposed_variables(prim, exposed_variables):
    """Sets the attributes that exist (a behavior makes its variables when it starts)."""
    if not _valid(prim):
        carb.log_warn("cannot set exposed variables: the prim is not valid")
        return
    for name, value in exposed_variables.items():
        attr = prim.GetAttribute(name)
        if attr:
            attr.Set(value)
        else:
            print(f"Attribute {name} not found on {prim.GetPath()}")


def remove_empty_scopes(prim, stage):
    """Removes, deepest first, Scope and typeless prims left without children."""
    if not _valid(prim):
        return
    for child in prim.GetChildren():
        remove_empty_scopes(child, stage)
    if (prim.GetTypeName() or "Scope") == "Scope" and not prim.GetChildren():
        stage.RemovePrim(prim.GetPath())


def add_behavior_script(prim, script_path, allow_duplicates=False):
    """Lists the script in the prim's omni:scripting:scripts (once, unless duplicates are allowed)."""
    if not _valid(prim):
        carb.log_warn("cannot add a behavior script: the prim is not valid")
        return
    attr = prim.GetAttribute(_SCRIPTS_ATTR)
    if not attr:
        omni.kit.commands.execute("ApplyScriptingAPICommand", paths=[prim.GetPath()])
        attr = prim.GetAttribute(_SCRIPTS_ATTR)
    listed = [asset.path for asset in (attr.Get() or [])]
    if allow_duplicates or script_path not in listed:
        attr.Set(Sdf.AssetPathArray(listed + [script_path]))


async def add_behavior_script_with_parameters_async(prim, script_path, exposed_variables=None,
                                                    allow_duplicates=False):
    """Attaches the script, waits until it has made its variables (three updates), then sets them."""
    if not _valid(prim):
        carb.log_warn("cannot add a behavior script: the prim is not valid")
        return
    add_behavior_script(prim, script_path, allow_duplicates)
    for _ in range(3):
        await omni.kit.app.get_app().next_update_async()
    set_exposed_variables(prim, exposed_variables or {})


def _same(received, expected):
    """Payloads travel as str, number or bool: an Sdf.Path expected matches its string."""
    if isinstance(expected, (str, bool, int, float)) or expected is None:
        return received == expected
    return received == str(expected)


async def publish_event_and_wait_for_completion_async(publish_payload, expected_payload, publish_event_name,
                                                      subscribe_event_name, max_wait_updates, verbose=True):
    """Publishes an event, then waits up to max_wait_updates updates for a reply whose payload holds every
    expected key and value. True when it came."""
    done = False

    def on_reply(event):
        nonlocal done
        matches = all(_same(event.payload.get(k), v) for k, v in expected_payload.items())
        if verbose:
            print(f"\t{'Action completed' if matches else 'Action not complete'}, received payload: {event.payload}")
        done = done or matches

    dispatcher = carb.eventdispatcher.get_eventdispatcher()
    subscription = dispatcher.observe_event(event_name=subscribe_event_name, on_event=on_reply,
                                            observer_name="behavior_utils.publish_event_and_wait")
    try:
        if verbose:
            print(f"Publishing {publish_payload} on {publish_event_name}, waiting for {expected_payload}")
        dispatcher.dispatch_event(event_name=publish_event_name, payload=publish_payload)
        for update in range(max_wait_updates):
            if done:
                if verbose:
                    print(f"\t\tExpected payload received after {update} updates.")
                break
            await omni.kit.app.get_app().next_update_async()
        else:
            if verbose:
                print(f"\t\tTimeout after {max_wait_updates} updates.")
    finally:
        subscription.reset()
    return done
