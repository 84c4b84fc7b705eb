#pragma once
// Composition tests compose in-memory layers: a map from identifier to
// usda text, read through the LayerReader callback.
#include <map>
#include <string>

#include "usd/compose.h"
#include "usd/layer_io.h"

namespace sdg::usd::test {

struct MemoryLayers {
  std::map<std::string, std::string> texts;
  mutable std::vector<std::string> reads;  // identifiers in the order they were read

  LayerReader reader() const {
    return [this](const std::string& identifier) {
      reads.push_back(identifier);
      auto it = texts.find(identifier);
      if (it == texts.end()) throw usdErrorAt(SourceLoc(identifier, 0, 0), "no such layer");
      return readUsdaLayer(it->second, identifier);
    };
  }
  ComposedStage compose(const std::string& root, const ComposeOptions& options = {}) const {
    return composeStage(root, reader(), options);
  }
};

// The composed value of an attribute ("/A.size"), failing the test when absent.
inline const Value& valueAt(const ComposedStage& stage, const std::string& primPath, const std::string& name) {
  const ComposedPrim* prim = stage.prim(primPath);
  if (!prim) throw std::runtime_error("no prim " + primPath);
  const ComposedProperty* prop = prim->property(name);
  if (!prop) throw std::runtime_error("no property " + primPath + "." + name);
  return prop->value;
}

inline double numberAt(const ComposedStage& stage, const std::string& primPath, const std::string& name) {
  return valueAt(stage, primPath, name).asDouble();
}

// The message of composing `root` (empty when it composes).
inline std::string composeError(const MemoryLayers& layers, const std::string& root, const ComposeOptions& options = {}) {
  try {
    layers.compose(root, options);
  } catch (const UsdError& e) {
    return e.what();
  }
  return "";
}

}  // namespace sdg::usd::test
