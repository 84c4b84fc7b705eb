#pragma once
// Human-readable description of a loaded scene: settings, then the prim tree
// with types, transforms, labels, attributes and behaviors.
#include <string>

#include "scene_io/scene.h"

namespace sdg {

// Where a value comes from, for people: "scene.yaml:12:5", with ", referenced
// from ..." for values of smart assets, "--set[1]:1:19", or "default".
std::string valueOrigin(const SourceLoc& loc);

std::string inspectScene(const Scene& scene);

}  // namespace sdg
