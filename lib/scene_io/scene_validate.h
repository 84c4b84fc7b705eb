#pragma once
// Checks that need the whole scene: references between prims, cameras,
// sizes. Runs after the --set overrides, so overridden values are checked too.
#include "core/diagnostics.h"
#include "scene_io/scene.h"
#include "stage/behavior_spec.h"

namespace sdg {

void validateScene(const Scene& scene, const BehaviorCatalog& catalog, Diagnostics& diag);

}  // namespace sdg
