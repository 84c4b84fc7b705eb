#pragma once
// One USD layer as Sdf models it: a map from paths to specs, each spec a
// type and a set of named fields ("specifier", "typeName", "default",
// "primChildren", ...). The usda parser and the usdc crate reader both fill
// this, the writer reads it, and composition (compose.h) turns a stack of
// layers into composed prims. Field names are USD's own (SdfFieldKeys /
// SdfChildrenKeys), so a crate file's fields map one to one.
//
// Paths are USD path strings: "/" (the pseudo-root), "/World/Cube",
// "/World/Cube.points" (a property), "/World/Cube.material:binding[/Mat]"
// (a relationship target), "/Asset{shadingVariant=red}Mesh" (inside a
// variant), "/World/Cube.points.connect[/Other.out]".
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/source_loc.h"
#include "usd/value.h"

namespace sdg::usd {

// Numbered as crate files number them (SdfSpecType).
enum class SpecType : uint8_t {
  Unknown = 0,
  Attribute = 1,
  Connection = 2,
  Expression = 3,
  Mapper = 4,
  MapperArg = 5,
  Prim = 6,
  PseudoRoot = 7,
  Relationship = 8,
  RelationshipTarget = 9,
  Variant = 10,
  VariantSet = 11,
};

struct Spec {
  SpecType type = SpecType::Unknown;
  std::map<std::string, Value> fields;
  // Where the spec was written: file:line:col for usda; for crate files the
  // file with line 0 (`where` names the spec's index, e.g. "spec 12").
  SourceLoc loc;

  const Value* field(const std::string& name) const {
    auto it = fields.find(name);
    return it == fields.end() ? nullptr : &it->second;
  }
};

// Field keys used across the module (a subset of SdfFieldKeys).
namespace field {
inline constexpr const char* kSpecifier = "specifier";
inline constexpr const char* kTypeName = "typeName";
inline constexpr const char* kDefault = "default";
inline constexpr const char* kTimeSamples = "timeSamples";
inline constexpr const char* kPrimChildren = "primChildren";      // TokenVector, on prims and the pseudo-root
inline constexpr const char* kProperties = "properties";          // TokenVector, on prims
inline constexpr const char* kVariantSetNames = "variantSetNames";  // StringListOp, on prims
inline constexpr const char* kVariantSetChildren = "variantSetChildren";  // TokenVector, on prims
inline constexpr const char* kVariantChildren = "variantChildren";  // TokenVector, on variant sets
inline constexpr const char* kVariantSelection = "variantSelection";  // VariantSelectionMap
inline constexpr const char* kReferences = "references";          // ReferenceListOp
inline constexpr const char* kPayload = "payload";                // PayloadListOp (or one Payload)
inline constexpr const char* kInheritPaths = "inheritPaths";      // PathListOp
inline constexpr const char* kSpecializes = "specializes";        // PathListOp
inline constexpr const char* kSubLayers = "subLayers";            // StringVector
inline constexpr const char* kSubLayerOffsets = "subLayerOffsets";  // LayerOffsetVector
inline constexpr const char* kDefaultPrim = "defaultPrim";        // Token
inline constexpr const char* kUpAxis = "upAxis";                  // Token
inline constexpr const char* kMetersPerUnit = "metersPerUnit";    // Double
inline constexpr const char* kStartTimeCode = "startTimeCode";    // Double
inline constexpr const char* kEndTimeCode = "endTimeCode";
inline constexpr const char* kTimeCodesPerSecond = "timeCodesPerSecond";
inline constexpr const char* kActive = "active";                  // Bool
inline constexpr const char* kInstanceable = "instanceable";      // Bool
inline constexpr const char* kKind = "kind";                      // Token
inline constexpr const char* kApiSchemas = "apiSchemas";          // TokenListOp
inline constexpr const char* kCustom = "custom";                  // Bool, on properties
inline constexpr const char* kVariability = "variability";        // Variability, on properties
inline constexpr const char* kConnectionPaths = "connectionPaths";  // PathListOp, on attributes
inline constexpr const char* kTargetPaths = "targetPaths";        // PathListOp, on relationships
inline constexpr const char* kCustomData = "customData";          // Dictionary
inline constexpr const char* kDocumentation = "documentation";    // String
inline constexpr const char* kComment = "comment";                // String (layer)
inline constexpr const char* kInterpolation = "interpolation";    // Token (primvars)
inline constexpr const char* kElementSize = "elementSize";        // Int (primvars)
inline constexpr const char* kColorSpace = "colorSpace";          // Token (asset attributes)
inline constexpr const char* kPrimOrder = "primOrder";            // TokenVector (`reorder nameChildren`/`rootPrims`)
inline constexpr const char* kPropertyOrder = "propertyOrder";    // TokenVector (`reorder properties`)
inline constexpr const char* kDisplayName = "displayName";        // String
inline constexpr const char* kHidden = "hidden";                  // Bool
inline constexpr const char* kPermission = "permission";          // Permission
inline constexpr const char* kRelocates = "relocates";            // Dictionary source path -> target path (String)
inline constexpr const char* kAssetInfo = "assetInfo";            // Dictionary
inline constexpr const char* kCustomLayerData = "customLayerData";  // Dictionary (layer)
}  // namespace field

// A whole layer. `specs` holds the pseudo-root at "/" (the layer's metadata:
// defaultPrim, upAxis, metersPerUnit, subLayers, ...; its primChildren).
struct Layer {
  std::string identifier;  // the path it was opened by (a package entry: "pkg.usdz[inner.usdc]")
  std::string realPath;    // the file on disk (the package for an entry)
  std::string format;      // "usda" or "usdc"
  std::map<std::string, Spec> specs;
  // Where each subLayers entry was written (usda; empty for crate layers).
  std::vector<SourceLoc> subLayerLocs;

  const Spec* spec(const std::string& path) const {
    auto it = specs.find(path);
    return it == specs.end() ? nullptr : &it->second;
  }
  const Spec& pseudoRoot() const;  // always present after a successful read
};

// Limits every reader enforces so that a hostile file fails cleanly instead
// of exhausting memory or the stack.
struct ReadLimits {
  uint64_t maxFileBytes = uint64_t(4) << 30;        // 4 GiB
  uint64_t maxArrayElements = uint64_t(1) << 28;    // per array value
  uint64_t maxDecompressedBytes = uint64_t(8) << 30;
  uint32_t maxNesting = 256;                        // prim/dictionary/paren nesting
  uint64_t maxSpecs = uint64_t(1) << 26;
  // A compressed .usdz entry inflates to at most this (a stored entry is
  // bounded by the package's own size); refused before anything is
  // allocated when its header says more, and while inflating when it lies.
  // Entries inflated on the way to another (a nested package) share it.
  uint64_t maxInflatedEntryBytes = uint64_t(256) << 20;  // 256 MiB
};

// Errors of the USD module: a message that names the file and the line:col
// (usda) or the section (crate: "TOKENS section", "spec 12", ...).
// scene_io turns these into SceneError (exit 2). Errors made by usdErrorAt
// (the usda reader, layer_io, composition) start their what() with
// loc.str() ("a.usda:12:5: expected ..."); loc() gives the parts.
class UsdError : public std::runtime_error {
 public:
  UsdError(SourceLoc loc, const std::string& message)
      : std::runtime_error(message), loc_(std::move(loc)) {}
  const SourceLoc& loc() const { return loc_; }

 private:
  SourceLoc loc_;
};

// A variant choice given to composition (ComposeOptions::variantOverrides)
// that the stage cannot take: the prim, or its set, or the variant is not
// there. Carries the choice, so that a caller reports it where it was made.
class VariantOverrideError : public UsdError {
 public:
  VariantOverrideError(std::string prim, std::string set, const std::string& message)
      : UsdError(SourceLoc(), message), prim_(std::move(prim)), set_(std::move(set)) {}
  const std::string& prim() const { return prim_; }
  const std::string& set() const { return set_; }

 private:
  std::string prim_, set_;
};

// A UsdError whose message starts with the location ("file:line:col: message").
inline UsdError usdErrorAt(const SourceLoc& loc, const std::string& message) {
  return UsdError(loc, loc.known() ? loc.str() + ": " + message : message);
}

}  // namespace sdg::usd
