#!/usr/bin/python3
"""Isaac's example_behavior.py and example_custom_event_behavior.py (read in place from
<repo>/../shared/isaac-behaviors) run unchanged: the pre-roll publishes the custom-event behavior's `.in`
event on sdgbehave's bus and waits for the `.out` reply the script dispatches through
carb.eventdispatcher, matched on its payload (a reply that does not match fails the run, so the replies
are really on the bus); the example behavior's hooks run every frame (scripts print to stderr). volume_stack_randomizer.py sets up
(crates and collision walls, checked from --save-stage), and its run, whose PhysX calls the layer does not
map yet, fails with the layer's located message (the missing name, the Isaac file:line that used it, the
docs page), exit 1; the physics schemas it authors are checked by
tests/data/isaac_scripts/physics_schemas_probe.py.

usage: check_isaac_examples.py SDGBEHAVE SCENE_DIR SHARED_DIR"""
import os
import subprocess
import sys
import tempfile

import yaml

from checklib import check, finish


def run(binary, scene, out):
    return subprocess.run([binary, "run", scene, "--out", out, "--no-render"], capture_output=True, text=True,
                          timeout=120)


def check_volume_stack_setup(binary, scene, tmp):
    """volume_stack.yaml's setup alone: the crates (Isaac's create_asset: an Xform referencing a mesh file,
    a Mesh prim here) at the surface's pose, and six collision walls around the surface's top, sized from
    UsdGeom.BBoxCache as Isaac's create_collision_walls sizes them."""
    with open(scene) as f:
        text = f.read()
    setup_only = os.path.join(os.path.dirname(scene), ".volume_stack_setup.yaml")
    saved = os.path.join(tmp, "setup_stage.yaml")
    try:
        with open(setup_only, "w") as f:
            f.write(text[:text.index("  - publish: isaacsim.replicator.behavior.volumeStackRandomizer.in\n"
                                     "    payload: {action: run}")])
        p = subprocess.run([binary, "run", setup_only, "--out", os.path.join(tmp, "setup"), "--no-render",
                            "--save-stage", saved], capture_output=True, text=True, timeout=120)
    finally:
        os.remove(setup_only)
    check(p.returncode == 0, f"volume_stack.yaml setup only: exit {p.returncode}: {p.stderr[-800:]}")
    with open(saved) as f:
        prims = yaml.safe_load(f)["prims"]
    assets = {k: v for k, v in prims.items() if k.startswith("/Behaviors/volumeStackRandomizer/Assets/Pallet/Asset_")}
    check(4 <= len(assets) <= 6, f"expected 4 to 6 crates (assets:numRange [4, 6]), found {sorted(assets)}")
    for path, a in assets.items():
        check(a.get("type") == "Mesh" and a.get("asset") == "meshes/crate.glb", f"{path}: {a}")
        check(a.get("translate") == [0.0, 0.0, 0.07], f"{path}: not at the surface's origin: {a}")
    walls = "/Behaviors/volumeStackRandomizer/CollisionWalls/Pallet/CollisionWalls/"
    floor = prims.get(walls + "floor", {})
    # Pallet: a size-2 Cube scaled (0.6, 0.5, 0.07) at z 0.07, so its top is at z 0.14; the floor is 0.4 thick
    # below it, and the walls' root sits at the pallet's origin.
    check(floor.get("scale") == [0.6, 0.5, 0.2] and abs(floor["translate"][2] + 0.13) < 1e-9,
          f"floor wall: {floor}")
    check(floor.get("attributes", {}).get("physics:collisionEnabled", {}).get("value") is True,
          f"floor wall has no CollisionAPI's physics:collisionEnabled: {floor}")
    for name in ("ceiling", "left_wall", "right_wall", "front_wall", "back_wall"):
        check(walls + name in prims, f"no {name} among the collision walls")


def main():
    binary, scenes, shared = sys.argv[1:4]
    scene = os.path.join(scenes, "examples.yaml")
    if not os.path.isdir(os.path.join(shared, "isaacsim", "replicator", "behavior")):
        print(f"skipped: Isaac Sim's behavior scripts are not at {shared}")
        return 77
    with tempfile.TemporaryDirectory() as tmp:
        p = run(binary, scene, os.path.join(tmp, "a"))
        check(p.returncode == 0, f"examples.yaml exited {p.returncode}: {p.stderr[-800:]}")
        for line in ("[ExampleCustomEventBehavior][/World/Box] setup()",
                     "[ExampleCustomEventBehavior][/World/Box] update()",
                     "[ExampleBehavior][/World/Box] on_play()", "[ExampleBehavior][/World/Box] on_stop()"):
            check(line in p.stderr, f"the scripts did not print {line!r}:\n{p.stderr[-800:]}")
        check(p.stderr.count("[ExampleBehavior][/World/Box] Applying behavior to prim /World/Box") == 3,
              "the example behavior did not apply once per frame (3 frames)")
        # A reply that does not match what the pre-roll waits for: the run fails, naming the event.
        with open(scene) as f:
            text = f.read()
        wrong = os.path.join(os.path.dirname(scene), ".examples_wrong_reply.yaml")
        try:
            with open(wrong, "w") as f:
                f.write(text.replace("wait_for: {prim_path: /World/Box, function_name: update}",
                                     "wait_for: {prim_path: /World/Box, function_name: reset}"))
            p = run(binary, wrong, os.path.join(tmp, "b"))
        finally:
            os.remove(wrong)
        check(p.returncode != 0 and "no reply on isaacsim.replicator.behavior.exampleCustomEventBehavior.out" in p.stderr,
              f"a reply the pre-roll does not wait for still passed (exit {p.returncode}): {p.stderr[-400:]}")
        p = run(binary, os.path.join(scenes, "volume_stack.yaml"), os.path.join(tmp, "c"))
        # The setup runs through the layer; the run's first PhysX call is the located 'not provided' error.
        p = run(binary, os.path.join(scenes, "volume_stack.yaml"), os.path.join(tmp, "c"))
        check(p.returncode == 1 and "omni.physx.get_physx_simulation_interface is not provided by sdgbehave's "
              "Isaac Sim layer (used at " in p.stderr and "utils/scene_utils.py:" in p.stderr
              and "docs/isaac-scripts.md" in p.stderr,
              f"volume_stack.yaml: expected the located 'not provided' error, exit 1; exit {p.returncode}: "
              f"{p.stderr[-500:]}")
        check_volume_stack_setup(binary, os.path.join(scenes, "volume_stack.yaml"), tmp)
        # The physics schemas the volume stack randomizer applies, authored and read back by a probe script.
        p = run(binary, os.path.join(scenes, "physics_schemas.yaml"), os.path.join(tmp, "d"))
        check(p.returncode == 0 and "[PhysicsSchemasProbe][/World/Box] physics schemas ok" in p.stderr,
              f"physics_schemas.yaml: exit {p.returncode}: {p.stderr[-800:]}")
    return finish("Isaac's example behaviors: the custom-event replies reach the bus; the example behavior runs")


if __name__ == "__main__":
    sys.exit(main())
