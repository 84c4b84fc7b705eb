# Attaches tests/data/exec/user_behavior.py (copied beside this program by
# the test) to a cube and records its height after each update.
import asyncio
import json
import os

import omni.kit.app
import omni.kit.commands
import omni.timeline
import omni.usd
from isaacsim.replicator.behavior.utils.behavior_utils import add_behavior_script_with_parameters_async


async def main():
    omni.usd.get_context().new_stage()
    stage = omni.usd.get_context().get_stage()
    omni.kit.commands.execute("CreateMeshPrimWithDefaultXform", prim_path="/World/Cube", prim_type="Cube")
    cube = stage.GetPrimAtPath("/World/Cube")
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "user_behavior.py")
    await add_behavior_script_with_parameters_async(cube, script, {"exposedVar:lift:step": 0.5})
    omni.timeline.get_timeline_interface().play()
    heights = []
    for _ in range(3):
        await omni.kit.app.get_app().next_update_async()
        heights.append(cube.GetAttribute("xformOp:translate").Get()[2])
    omni.timeline.get_timeline_interface().stop()
    with open("heights.json", "w") as f:
        json.dump(heights, f)


asyncio.ensure_future(main())
