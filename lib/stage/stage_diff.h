#pragma once
// What changed between two states of a stage, attribute by attribute:
// authored attributes, xform ops (by op name), material bindings and prims
// created or removed. Used by `run --record` and by the reset tests.
#include <optional>
#include <string>
#include <vector>

#include "stage/stage.h"

namespace sdg {

struct StageChange {
  std::string prim;
  std::string attribute;       // attribute or op name; "material:binding"; "prim" for creation/removal
  std::optional<Value> value;  // the new value; nullopt when removed
};

std::vector<StageChange> diffStages(const Stage& before, const Stage& after);

}  // namespace sdg
