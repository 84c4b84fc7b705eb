#pragma once
// sdgbehave's run settings inside a USD layer. export-usd writes what has no
// USD home (render, capture, physics, run, the writers and the pre-roll
// events) into the root layer's customLayerData["sdgbehave"]; importing
// such a layer reads them back through the YAML loader's section readers,
// so they get the same checks and the stage runs as the scene it came from.
#include "core/diagnostics.h"
#include "scene_io/scene.h"
#include "usd/compose.h"

namespace sdg {

// True when the root layer holds customLayerData["sdgbehave"] (an exported
// scene): its sections are read into `scene` (problems to `diag`, located
// at the root layer). False, with `scene` untouched, otherwise.
bool importUsdSceneSettings(const usd::ComposedStage& composed, Scene& scene, Diagnostics& diag);

}  // namespace sdg
