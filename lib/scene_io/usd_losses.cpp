#include "scene_io/usd_losses.h"

#include <algorithm>
#include <array>
#include <string_view>

namespace sdg {
namespace {

// The sentence each kind ends with: what the user gets instead.
std::string describe(UsdLossKind kind, const std::string& what, size_t count, const std::string& where) {
  const std::string n = std::to_string(count);
  const bool one = count == 1;
  const std::string first = where.empty() ? "" : (one ? " (" : " (first ") + where + ")";
  switch (kind) {
    case UsdLossKind::PrimType:
      return "dropped: " + n + (one ? " prim" : " prims") + " of type " + what + first +
             ": imported as " + (one ? "a group" : "groups") + " (Xform); what the type draws or does is missing";
    case UsdLossKind::AppliedSchema:
      return "dropped: applied schema " + what + " on " + n + (one ? " prim" : " prims") + first +
             ": not read; how it changes the prim's look is missing";
    case UsdLossKind::MaterialNetwork:
      return "dropped: " + n + (one ? " material" : " materials") + " with " + what + first +
             ": only UsdPreviewSurface and MDL OmniPBR are read; prims bound to " + (one ? "it" : "them") +
             " keep their primvars:displayColor";
    case UsdLossKind::MaterialInput:
      return "dropped: material input " + what + " on " + n + (one ? " material" : " materials") + first +
             ": not carried over";
    case UsdLossKind::Binding:
      return "dropped: " + what + ", " + n + (one ? " time" : " times") + first;
    case UsdLossKind::Composition:
      return "dropped: composition feature '" + what + "', " + n + (one ? " time" : " times") + first +
             ": not applied";
    case UsdLossKind::Attribute:
      return "dropped: attribute " + what + " on " + n + (one ? " prim" : " prims") + first +
             ": not read by the stage";
  }
  return "dropped: " + what;
}

}  // namespace

const char* usdLossKindName(UsdLossKind kind) {
  switch (kind) {
    case UsdLossKind::PrimType: return "prim_type";
    case UsdLossKind::AppliedSchema: return "applied_schema";
    case UsdLossKind::MaterialNetwork: return "material_network";
    case UsdLossKind::MaterialInput: return "material_input";
    case UsdLossKind::Binding: return "binding";
    case UsdLossKind::Composition: return "composition";
    case UsdLossKind::Attribute: return "attribute";
  }
  return "other";
}

void UsdLosses::note(UsdLossKind kind, const std::string& what, const SourceLoc& loc, const std::string& where) {
  for (Entry& e : entries_)
    if (e.kind == kind && e.what == what) {
      ++e.count;
      return;
    }
  entries_.push_back(Entry{kind, what, 1, loc, where});
}

void UsdLosses::append(const UsdLosses& other) {
  for (const Entry& o : other.entries_) {
    auto it = std::find_if(entries_.begin(), entries_.end(),
                           [&](const Entry& e) { return e.kind == o.kind && e.what == o.what; });
    if (it == entries_.end()) entries_.push_back(o);
    else it->count += o.count;
  }
}

std::vector<DroppedWarning> UsdLosses::warnings() const {
  std::vector<DroppedWarning> out;
  for (const Entry& e : entries_)
    out.push_back(DroppedWarning{Diagnostic{Severity::Warning, e.first, describe(e.kind, e.what, e.count, e.firstWhere)},
                                 DroppedInfo{usdLossKindName(e.kind), e.what, e.count}});
  return out;
}

bool appliedSchemaChangesAppearance(const std::string& schema, bool onLight) {
  // Schemas that change the look and that nothing here reads; every other
  // schema is either read (MaterialBindingAPI, SemanticsAPI, SkelBindingAPI, ...) or has no
  // visible effect (physics, collections, tools' own tags).
  // The lens schemas of usd_lens_schemas.h are read; the family's others are not.
  static constexpr std::array<std::string_view, 10> kVisible = {
      "ShapingAPI", "ShadowAPI", "LightListAPI", "MotionAPI", "VisibilityAPI", "GeomModelAPI", "VolumeLightAPI",
      "OmniLensDistortionRadTanThinPrismAPI", "OmniLensDistortionLutAPI", "OmniLensDistortionOmniDirectionalStereoAPI"};
  const std::string_view name = std::string_view(schema).substr(0, schema.find(':'));  // multiple-apply: "X:instance"
  // A light's own LightAPI is what makes it a light; on geometry it makes a mesh light.
  if (name == "LightAPI" || name == "MeshLightAPI") return !onLight;
  for (std::string_view v : kVisible)
    if (name.starts_with(v)) return true;
  return false;
}

}  // namespace sdg
