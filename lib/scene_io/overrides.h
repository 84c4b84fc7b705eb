#pragma once
// `--set TARGET=VALUE` overrides, applied after loading and typed by what
// they hit:
//   --set /Root/Target.exposedVar:locationRandomizer:interval=5
//   --set /Root/Camera.focalLength=35      --set /Root/Box.translate=[0,0,1]
//   --set render.resolution=[640,480]     --set writer.rgb=true
//   --set /World/Chair.variants:color=red (a USD variant selection)
// VALUE is YAML (a flow list, a number, a string). Problems are located as
// "--set[N]:1:COLUMN" where COLUMN points into the Nth override.
#include <span>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "scene_io/scene.h"
#include "stage/behavior_spec.h"

namespace sdg {

// Every override but variant selections (below), which composition applies.
void applyOverrides(std::span<const std::string> overrides, const BehaviorCatalog& catalog, Scene& scene,
                    Diagnostics& diag);

// `--set /World/Chair.variants:color=red`: a USD variant selection. It is
// applied before composition (a USD stage's, or a USD file a YAML scene
// mounts with reference:), so it is taken out of the overrides first; the
// composer reports a prim, set or variant that does not exist.
struct VariantSelection {
  std::string prim, set, variant;
  SourceLoc loc;  // the override, "--set[N]:1:1"
};
inline constexpr const char* kVariantsPrefix = "variants:";
std::vector<VariantSelection> variantSelections(std::span<const std::string> overrides, Diagnostics& diag);

}  // namespace sdg
