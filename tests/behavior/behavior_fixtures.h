#pragma once
// Helpers for behavior tests: a scene from inline YAML with the built-in
// behaviors, and a runtime over it.
#include <catch2/catch.hpp>

#include <functional>
#include <memory>
#include <string>

#include "assets/asset_resolver.h"
#include "behavior/runtime.h"
#include "builtin_behaviors/builtin_behaviors.h"
#include "scene_io/scene_loader.h"
#include "stage/stage_diff.h"

namespace sdg::test {

struct BehaviorScene {
  BehaviorRegistry registry = builtinRegistry();
  Scene scene;
  AssetResolver assets{{SDG_SOURCE_DIR "/scenes"}};
  std::unique_ptr<BehaviorRuntime> runtime;

  // `configure` may add to the context (physics settings, run hooks).
  explicit BehaviorScene(const std::string& yaml, int64_t seed = 0,
                         const std::function<void(BehaviorContext&)>& configure = {}) {
    scene = buildScene(sceneDocumentFromText(yaml, "t.yaml"), registry.catalog());
    BehaviorContext context;
    context.assets = &assets;
    context.runSeed = seed;
    if (configure) configure(context);
    runtime = std::make_unique<BehaviorRuntime>(scene.stage, registry, context);
    runtime->init();
  }
  Stage& stage() { return scene.stage; }
  Prim& prim(const std::string& path) {
    Prim* p = scene.stage.find(path);
    REQUIRE(p);
    return *p;
  }
  Vec3d translate(const std::string& path) { return prim(path).findXformOp("xformOp:translate")->value.get<Vec3d>(); }
};

}  // namespace sdg::test
