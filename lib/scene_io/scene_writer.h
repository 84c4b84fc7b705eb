#pragma once
// Scene -> YAML. Loading what this writes gives an equal scene (the
// round-trip tests check it for every scene in scenes/). Only authored
// values and options that differ from their defaults are written.
#include <string>

#include "scene_io/scene.h"
#include "stage/behavior_spec.h"

namespace sdg {

// `schemaRef`, when not empty, becomes the yaml-language-server comment.
std::string writeSceneYaml(const Scene& scene, const BehaviorCatalog& catalog, const std::string& schemaRef = "");

}  // namespace sdg
