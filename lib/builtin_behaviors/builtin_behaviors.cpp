#include "builtin_behaviors/builtin_behaviors.h"

namespace sdg {

void registerBuiltinBehaviors(BehaviorRegistry& registry) {
  struct Row {
    BehaviorSpec (*spec)();
    std::unique_ptr<Behavior> (*make)();
  };
  // The one list of built-ins: add a row here when adding a behavior.
  static constexpr Row kBuiltins[] = {
      {locationRandomizerSpec, makeLocationRandomizer},
      {rotationRandomizerSpec, makeRotationRandomizer},
      {lookAtBehaviorSpec, makeLookAtBehavior},
      {lightRandomizerSpec, makeLightRandomizer},
      {textureRandomizerSpec, makeTextureRandomizer},
      {volumeStackRandomizerSpec, makeVolumeStackRandomizer},
  };
  for (const Row& row : kBuiltins) registry.add(row.spec(), row.make);
}

BehaviorRegistry builtinRegistry() {
  BehaviorRegistry registry;
  registerBuiltinBehaviors(registry);
  return registry;
}

}  // namespace sdg
