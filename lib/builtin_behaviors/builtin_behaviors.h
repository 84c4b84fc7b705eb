#pragma once
// The built-in behaviors, listed in one table (builtin_behaviors.cpp).
#include "assets/labelled_mesh.h"
#include "behavior/registry.h"

namespace sdg {

void registerBuiltinBehaviors(BehaviorRegistry& registry);

// Each behavior file provides its spec and factory.
BehaviorSpec locationRandomizerSpec();
std::unique_ptr<Behavior> makeLocationRandomizer();
BehaviorSpec rotationRandomizerSpec();
std::unique_ptr<Behavior> makeRotationRandomizer();
BehaviorSpec lookAtBehaviorSpec();
std::unique_ptr<Behavior> makeLookAtBehavior();
BehaviorSpec lightRandomizerSpec();
std::unique_ptr<Behavior> makeLightRandomizer();
BehaviorSpec textureRandomizerSpec();
std::unique_ptr<Behavior> makeTextureRandomizer();
BehaviorSpec volumeStackRandomizerSpec();
std::unique_ptr<Behavior> makeVolumeStackRandomizer();

// The labelled meshes the built-ins put on the stage during a run (the
// volume stack's assets), read from the stage as loaded.
std::vector<LabelledMesh> meshesSpawnedByBuiltins(const Stage& stage, const AssetResolver& resolver);

}  // namespace sdg
