#pragma once
// Small builders for behavior specs and the checks they share.
#include <string>

#include "core/diagnostics.h"
#include "stage/behavior_spec.h"

namespace sdg::behaviors {

AttributeSpec variable(std::string name, Value fallback, std::string doc);
AttributeSpec primPathVariable(std::string name, std::string doc);
// An asset, asset[] or comma-separated string variable naming files of `kind`.
AttributeSpec fileVariable(std::string name, Value fallback, FileKind kind, std::string doc);
// The variables every timeline randomizer shares.
AttributeSpec includeChildrenVariable();
AttributeSpec intervalVariable();
AttributeSpec seedVariable();

// Reports when a component of `minName` exceeds the same component of
// `maxName` (vector3d, color3f, or the two halves of one float2 when
// maxName is empty), naming both attributes.
void checkRange(const Prim& prim, std::string_view behavior, const std::string& minName, const std::string& maxName,
                Diagnostics& diag);

}  // namespace sdg::behaviors
