#!/usr/bin/python3
"""Isaac's example_behavior.py and example_custom_event_behavior.py (read in place from
<repo>/../shared/isaac-behaviors) run unchanged: the pre-roll publishes the custom-event behavior's `.in`
event on sdgbehave's bus and waits for the `.out` reply the script dispatches through
carb.eventdispatcher, matched on its payload (a reply that does not match fails the run, so the replies
are really on the bus); the example behavior's hooks run every frame (scripts print to stderr). The physics schemas
volume_stack_randomizer.py authors are checked by tests/data/isaac_scripts/physics_schemas_probe.py (its
stacking: check_isaac_volume_stack.py).

usage: check_isaac_examples.py SDGBEHAVE SCENE_DIR SHARED_DIR"""
import os
import subprocess
import sys
import tempfile

from checklib import check, finish


def run(binary, scene, out):
    return subprocess.run([binary, "run", scene, "--out", out, "--no-render"], capture_output=True, text=True,
                          timeout=120)


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
        # The physics schemas the volume stack randomizer applies, authored and read back by a probe script.
        p = run(binary, os.path.join(scenes, "physics_schemas.yaml"), os.path.join(tmp, "d"))
        check(p.returncode == 0 and "[PhysicsSchemasProbe][/World/Box] physics schemas ok" in p.stderr,
              f"physics_schemas.yaml: exit {p.returncode}: {p.stderr[-800:]}")
    return finish("Isaac's example behaviors: the custom-event replies reach the bus; the example behavior runs")


if __name__ == "__main__":
    sys.exit(main())
