#pragma once
// What a scripted behavior changed, so that sdgbehave can undo it without
// code in the script: before the first write to a field of a prim (an
// attribute, the xform op list, the semantic labels, the material binding)
// the field's value is saved; prims the script creates are remembered.
// undo() puts every saved field back, newest first, and removes the created
// prims, so the stage equals what it was when the journal started.
//
// Writes to prims the script created are not saved: those prims go.
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "stage/stage.h"

namespace sdg::scripting {

class StageJournal {
 public:
  void beforeAttributeWrite(const Prim& prim, const std::string& name);
  void beforeXformWrite(const Prim& prim);
  void beforeSemanticsWrite(const Prim& prim);
  void beforeMaterialWrite(const Prim& prim);
  void created(const Prim& prim);
  bool createdHere(const Prim& prim) const;
  // The prim is about to be removed by the script that created it.
  void forget(const Prim& prim);

  // Restores every saved field, removes every created prim (newest first;
  // the scopes created to hold them are created prims too), and forgets.
  void undo(Stage& stage);
  bool empty() const { return records_.empty() && createdPaths_.empty(); }

 private:
  enum class Field { Attribute, XformOps, Semantics, Material };
  struct Saved {
    Field field;
    std::string attribute;              // for Field::Attribute
    std::optional<Attribute> value;     // nullopt: the attribute was not authored
    std::vector<XformOp> ops;
    SemanticLabels semantics;
    std::optional<MaterialBinding> material;
  };
  struct PrimRecord {
    std::string path;
    std::vector<Saved> saved;
  };
  // The record for `prim` (created on first use); nullptr for prims created here.
  PrimRecord* recordFor(const Prim& prim);
  static bool has(const PrimRecord& record, Field field, const std::string& attribute = {});

  std::unordered_map<const Prim*, size_t> index_;  // prim -> records_ slot; SIZE_MAX = created here
  std::vector<PrimRecord> records_;                // in first-write order
  std::vector<std::string> createdPaths_;
};

}  // namespace sdg::scripting
