# A Script Editor program written the way Isaac Sim's documentation shows:
# it builds a stage with Kit commands, labels a prim, attaches three of
# Isaac's behaviors and captures rgb, semantic segmentation and tight boxes
# with step_async. `sdgbehave exec` runs it unchanged (tests/python/check_exec.py).
import asyncio
import inspect
import os

import omni.kit.app
import omni.kit.commands
import omni.replicator.core as rep
import omni.timeline
import omni.usd
from isaacsim.core.utils.semantics import add_update_semantics
from isaacsim.replicator.behavior.behaviors import LightRandomizer, LocationRandomizer, RotationRandomizer
from isaacsim.replicator.behavior.global_variables import EXPOSED_ATTR_NS
from isaacsim.replicator.behavior.utils.behavior_utils import add_behavior_script_with_parameters_async
from pxr import Gf, Sdf, UsdGeom


async def build_stage_async():
    omni.usd.get_context().new_stage()
    stage = omni.usd.get_context().get_stage()
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.z)
    UsdGeom.SetStageMetersPerUnit(stage, 1.0)
    light = stage.DefinePrim("/World/Light", "SphereLight")
    light.CreateAttribute("inputs:intensity", Sdf.ValueTypeNames.Float).Set(30000.0)
    UsdGeom.XformCommonAPI(light).SetTranslate((0.0, -2.0, 4.0))
    omni.kit.commands.execute("CreateMeshPrimWithDefaultXform", prim_path="/World/Floor", prim_type="Plane")
    stage.GetPrimAtPath("/World/Floor").GetAttribute("xformOp:scale").Set(Gf.Vec3d(10, 10, 1))
    omni.kit.commands.execute("CreateMeshPrimWithDefaultXform", prim_path="/World/Cube", prim_type="Cube")
    omni.kit.commands.execute("MovePrim", path_from="/World/Cube", path_to="/World/Crate")
    crate = stage.GetPrimAtPath("/World/Crate")
    crate.GetAttribute("xformOp:translate").Set(Gf.Vec3d(0, 0, 0.5))
    add_update_semantics(crate, "crate")
    camera = stage.DefinePrim("/World/Camera", "Camera")
    UsdGeom.XformCommonAPI(camera).SetTranslate((0.0, -4.0, 3.0))
    UsdGeom.XformCommonAPI(camera).SetRotate((55.0, 0.0, 0.0))
    return stage, crate, light, camera


async def attach_behaviors_async(crate, light):
    await add_behavior_script_with_parameters_async(crate, inspect.getfile(LocationRandomizer), {
        f"{EXPOSED_ATTR_NS}:{LocationRandomizer.BEHAVIOR_NS}:range:minPosition": Gf.Vec3d(-0.5, -0.5, 0.5),
        f"{EXPOSED_ATTR_NS}:{LocationRandomizer.BEHAVIOR_NS}:range:maxPosition": Gf.Vec3d(0.5, 0.5, 0.5),
    })
    await add_behavior_script_with_parameters_async(crate, inspect.getfile(RotationRandomizer), {})
    await add_behavior_script_with_parameters_async(light, inspect.getfile(LightRandomizer), {
        f"{EXPOSED_ATTR_NS}:{LightRandomizer.BEHAVIOR_NS}:range:intensity": Gf.Vec2f(20000, 40000),
    })


async def capture_async(camera, frames):
    product = rep.create.render_product(str(camera.GetPath()), (128, 96))
    writer = rep.writers.get("BasicWriter")
    writer.initialize(output_dir=os.path.join(os.getcwd(), "_out_driver"), rgb=True,
                      semantic_segmentation=True, bounding_box_2d_tight=True)
    writer.attach(product)
    rep.orchestrator.set_capture_on_play(False)
    timeline = omni.timeline.get_timeline_interface()
    timeline.play()
    for _ in range(frames):
        await omni.kit.app.get_app().next_update_async()
        await rep.orchestrator.step_async(delta_time=0.0, pause_timeline=False)
    timeline.stop()
    writer.detach()
    product.destroy()
    await rep.orchestrator.wait_until_complete_async()


async def main_async():
    stage, crate, light, camera = await build_stage_async()
    await attach_behaviors_async(crate, light)
    await capture_async(camera, 4)


rep.set_global_seed(7)
asyncio.ensure_future(main_async())
