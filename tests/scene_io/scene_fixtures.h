#pragma once
// Helpers for loader tests: build scenes from inline YAML.
#include <catch2/catch.hpp>

#include <span>
#include <string>

#include "builtin_behaviors/builtin_behaviors.h"
#include "scene_io/scene_loader.h"

namespace sdg::test {

// The behaviors the shipped scenes may use: the built-ins.
inline BehaviorCatalog testCatalog() { return builtinRegistry().catalog(); }

inline Scene loadText(const std::string& yaml, const BehaviorCatalog& catalog = {},
                      std::span<const std::string> overrides = {}) {
  return buildScene(sceneDocumentFromText(yaml, "t.yaml"), catalog, overrides);
}

// All messages of the SceneError the text raises, one per line ("" if none).
inline std::string errorsOf(const std::string& yaml, const BehaviorCatalog& catalog = {},
                            std::span<const std::string> overrides = {}) {
  try {
    loadText(yaml, catalog, overrides);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace sdg::test
