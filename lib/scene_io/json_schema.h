#pragma once
// JSON Schema (draft-07) of the scene format, generated from the same tables
// the loader reads: prim types, option tables and behavior specs. The
// committed schemas/scene.schema.json must equal this output (a test).
#include <string>

#include "stage/behavior_spec.h"

namespace sdg {

std::string sceneJsonSchema(const BehaviorCatalog& catalog);

}  // namespace sdg
