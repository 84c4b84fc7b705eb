#pragma once
// Where behaviors create prims (/Behaviors) and the stage helpers they share
// to name, create and tidy them there: built-ins and scripts alike.
#include <string>

#include "stage/stage.h"

namespace sdg {

inline constexpr const char* kBehaviorsScope = "/Behaviors";

// `path` when free, else path_01, path_02, ... (the first free one).
std::string nextFreePath(const Stage& stage, const std::string& path);
// Defines `path` as a Scope, and any missing ancestors too.
Prim& ensureScope(Stage& stage, const std::string& path);
// Removes Scope prims left without children, post-order, from `root` down
// (root included).
void removeEmptyScopes(Stage& stage, const std::string& root);

}  // namespace sdg
