// libFuzzer harness: `--set` arguments (one per line of the input) applied
// to a small scene with every kind of target: prim attributes of each value
// type, xform ops, exposed variables and run settings.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "builtin_behaviors/builtin_behaviors.h"
#include "core/diagnostics.h"
#include "scene_io/scene_loader.h"

namespace {
constexpr const char* kScene = R"(version: 1
render: {resolution: [64, 64]}
writer: {type: BasicWriter, rgb: true}
prims:
  /World: {}
  /World/Box:
    type: Cube
    translate: [0, 0, 1]
    rotateXYZ: [0, 0, 0]
    semantics: {class: box}
    behaviors:
      locationRandomizer: {interval: 2}
      volumeStackRandomizer: {}
  /World/Light: {type: SphereLight, inputs:intensity: 1000}
  /World/Cam: {type: Camera, translate: [0, -5, 1], orient: [1, 0, 0, 0]}
)";
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const sdg::BehaviorRegistry registry = sdg::builtinRegistry();
  static const sdg::SceneDocument doc = sdg::sceneDocumentFromText(kScene, "fuzz.yaml");
  std::vector<std::string> overrides;
  std::string current;
  for (size_t i = 0; i < size && overrides.size() < 16; ++i) {
    if (data[i] == '\n') {
      overrides.push_back(current);
      current.clear();
    } else {
      current += char(data[i]);
    }
  }
  overrides.push_back(current);
  try {
    sdg::Scene scene = sdg::buildScene(doc, registry.catalog(), overrides);
    (void)scene;
  } catch (const sdg::SceneError&) {
  } catch (const sdg::RunError&) {
  }
  return 0;
}
