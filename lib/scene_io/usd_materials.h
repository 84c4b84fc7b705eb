#pragma once
// Helpers of the USD material mapping (usd_materials.cpp) that the per-prim
// labels need: whether a Material prim maps onto a stage Material at all
// (bindings to one that does not are left out, so the prim keeps its
// primvars:displayColor, as the fallback promises).
#include "usd/compose.h"

namespace sdg {

// True when `material` has a surface the mapping reads: Isaac's MDL OmniPBR
// on outputs:mdl:surface, or a UsdPreviewSurface on outputs:surface.
bool usdMaterialIsSupported(const usd::ComposedStage& composed, const usd::ComposedPrim& material);

}  // namespace sdg
