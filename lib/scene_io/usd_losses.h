#pragma once
// What a USD stage has that the mapping onto sdgbehave's stage does not
// carry over, counted by kind: the import notes every place, and a run,
// `validate` and `inspect` print one warning per kind of loss with its
// count and the first place it was met (docs/usd.md "What is dropped").
#include <string>
#include <vector>

#include "core/dropped.h"

namespace sdg {

enum class UsdLossKind {
  PrimType,         // a prim type the stage has no counterpart for (imported as a group)
  AppliedSchema,    // an applied API schema that changes appearance and is not read
  MaterialNetwork,  // a material whose surface is neither UsdPreviewSurface nor OmniPBR
  MaterialInput,    // an input of a read material that is not carried over
  Binding,          // a material binding the stage cannot express
  Composition,      // a composition feature USD would apply and lib/usd does not
  Attribute,        // an attribute of a mapped prim that the stage does not read
};

// "prim_type", "applied_schema", ... (the JSON log's `dropped.kind`).
const char* usdLossKindName(UsdLossKind kind);

class UsdLosses {
 public:
  // One more place that loses `what`; the first place is kept, with the
  // prim (or layer) it belongs to.
  void note(UsdLossKind kind, const std::string& what, const SourceLoc& loc, const std::string& where);
  bool empty() const { return entries_.empty(); }
  void append(const UsdLosses& other);
  // One warning per (kind, what), in the order first met.
  std::vector<DroppedWarning> warnings() const;

 private:
  struct Entry {
    UsdLossKind kind;
    std::string what;
    size_t count = 0;
    SourceLoc first;
    std::string firstWhere;
  };
  std::vector<Entry> entries_;
};

// Applied API schemas that change how a prim looks and that the mapping
// does not read (ShapingAPI, ShadowAPI, light lists, lens distortion, draw
// modes, LightAPI on geometry...). Schemas the mapping reads
// (MaterialBindingAPI, SemanticsAPI) and those that change nothing visible
// (physics, collections, tools' own tags) are not losses.
bool appliedSchemaChangesAppearance(const std::string& schema, bool onLight);

}  // namespace sdg
