#include "usd/layer.h"

namespace sdg::usd {

const Spec& Layer::pseudoRoot() const {
  auto it = specs.find("/");
  if (it == specs.end())
    throw UsdError(SourceLoc(identifier, 0, 0), identifier + ": the layer has no pseudo-root spec");
  return it->second;
}

}  // namespace sdg::usd
