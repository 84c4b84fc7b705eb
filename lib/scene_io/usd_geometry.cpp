// A UsdGeomMesh onto a stage Mesh with inline geometry. Primvars of every
// interpolation (constant, uniform, vertex, varying, faceVarying), indexed
// or not, are written one item per face-vertex, the one layout the stage's
// triangulation needs no hint for (assets/inline_mesh.h).
#include <algorithm>

#include "core/text.h"
#include "scene_io/usd_import_internal.h"
#include "scene_io/usd_mesh_topology.h"

namespace sdg::usd_map {
namespace {

// The primvar holding texture coordinates: primvars:st, else the first
// texCoord2f[] / float2[] primvar (st0, UVMap, ...).
const usd::ComposedProperty* uvPrimvar(const usd::ComposedPrim& mesh) {
  if (const usd::ComposedProperty* st = mesh.property("primvars:st"); st && !st->value.empty()) return st;
  for (const usd::ComposedProperty& p : mesh.properties)
    if (p.name.rfind("primvars:", 0) == 0 && p.name.find(":indices") == std::string::npos &&
        (p.typeName == "texCoord2f[]" || p.typeName == "float2[]") && !p.value.empty())
      return &p;
  return nullptr;
}

struct Topology {
  std::vector<int32_t> counts, indices;
  std::vector<size_t> faceStart;  // first corner of each face
};

// One item per kept corner of `width` numbers from a primvar of the given
// interpolation (`fallback` when the property does not say); empty after
// reporting when its length does not fit.
std::vector<float> perCorner(const usd::ComposedPrim& mesh, const usd::ComposedProperty& p, size_t width,
                             const std::string& fallback, const Topology& topo, const std::vector<size_t>& faces,
                             size_t points, Diagnostics& diag) {
  const std::string interpolation = primvarInterpolation(p, fallback);
  const std::vector<double>& values = p.value.numbers;
  const size_t items = values.size() / width;
  std::vector<int64_t> index;  // indexed primvar: item of each element
  if (const usd::ComposedProperty* ix = mesh.property(p.name + ":indices"); ix && !ix->value.empty())
    for (double d : ix->value.numbers) index.push_back(int64_t(d));
  const size_t elements = index.empty() ? items : index.size();
  size_t expected = 0;
  if (interpolation == "constant") expected = 1;
  else if (interpolation == "uniform") expected = topo.counts.size();
  else if (interpolation == "vertex" || interpolation == "varying") expected = points;
  else if (interpolation == "faceVarying") expected = topo.indices.size();
  else {
    diag.error(p.loc, mesh.path + "." + p.name + ": interpolation " + interpolation +
                          " is not one of constant, uniform, vertex, varying, faceVarying");
    return {};
  }
  if (elements < expected) {
    diag.error(p.loc, mesh.path + "." + p.name + ": " + interpolation + " needs " + std::to_string(expected) +
                          " items, found " + std::to_string(elements));
    return {};
  }
  std::vector<float> out;
  auto push = [&](size_t element) -> bool {
    size_t item = element;
    if (!index.empty()) {
      if (index[element] < 0 || size_t(index[element]) >= items) {
        diag.error(p.loc, mesh.path + "." + p.name + ":indices: " + std::to_string(index[element]) +
                              " is outside the " + std::to_string(items) + " values");
        return false;
      }
      item = size_t(index[element]);
    }
    for (size_t k = 0; k < width; ++k) out.push_back(float(values[item * width + k]));
    return true;
  };
  for (size_t f : faces)
    for (size_t c = 0; c < size_t(topo.counts[f]); ++c) {
      const size_t corner = topo.faceStart[f] + c;
      size_t element = 0;
      if (interpolation == "uniform") element = f;
      else if (interpolation == "vertex" || interpolation == "varying") element = size_t(topo.indices[corner]);
      else if (interpolation == "faceVarying") element = corner;
      if (!push(element)) return {};
    }
  return out;
}

std::vector<int32_t> ints(const usd::ComposedProperty* p) {
  std::vector<int32_t> out;
  if (p)
    for (double d : p->value.numbers) out.push_back(int32_t(d));
  return out;
}

}  // namespace

void importMeshGeometry(const usd::ComposedPrim& mesh, Prim& stagePrim, const std::vector<int32_t>* subsetFaces,
                        Diagnostics& diag) {
  // Counts, indices, points and primvar sizes checked before anything below indexes with them.
  if (!checkMeshTopology(mesh, diag)) return;
  const usd::ComposedProperty* points = mesh.property("points");
  std::optional<Value> pointsValue = points ? toStageValue(points->value, ValueType::Point3fArray) : std::nullopt;
  if (!pointsValue) {
    diag.error(points ? points->loc : mesh.loc, mesh.path + ".points: a Mesh needs points (point3f[])");
    return;
  }
  Topology topo;
  topo.counts = ints(mesh.property("faceVertexCounts"));
  topo.indices = ints(mesh.property("faceVertexIndices"));
  const size_t pointCount = pointsValue->get<FloatArray>().size() / 3;
  size_t corner = 0;
  for (int32_t c : topo.counts) {
    topo.faceStart.push_back(corner);
    corner += size_t(std::max(c, 0));
  }
  if (corner != topo.indices.size()) {
    diag.error(mesh.loc, mesh.path + ": faceVertexCounts add up to " + std::to_string(corner) +
                             " but faceVertexIndices has " + std::to_string(topo.indices.size()) + " items");
    return;
  }
  std::vector<size_t> faces;
  if (subsetFaces) {
    for (int32_t f : *subsetFaces)
      if (f >= 0 && size_t(f) < topo.counts.size()) faces.push_back(size_t(f));
  } else {
    for (size_t f = 0; f < topo.counts.size(); ++f) faces.push_back(f);
  }
  std::vector<int32_t> counts, indices;
  for (size_t f : faces) {
    counts.push_back(topo.counts[f]);
    for (size_t c = 0; c < size_t(topo.counts[f]); ++c) indices.push_back(topo.indices[topo.faceStart[f] + c]);
  }
  stagePrim.setAttribute("points", *pointsValue).loc = points->loc;
  stagePrim.setAttribute("faceVertexCounts", Value::makeIntArray(std::move(counts))).loc = mesh.loc;
  stagePrim.setAttribute("faceVertexIndices", Value::makeIntArray(std::move(indices))).loc = mesh.loc;

  // primvars:normals overrides normals, as in USD.
  const usd::ComposedProperty* normals = mesh.property("primvars:normals");
  if (!normals || normals->value.empty()) normals = mesh.property("normals");
  if (normals && !normals->value.empty() && usd::componentCount(normals->value.kind) == 3) {
    std::vector<float> n = perCorner(mesh, *normals, 3, "vertex", topo, faces, pointCount, diag);
    if (!n.empty()) stagePrim.setAttribute("normals", Value::makeFloatArray(ValueType::Normal3fArray, std::move(n))).loc = normals->loc;
  }
  if (const usd::ComposedProperty* st = uvPrimvar(mesh); st && usd::componentCount(st->value.kind) == 2) {
    std::vector<float> uv = perCorner(mesh, *st, 2, "vertex", topo, faces, pointCount, diag);
    if (!uv.empty()) stagePrim.setAttribute("primvars:st", Value::makeFloatArray(ValueType::TexCoord2fArray, std::move(uv))).loc = st->loc;
  }
  // Non-constant displayColor and displayOpacity (the constant ones are
  // gprim attributes: usd_display_primvars.cpp).
  const std::pair<std::string, size_t> displayPrimvars[] = {{"primvars:displayColor", 3}, {"primvars:displayOpacity", 1}};
  for (const auto& [name, width] : displayPrimvars)
    if (const usd::ComposedProperty* p = mesh.property(name); p && isVaryingDisplayPrimvar(mesh, *p))
      if (std::optional<std::string> interpolation =
              displayPrimvarInterpolation(mesh, *p, topo.counts.size(), pointCount, topo.indices.size(), diag)) {
        std::vector<float> v = perCorner(mesh, *p, width, *interpolation, topo, faces, pointCount, diag);
        if (!v.empty())
          stagePrim.setAttribute(name + ":faceVarying", Value::makeFloatArray(width == 3 ? ValueType::Color3fArray : ValueType::FloatArray, std::move(v))).loc = p->loc;
      }
  for (const char* token : {"subdivisionScheme", "orientation"})
    if (const usd::ComposedProperty* p = mesh.property(token); p && !p->value.empty() && usd::isText(p->value.kind)) {
      const AttributeSpec* spec = findSchemaAttribute(PrimType::Mesh, token);
      const std::string& v = p->value.strings[0];
      if (std::find(spec->allowedTokens.begin(), spec->allowedTokens.end(), v) == spec->allowedTokens.end())
        diag.error(p->loc, mesh.path + "." + token + ": expected one of " + text::join(spec->allowedTokens, ", ") + ", found " + v);
      else
        stagePrim.setAttribute(token, Value::makeToken(v)).loc = p->loc;
    }
  importSubdivisionTags(mesh, stagePrim, faces, diag);
}

}  // namespace sdg::usd_map
