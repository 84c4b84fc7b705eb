// A UsdGeomMesh's subdivision arrays onto a stage Mesh (refined by
// assets/subdivision.h): creases and corners as authored (they name points,
// which a GeomSubset's mesh keeps), holes renumbered to the faces the stage
// Mesh keeps. The rule tokens (interpolateBoundary, ...) are schema
// attributes of the stage Mesh: the importer reads them as it reads others.
#include <algorithm>

#include "core/text.h"
#include "scene_io/usd_import_internal.h"

namespace sdg::usd_map {

void importSubdivisionTags(const usd::ComposedPrim& mesh, Prim& stagePrim, const std::vector<size_t>& faces,
                           Diagnostics& diag) {
  for (const auto& [name, type] : {std::pair{"creaseIndices", ValueType::IntArray}, std::pair{"creaseLengths", ValueType::IntArray},
                                   std::pair{"creaseSharpnesses", ValueType::FloatArray},
                                   std::pair{"cornerIndices", ValueType::IntArray},
                                   std::pair{"cornerSharpnesses", ValueType::FloatArray}}) {
    const usd::ComposedProperty* p = mesh.property(name);
    if (!p || p->value.empty()) continue;
    if (std::optional<Value> v = toStageValue(p->value, type))
      stagePrim.setAttribute(name, *v).loc = p->loc;
    else
      diag.error(p->loc, mesh.path + "." + name + ": expected " + std::string(valueTypeName(type)) + ", found " +
                             p->typeName);
  }
  if (const usd::ComposedProperty* p = mesh.property("holeIndices"); p && !p->value.empty()) {
    std::vector<int32_t> kept(faces.size() ? *std::max_element(faces.begin(), faces.end()) + 1 : 0, -1);
    for (size_t i = 0; i < faces.size(); ++i) kept[faces[i]] = int32_t(i);
    const usd::ComposedProperty* counts = mesh.property("faceVertexCounts");
    const size_t faceCount = counts ? counts->value.numbers.size() : 0;
    std::vector<int32_t> holes;
    for (double d : p->value.numbers) {
      if (!(d >= 0 && d < double(faceCount))) {
        diag.error(p->loc, mesh.path + ".holeIndices: " + text::formatDouble(d) + " is outside the " +
                               std::to_string(faceCount) + " faces");
        return;
      }
      if (d < double(kept.size()) && kept[size_t(d)] >= 0) holes.push_back(kept[size_t(d)]);
    }
    if (!holes.empty()) stagePrim.setAttribute("holeIndices", Value::makeIntArray(std::move(holes))).loc = p->loc;
  }
}

}  // namespace sdg::usd_map
