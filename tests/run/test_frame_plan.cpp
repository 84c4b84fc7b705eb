// The frame plan, decided in one place for `run` and the studio: frames per
// iteration from --frames, else capture.frames_per_iteration, else
// capture.frames; iterations; the shard from flags or the scheduler.
#include <catch2/catch.hpp>

#include "core/diagnostics.h"
#include "run/frame_plan.h"
#include "scene_io/scene.h"

using namespace sdg;

namespace {

Scene sceneWith(uint32_t frames, uint32_t perIteration, uint32_t iterations) {
  Scene scene;
  scene.capture.set("frames", Value::makeUInt(frames));
  scene.capture.set("frames_per_iteration", Value::makeUInt(perIteration));
  scene.capture.set("iterations", Value::makeUInt(iterations));
  return scene;
}

}  // namespace

TEST_CASE("frame plan: the scene's frames, frames_per_iteration and iterations, then the flags", "[run]") {
  FramePlan plan = framePlanFor(sceneWith(6, 0, 1), {}, noEnvironment);
  CHECK(plan.framesPerIteration == 6);
  CHECK(plan.total() == 6);
  plan = framePlanFor(sceneWith(6, 2, 3), {}, noEnvironment);
  CHECK(plan.framesPerIteration == 2);
  CHECK(plan.iterations == 3);
  CHECK(plan.total() == 6);
  FramePlanFlags flags;
  flags.frames = 5;
  flags.iterations = 4;
  plan = framePlanFor(sceneWith(6, 2, 3), flags, noEnvironment);
  CHECK(plan.framesPerIteration == 5);
  CHECK(plan.iterations == 4);
  flags.iterations = uint64_t(1) << 49;
  CHECK_THROWS_AS(framePlanFor(sceneWith(6, 2, 3), flags, noEnvironment), SceneError);
}

TEST_CASE("frame plan: the shard from the flags, else the scheduler, unless it is ignored", "[run]") {
  const Scene scene = sceneWith(10, 0, 1);
  auto slurm = [](const char* name) -> std::optional<std::string> {
    const std::string n = name;
    if (n == "SLURM_ARRAY_TASK_ID") return "1";
    if (n == "SLURM_ARRAY_TASK_MIN") return "0";
    if (n == "SLURM_ARRAY_TASK_MAX") return "1";
    if (n == "SLURM_ARRAY_TASK_STEP") return "1";
    if (n == "SLURM_ARRAY_TASK_COUNT") return "2";
    return std::nullopt;
  };
  FramePlan plan = framePlanFor(scene, {}, slurm);
  CHECK(plan.shard.index == 1);
  CHECK(plan.shard.count == 2);
  CHECK(plan.ownedBegin() == 5);
  CHECK_FALSE(framePlanFor(scene, {}, noEnvironment).shard.sharded());
  FramePlanFlags flags;
  flags.shard = "0/4";
  CHECK(framePlanFor(scene, flags, slurm).shard.count == 4);
  flags.shardIndex = 1;
  CHECK_THROWS_AS(framePlanFor(scene, flags, noEnvironment), SceneError);
}
