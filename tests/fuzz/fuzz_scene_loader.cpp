// libFuzzer harness: any bytes as a scene file. The loader must answer with
// a scene or a SceneError, never crash, hang or exhaust memory.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "builtin_behaviors/builtin_behaviors.h"
#include "core/diagnostics.h"
#include "scene_io/scene_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const sdg::BehaviorRegistry registry = sdg::builtinRegistry();
  try {
    sdg::SceneDocument doc =
        sdg::sceneDocumentFromText(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.yaml");
    sdg::Scene scene = sdg::buildScene(doc, registry.catalog());
    (void)scene;
  } catch (const sdg::SceneError&) {
  } catch (const sdg::RunError&) {
  }
  return 0;
}
