// The checks of usd_mesh_topology.h. Each attribute gets one message, for
// its first bad item, with how many more are bad: a broken array of a
// million items must not print a million lines.
#include "scene_io/usd_mesh_topology.h"

#include <cmath>
#include <limits>

#include "core/text.h"

namespace sdg::usd_map {
namespace {

std::string count(size_t n) { return std::to_string(n); }

// A number as usda writes it: nan and inf bare (text::formatNumber says .nan, as YAML does).
std::string number(double d) {
  if (std::isnan(d)) return "nan";
  if (std::isinf(d)) return d < 0 ? "-inf" : "inf";
  return text::formatNumber(d);
}

bool whole(double d) { return std::isfinite(d) && d == std::floor(d); }

// d is a whole number in [0, end).
bool indexIn(double d, size_t end) { return whole(d) && d >= 0 && d < double(end); }

// " (3 of 12 faceVertexIndices are)": how many items share the first one's problem.
std::string ofWhich(size_t bad, size_t all, const std::string& noun) {
  return bad > 1 ? " (" + count(bad) + " of " + count(all) + " " + noun + " are)" : "";
}

// The numbers of an authored numeric array property; null when absent,
// blocked or empty.
const usd::ComposedProperty* authoredArray(const usd::ComposedPrim& prim, const std::string& name) {
  const usd::ComposedProperty* p = prim.property(name);
  if (!p || p->value.empty() || !usd::isNumeric(p->value.kind)) return nullptr;
  return p;
}

SourceLoc locOf(const usd::ComposedPrim& prim, const usd::ComposedProperty* p) {
  return p && p->loc.known() ? p->loc : prim.loc;
}


struct MeshSizes {
  size_t points = 0, faces = 0, faceVertices = 0;
};

// Every index of `values` one of `items` (the indices of an indexed primvar).
bool checkIndices(const usd::ComposedPrim& mesh, const usd::ComposedProperty& ix, size_t items, Diagnostics& diag) {
  size_t bad = 0, first = 0;
  for (size_t i = 0; i < ix.value.numbers.size(); ++i)
    if (!indexIn(ix.value.numbers[i], items) && bad++ == 0) first = i;
  if (bad == 0) return true;
  diag.error(ix.loc, mesh.path + "." + ix.name + ": expected each index to be one of the " + count(items) +
                         " values (0 to " + count(items ? items - 1 : 0) + "), found " +
                         number(ix.value.numbers[first]) + " at [" + count(first) + "]" +
                         ofWhich(bad, ix.value.numbers.size(), "indices"));
  return false;
}

// A primvar long enough for its interpolation, its indices (when indexed)
// inside its values.
bool checkPrimvar(const usd::ComposedPrim& mesh, const usd::ComposedProperty& p, const std::string& fallback,
                  const MeshSizes& sizes, Diagnostics& diag) {
  const std::string interpolation = primvarInterpolation(p, fallback);
  size_t expected = 0;
  std::string per;
  if (interpolation == "constant") expected = 1, per = "one value";
  else if (interpolation == "uniform") expected = sizes.faces, per = "one per face";
  else if (interpolation == "vertex" || interpolation == "varying") expected = sizes.points, per = "one per point";
  else if (interpolation == "faceVarying") expected = sizes.faceVertices, per = "one per face-vertex";
  else {
    diag.error(locOf(mesh, &p), mesh.path + "." + p.name + ": expected interpolation constant, uniform, vertex, " +
                                    "varying or faceVarying, found " + text::quote(interpolation));
    return false;
  }
  const size_t width = size_t(std::max(usd::componentCount(p.value.kind), 1));
  const size_t items = p.value.numbers.size() / width;
  if (const usd::ComposedProperty* ix = mesh.property(p.name + ":indices"); ix && !ix->value.empty()) {
    const size_t n = ix->value.numbers.size();
    if (n < expected) {
      diag.error(locOf(mesh, ix), mesh.path + "." + ix->name + ": " + interpolation + " needs " + count(expected) +
                                      " indices (" + per + "), found " + count(n));
      return false;
    }
    return checkIndices(mesh, *ix, items, diag);
  }
  if (items < expected) {
    diag.error(locOf(mesh, &p), mesh.path + "." + p.name + ": " + interpolation + " needs " + count(expected) +
                                    " items (" + per + "), found " + count(items));
    return false;
  }
  return true;
}

bool isTexCoord2(const usd::ComposedProperty& p) {
  return p.typeName == "texCoord2f[]" || p.typeName == "texCoord2h[]" || p.typeName == "texCoord2d[]" ||
         p.typeName == "float2[]";
}

// The primvars the importer reads, with its fallback interpolation.
std::vector<std::pair<const usd::ComposedProperty*, std::string>> primvarsRead(const usd::ComposedPrim& mesh) {
  std::vector<std::pair<const usd::ComposedProperty*, std::string>> out;
  for (const usd::ComposedProperty& p : mesh.properties) {
    if (p.isRelationship || p.value.empty() || !usd::isNumeric(p.value.kind)) continue;
    if (p.name.size() > 8 && p.name.ends_with(":indices")) continue;
    if (p.name == "normals" || p.name == "primvars:normals" || p.name == "primvars:st" ||
        (p.name.starts_with("primvars:") && isTexCoord2(p)))
      out.emplace_back(&p, "vertex");
    else if (p.name == "primvars:displayColor" || p.name == "primvars:displayOpacity")
      out.emplace_back(&p, "constant");
  }
  return out;
}

bool checkPoints(const usd::ComposedPrim& mesh, const usd::ComposedProperty& points, Diagnostics& diag) {
  const std::vector<double>& v = points.value.numbers;
  size_t bad = 0, first = 0;
  for (size_t i = 0; i + 2 < v.size(); i += 3)
    if (!(std::isfinite(float(v[i])) && std::isfinite(float(v[i + 1])) && std::isfinite(float(v[i + 2]))) &&
        bad++ == 0)
      first = i / 3;
  if (bad == 0) return true;
  diag.error(locOf(mesh, &points),
             mesh.path + ".points: expected finite coordinates, found (" + number(v[3 * first]) + ", " +
                 number(v[3 * first + 1]) + ", " + number(v[3 * first + 2]) + ") at [" +
                 count(first) + "]" + ofWhich(bad, v.size() / 3, "points"));
  return false;
}

}  // namespace

bool checkMeshTopology(const usd::ComposedPrim& mesh, Diagnostics& diag) {
  const usd::ComposedProperty* points = mesh.property("points");
  if (!points || !points->value.isArray || usd::componentCount(points->value.kind) != 3) return true;  // the importer says so
  MeshSizes sizes;
  sizes.points = points->value.numbers.size() / 3;
  bool ok = checkPoints(mesh, *points, diag);

  // Counts: whole numbers of at least 3 corners. A negative one used to wrap
  // round to a huge loop over the indices.
  const usd::ComposedProperty* counts = authoredArray(mesh, "faceVertexCounts");
  const usd::ComposedProperty* indices = authoredArray(mesh, "faceVertexIndices");
  bool topologyOk = true;
  double sum = 0;
  if (counts) {
    const std::vector<double>& c = counts->value.numbers;
    sizes.faces = c.size();
    size_t bad = 0, first = 0;
    for (size_t i = 0; i < c.size(); ++i) {
      if (!(whole(c[i]) && c[i] >= 3) && bad++ == 0) first = i;
      if (std::isfinite(c[i])) sum += c[i];
    }
    if (bad) {
      diag.error(locOf(mesh, counts), mesh.path + ".faceVertexCounts: expected each face to have at least 3 " +
                                          "vertices, found " + number(c[first]) + " for face " +
                                          count(first) + ofWhich(bad, c.size(), "counts"));
      topologyOk = false;
    }
  }
  const size_t indexCount = indices ? indices->value.numbers.size() : 0;
  if (topologyOk && sum != double(indexCount)) {
    diag.error(locOf(mesh, indices ? indices : counts),
               mesh.path + ".faceVertexIndices: expected " + number(sum) +
                   " indices (the sum of faceVertexCounts), found " + count(indexCount));
    topologyOk = false;
  }
  sizes.faceVertices = indexCount;
  if (indices) {
    const std::vector<double>& ix = indices->value.numbers;
    size_t bad = 0, first = 0;
    for (size_t i = 0; i < ix.size(); ++i)
      if (!indexIn(ix[i], sizes.points) && bad++ == 0) first = i;
    if (bad) {
      diag.error(locOf(mesh, indices), mesh.path + ".faceVertexIndices: expected each index to be one of the " +
                                           count(sizes.points) + " points (0 to " +
                                           count(sizes.points ? sizes.points - 1 : 0) + "), found " +
                                           number(ix[first]) + " at [" + count(first) + "]" +
                                           ofWhich(bad, ix.size(), "indices"));
      topologyOk = false;
    }
  }
  // Primvar sizes are measured against the faces and corners: only
  // meaningful once those are sound.
  if (topologyOk)
    for (const auto& [primvar, fallback] : primvarsRead(mesh))
      if (!checkPrimvar(mesh, *primvar, fallback, sizes, diag)) ok = false;
  return ok && topologyOk;
}

std::optional<std::vector<int32_t>> subsetFaces(const usd::ComposedPrim& subset, const std::string& meshPath,
                                                size_t faceCount, Diagnostics& diag) {
  std::vector<int32_t> faces;
  const usd::ComposedProperty* indices = subset.property("indices");
  if (!indices) return faces;
  const std::vector<double>& v = indices->value.numbers;
  size_t bad = 0, first = 0;
  for (size_t i = 0; i < v.size(); ++i) {
    if (!indexIn(v[i], faceCount)) {
      if (bad++ == 0) first = i;
      continue;
    }
    faces.push_back(int32_t(v[i]));
  }
  if (bad == 0) return faces;
  diag.error(locOf(subset, indices), subset.path + ".indices: expected faces of " + meshPath + " (0 to " +
                                         count(faceCount ? faceCount - 1 : 0) + "), found " +
                                         number(v[first]) + " at [" + count(first) + "]" +
                                         ofWhich(bad, v.size(), "indices"));
  return std::nullopt;
}

std::string primvarInterpolation(const usd::ComposedProperty& p, const std::string& fallback) {
  auto it = p.metadata.find("interpolation");
  if (it != p.metadata.end() && usd::isText(it->second.kind) && !it->second.strings.empty()) return it->second.strings[0];
  return fallback;
}

}  // namespace sdg::usd_map
