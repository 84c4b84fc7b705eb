#pragma once
// The `prims:` section: a mapping from absolute prim path to prim entry.
#include "core/diagnostics.h"
#include "scene_io/raw_node.h"
#include "stage/behavior_spec.h"
#include "stage/stage.h"

namespace sdg {

// Keys of a prim entry besides attributes and xform ops.
// `omni:scripting:scripts` lists behavior script files as Isaac Sim attaches
// them (scene_io/attached_scripts.h).
inline constexpr std::string_view kScriptsKey = "omni:scripting:scripts";
inline constexpr std::string_view kPrimStructuralKeys[] = {"type",     "semantics", "material",  "behaviors", "attributes",
                                                           "metadata", "reference", kScriptsKey};

class AssetLibrary;
// Where `reference:` entries are mounted from: the load's asset library and
// the folder of the file being read (references are relative to it).
struct PrimReferences {
  AssetLibrary* library = nullptr;
  std::string fromDir;
};

// Declares and fills every prim. Parents are never created implicitly: a
// prim whose parent is neither listed nor mounted from a referenced asset is
// an error (it catches path typos). A prim with `reference:` gets the
// asset's prim tree; entries on it and below it override the asset's values.
void readPrims(const RawNode& prims, const BehaviorCatalog& catalog, Stage& stage, Diagnostics& diag,
               const PrimReferences& references = {});

// True for "name" or "ns:name:more" with identifier components.
bool isValidAttributeName(std::string_view name);

}  // namespace sdg
