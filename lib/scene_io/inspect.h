#pragma once
// Human-readable description of a loaded scene: settings, then the prim tree
// with types, transforms, labels, attributes and behaviors.
#include <string>

#include "scene_io/scene.h"

namespace sdg {

std::string inspectScene(const Scene& scene);

}  // namespace sdg
