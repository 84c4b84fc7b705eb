#pragma once
// `--set TARGET=VALUE` overrides, applied after loading and typed by what
// they hit:
//   --set /Root/Target.exposedVar:locationRandomizer:interval=5
//   --set /Root/Camera.focalLength=35      --set /Root/Box.translate=[0,0,1]
//   --set render.resolution=[640,480]     --set writer.rgb=true
// VALUE is YAML (a flow list, a number, a string). Problems are located as
// "--set[N]:1:COLUMN" where COLUMN points into the Nth override.
#include <span>
#include <string>

#include "core/diagnostics.h"
#include "scene_io/scene.h"
#include "stage/behavior_spec.h"

namespace sdg {

void applyOverrides(std::span<const std::string> overrides, const BehaviorCatalog& catalog, Scene& scene,
                    Diagnostics& diag);

}  // namespace sdg
