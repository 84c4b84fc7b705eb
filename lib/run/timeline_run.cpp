#include "run/timeline_run.h"

#include <memory>

#include "behavior/runtime.h"
#include "core/log.h"
#include "run/preroll.h"
#include "run/record.h"
#include "run/scene_setup.h"

namespace sdg {

TimelineRunResult runTimeline(LoadedScene& loaded, const TimelineRunOptions& options) {
  Stage& stage = loaded.scene.stage;
  const Stage original = stage;
  RunBehaviorSetup setup;
  BehaviorRuntime runtime(stage, loaded.registry, behaviorContextFor(loaded, options.seed, setup));
  runtime.init();
  runPreroll(loaded.scene.events, runtime);
  if (!options.saveStagePath.empty()) saveStageAfterPreroll(loaded, options.saveStagePath);

  const Stage beforePlay = stage;
  std::unique_ptr<ChangeRecorder> recorder;
  if (!options.recordPath.empty()) {
    recorder = std::make_unique<ChangeRecorder>(options.recordPath, original);
    recorder->recordPreroll(setup.reports, stage);
  }

  TimelineRunResult result;
  result.settle = setup.reports;
  result.behaviors = runtime.behaviorCount();
  runtime.play();
  for (uint64_t frame = 0; frame < options.frames; ++frame) {
    runtime.update();
    if (recorder) recorder->recordFrame(frame, runtime.timeline().time(), stage);
    ++result.frames;
  }
  runtime.stop();
  result.stageRestored = stage == beforePlay;
  if (!result.stageRestored) log::warn("the stage after stop differs from the stage before play");
  if (recorder) {
    recorder->recordStop(stage);
    recorder->close();
  }
  runtime.destroy();
  result.updates = runtime.updateCount();
  return result;
}

}  // namespace sdg
