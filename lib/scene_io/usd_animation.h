#pragma once
// A USD stage's time samples as the stage's own animation
// (stage/stage_animation.h). Composition keeps each attribute's samples
// with the layer offset onto the stage's time (usd::AttributeSamples); here
// a prim whose samples vary is composed again at each of their time codes
// and mapped by the import's own code (the sampler: transform ops, schema
// attributes, mesh geometry), so a sampled value becomes exactly the stage
// value the import would give at that time. Every attribute or op whose
// stage value changes becomes an animated value.
#include <functional>

#include "stage/prim.h"
#include "stage/stage_animation.h"
#include "usd/compose.h"

namespace sdg {

// Some property of `prim` has time samples that are not all alike.
bool usdPrimIsAnimated(const usd::ComposedPrim& prim);

// How a composed stage's time codes follow the timeline: from the time
// composition resolved at (startTimeCode), at timeCodesPerSecond (else
// framesPerSecond, else USD's fallback, 24).
AnimationClock usdAnimationClock(const usd::ComposedStage& composed);
// The stage's rate where the layer authors one (timeCodesPerSecond, else framesPerSecond).
std::optional<double> usdAuthoredRate(const usd::ComposedStage& composed);

// `prim` with every varying property's value taken at stage time code `timeCode`.
usd::ComposedPrim usdPrimAt(const usd::ComposedPrim& prim, double timeCode);

// Fills `into` (a scratch prim of the imported prim's path and type) with
// what the import gives for a composed prim: its transform ops, schema
// attributes and geometry.
using UsdPrimSampler = std::function<void(const usd::ComposedPrim& at, Prim& into)>;

// Samples `prim` at every time code of its varying properties through
// `sample` and adds to `animation` each attribute and op of `imported`
// (the prim as the import defined it) whose value is not the same at all of them.
void recordUsdPrimAnimation(const usd::ComposedPrim& prim, const Prim& imported, const AnimationClock& clock,
                            const UsdPrimSampler& sample, StageAnimation& animation);

}  // namespace sdg
