#pragma once
// The `prims:` section: a mapping from absolute prim path to prim entry.
#include "core/diagnostics.h"
#include "scene_io/raw_node.h"
#include "stage/behavior_spec.h"
#include "stage/stage.h"

namespace sdg {

// Keys of a prim entry besides attributes and xform ops.
inline constexpr std::string_view kPrimStructuralKeys[] = {"type",      "semantics", "material",
                                                           "behaviors", "attributes", "metadata"};

// Declares and fills every prim. Parents are never created implicitly: a
// prim whose parent is not listed is an error (it catches path typos).
void readPrims(const RawNode& prims, const BehaviorCatalog& catalog, Stage& stage, Diagnostics& diag);

// True for "name" or "ns:name:more" with identifier components.
bool isValidAttributeName(std::string_view name);

}  // namespace sdg
