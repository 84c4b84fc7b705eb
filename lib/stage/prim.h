#pragma once
// One node of the stage: a path, a type, ordered children, typed attributes,
// transform ops, semantic labels, a material binding and attached behaviors.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/source_loc.h"
#include "stage/prim_types.h"
#include "stage/value.h"
#include "stage/xform.h"

namespace sdg {

struct Attribute {
  Value value;
  bool custom = false;  // authored by the user or a behavior, not in the type's schema
  std::string doc;
  SourceLoc loc;        // where it was authored; not part of the stage's state

  // doc and loc describe the attribute; only value and custom are state.
  bool operator==(const Attribute& o) const { return value == o.value && custom == o.custom; }
};

struct MaterialBinding {
  std::string path;
  // USD binding strengths; the texture randomizer binds strongerThanDescendants.
  std::string strength = "weakerThanDescendants";
  bool operator==(const MaterialBinding&) const = default;
};

using AttributeMap = std::map<std::string, Attribute, std::less<>>;
// taxonomy ("class") -> labels, in authored order
using SemanticLabels = std::map<std::string, std::vector<std::string>, std::less<>>;

class Prim {
 public:
  Prim(std::string path, PrimType type, Prim* parent);

  const std::string& path() const { return path_; }
  std::string_view name() const;
  PrimType type() const { return type_; }
  const PrimTypeInfo& typeInfo() const { return primTypeInfo(type_); }
  bool isPseudoRoot() const { return parent_ == nullptr; }
  Prim* parent() const { return parent_; }
  const std::vector<Prim*>& children() const { return children_; }

  // --- attributes ---------------------------------------------------------
  const AttributeMap& attributes() const { return attributes_; }
  const Attribute* findAttribute(std::string_view name) const;
  Attribute* findAttribute(std::string_view name);
  // Creates or replaces an authored attribute.
  Attribute& setAttribute(const std::string& name, Value value, bool custom = false);
  bool removeAttribute(std::string_view name);
  // The authored value, else the schema fallback, else nullptr.
  const Value* value(std::string_view name) const;
  // Typed reads of schema attributes (authored or fallback). The caller names
  // a schema attribute of the right type; anything else is a programming error.
  double getDouble(std::string_view name) const;
  float getFloat(std::string_view name) const;
  bool getBool(std::string_view name) const;
  const std::string& getString(std::string_view name) const;

  // --- transform, labels, material, behaviors ------------------------------
  std::vector<XformOp>& xformOps() { return xformOps_; }
  const std::vector<XformOp>& xformOps() const { return xformOps_; }
  XformOp* findXformOp(std::string_view attributeName);
  Matrix4d localMatrix() const { return sdg::localMatrix(xformOps_); }

  SemanticLabels& semantics() { return semantics_; }
  const SemanticLabels& semantics() const { return semantics_; }
  std::optional<MaterialBinding>& material() { return material_; }
  const std::optional<MaterialBinding>& material() const { return material_; }
  // Names of attached behaviors, in the order the scene lists them.
  std::vector<std::string>& behaviors() { return behaviors_; }
  const std::vector<std::string>& behaviors() const { return behaviors_; }
  std::map<std::string, std::string, std::less<>>& metadata() { return metadata_; }
  const std::map<std::string, std::string, std::less<>>& metadata() const { return metadata_; }

  SourceLoc& loc() { return loc_; }
  const SourceLoc& loc() const { return loc_; }

  // Same type, attributes, ops, labels, binding, behaviors and metadata
  // (children are compared by the stage).
  bool sameContent(const Prim& other) const;

 private:
  friend class Stage;
  std::string path_;
  PrimType type_;
  Prim* parent_;
  std::vector<Prim*> children_;
  AttributeMap attributes_;
  std::vector<XformOp> xformOps_;
  SemanticLabels semantics_;
  std::optional<MaterialBinding> material_;
  std::vector<std::string> behaviors_;
  std::map<std::string, std::string, std::less<>> metadata_;
  SourceLoc loc_;
};

}  // namespace sdg
