#include "run/timeline_run.h"

#include <memory>

#include "behavior/runtime.h"
#include "core/log.h"
#include "run/preroll.h"
#include "run/record.h"

namespace sdg {

TimelineRunResult runTimeline(LoadedScene& loaded, const TimelineRunOptions& options) {
  Stage& stage = loaded.scene.stage;
  BehaviorContext context;
  context.assets = &loaded.assets;
  context.runSeed = options.seed;
  BehaviorRuntime runtime(stage, loaded.registry, context);
  runtime.init();
  runPreroll(loaded.scene.events, runtime);

  const Stage beforePlay = stage;
  std::unique_ptr<ChangeRecorder> recorder;
  if (!options.recordPath.empty()) recorder = std::make_unique<ChangeRecorder>(options.recordPath, beforePlay);

  TimelineRunResult result;
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
