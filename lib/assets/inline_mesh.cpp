#include "assets/inline_mesh.h"

#include <cmath>
#include <cstdio>

#include "assets/subdivision.h"
#include "core/diagnostics.h"

namespace sdg {
namespace {

std::string hex(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

uint64_t hashOf(const Value& v) {
  return v.type() == ValueType::IntArray ? v.get<IntArray>().hash() : v.get<FloatArray>().hash();
}

// The part of the key a refined surface adds: its level, scheme and tags.
std::string subdivisionKey(const SubdivisionSurface& s) {
  std::string key = ":subdiv" + std::to_string(s.level) + s.scheme + "," + s.interpolateBoundary + "," +
                    s.faceVaryingLinearInterpolation + "," + s.triangleSubdivisionRule + ",";
  for (const Value* v : {&s.creaseIndices, &s.creaseLengths, &s.creaseSharpnesses, &s.cornerIndices,
                         &s.cornerSharpnesses})
    key += hex(hashOf(*v));
  return key;
}

size_t itemsOf(const Value& v) { return v.get<FloatArray>().size() / size_t(arrayWidth(v.type())); }

// A primvar is per point or per face-vertex; anything else is a problem.
std::string primvarProblem(const char* name, const Value& v, size_t points, size_t faceVertices) {
  const size_t n = itemsOf(v);
  if (n == points || n == faceVertices) return "";
  return std::string(name) + " has " + std::to_string(n) + " items; expected one per point (" +
         std::to_string(points) + ") or per face-vertex (" + std::to_string(faceVertices) + ")";
}

Vec3f item3(const Value& v, size_t i) {
  const FloatArray& a = v.get<FloatArray>();
  return {a[3 * i], a[3 * i + 1], a[3 * i + 2]};
}

}  // namespace

std::string InlineMesh::id() const {
  std::string key = "inline:" + hex(hashOf(points)) + hex(hashOf(faceVertexCounts)) + hex(hashOf(faceVertexIndices));
  key += normals ? hex(hashOf(*normals)) : "-";
  key += st ? hex(hashOf(*st)) : "-";
  // Only meshes with colours grow the key, so every other key stays as it was.
  if (displayColor) key += "c" + hex(hashOf(*displayColor));
  if (displayOpacity) key += "o" + hex(hashOf(*displayOpacity));
  if (!holeIndices.get<IntArray>().items().empty()) key += "h" + hex(hashOf(holeIndices));
  key += (flat ? "f" : "s");
  key += (leftHanded ? "l" : "r");
  return refined() ? key + subdivisionKey(subdivision) : key;
}

std::shared_ptr<const InlineMesh> inlineMeshOf(const Prim& prim, int subdivisionLevel) {
  const Attribute* points = prim.findAttribute("points");
  if (!points) return nullptr;
  auto mesh = std::make_shared<InlineMesh>();
  mesh->points = points->value;
  mesh->faceVertexCounts = *prim.value("faceVertexCounts");
  mesh->faceVertexIndices = *prim.value("faceVertexIndices");
  if (const Attribute* a = prim.findAttribute("normals")) mesh->normals = a->value;
  if (const Attribute* a = prim.findAttribute("primvars:st")) mesh->st = a->value;
  if (const Attribute* a = prim.findAttribute("primvars:displayColor:faceVarying")) mesh->displayColor = a->value;
  if (const Attribute* a = prim.findAttribute("primvars:displayOpacity:faceVarying")) mesh->displayOpacity = a->value;
  const std::string& scheme = prim.getString("subdivisionScheme");
  mesh->flat = scheme == "none";
  mesh->leftHanded = prim.getString("orientation") == "leftHanded";
  mesh->holeIndices = *prim.value("holeIndices");
  if (scheme != "none" && subdivisionLevel > 0) {
    SubdivisionSurface& s = mesh->subdivision;
    s.scheme = scheme;
    s.level = subdivisionLevel;
    s.interpolateBoundary = prim.getString("interpolateBoundary");
    s.faceVaryingLinearInterpolation = prim.getString("faceVaryingLinearInterpolation");
    s.triangleSubdivisionRule = prim.getString("triangleSubdivisionRule");
    s.creaseIndices = *prim.value("creaseIndices");
    s.creaseLengths = *prim.value("creaseLengths");
    s.creaseSharpnesses = *prim.value("creaseSharpnesses");
    s.cornerIndices = *prim.value("cornerIndices");
    s.cornerSharpnesses = *prim.value("cornerSharpnesses");
  }
  return mesh;
}

std::string inlineMeshProblem(const InlineMesh& mesh, std::string* attribute) {
  auto at = [attribute](const char* name, std::string problem) {
    if (attribute) *attribute = name;
    return problem;
  };
  const size_t points = itemsOf(mesh.points);
  const auto counts = mesh.faceVertexCounts.get<IntArray>().items();
  const auto indices = mesh.faceVertexIndices.get<IntArray>().items();
  size_t total = 0;
  for (size_t f = 0; f < counts.size(); ++f) {
    if (counts[f] < 3)
      return at("faceVertexCounts", "faceVertexCounts: expected each face to have at least 3 vertices, found " +
                                        std::to_string(counts[f]) + " for face " + std::to_string(f));
    total += size_t(counts[f]);
  }
  if (total != indices.size())
    return at("faceVertexIndices", "faceVertexCounts add up to " + std::to_string(total) +
                                       " but faceVertexIndices has " + std::to_string(indices.size()) + " items");
  for (size_t i = 0; i < indices.size(); ++i)
    if (indices[i] < 0 || size_t(indices[i]) >= points)
      return at("faceVertexIndices", "faceVertexIndices[" + std::to_string(i) + "] is " +
                                         std::to_string(indices[i]) + ", outside the " + std::to_string(points) +
                                         " points");
  const FloatArray& p = mesh.points.get<FloatArray>();
  for (size_t i = 0; i < p.size(); ++i)
    if (!std::isfinite(p[i]))
      return at("points", "points[" + std::to_string(i / 3) + "] is not finite (found " + std::to_string(p[i]) + ")");
  if (mesh.normals) {
    if (std::string problem = primvarProblem("normals", *mesh.normals, points, indices.size()); !problem.empty())
      return at("normals", problem);
  }
  if (mesh.st) {
    if (std::string problem = primvarProblem("primvars:st", *mesh.st, points, indices.size()); !problem.empty())
      return at("primvars:st", problem);
  }
  const std::pair<const char*, const std::optional<Value>*> perCorner[] = {
      {"primvars:displayColor:faceVarying", &mesh.displayColor}, {"primvars:displayOpacity:faceVarying", &mesh.displayOpacity}};
  for (const auto& [name, value] : perCorner)
    if (*value && itemsOf(**value) != indices.size())
      return at(name, std::string(name) + " has " + std::to_string(itemsOf(**value)) +
                          " items; expected one per face-vertex (" + std::to_string(indices.size()) + ")");
  const auto holes = mesh.holeIndices.get<IntArray>().items();
  for (size_t i = 0; i < holes.size(); ++i)
    if (holes[i] < 0 || size_t(holes[i]) >= counts.size())
      return at("holeIndices", "holeIndices[" + std::to_string(i) + "] is " + std::to_string(holes[i]) +
                                   ", outside the " + std::to_string(counts.size()) + " faces");
  if (mesh.refined()) return subdivisionProblem(mesh);
  return "";
}

MeshData triangulateInlineMesh(const InlineMesh& authored, const std::string& primPath) {
  if (std::string problem = inlineMeshProblem(authored); !problem.empty()) throw RunError(primPath + ": " + problem);
  // A subdivision surface: its refined polygons (no normals: computed smooth below).
  std::optional<InlineMesh> refined;
  if (authored.refined()) refined = refineSubdivisionSurface(authored, primPath);
  const InlineMesh& mesh = refined ? *refined : authored;
  const size_t points = itemsOf(mesh.points);
  const auto counts = mesh.faceVertexCounts.get<IntArray>().items();
  const auto indices = mesh.faceVertexIndices.get<IntArray>().items();
  // Per point unless the length says per face-vertex (a mesh whose two
  // counts are equal reads as per face-vertex, which importers write).
  const bool normalsPerCorner = mesh.normals && itemsOf(*mesh.normals) == indices.size();
  const bool stPerCorner = mesh.st && itemsOf(*mesh.st) == indices.size();

  std::vector<bool> hole(counts.size(), false);
  for (int32_t f : mesh.holeIndices.get<IntArray>().items()) hole[size_t(f)] = true;

  // Smooth normals where none are given: area-weighted per point.
  std::vector<Vec3f> smooth;
  if (!mesh.normals && !mesh.flat) {
    smooth.assign(points, Vec3f::Zero());
    size_t first = 0;
    for (size_t f = 0; f < counts.size(); ++f) {
      const int32_t c = hole[f] ? 0 : counts[f];
      for (int32_t k = 1; k + 1 < c; ++k) {
        const size_t a = size_t(indices[first]), b = size_t(indices[first + size_t(k)]),
                     d = size_t(indices[first + size_t(k) + 1]);
        Vec3f n = (item3(mesh.points, b) - item3(mesh.points, a)).cross(item3(mesh.points, d) - item3(mesh.points, a));
        if (mesh.leftHanded) n = -n;
        smooth[a] += n;
        smooth[b] += n;
        smooth[d] += n;
      }
      first += size_t(counts[f]);
    }
    for (Vec3f& n : smooth) n = n.norm() > 0 ? Vec3f(n.normalized()) : Vec3f(0, 0, 1);
  }

  MeshData out;
  size_t first = 0;
  for (size_t f = 0; f < counts.size(); ++f) {
    const int32_t c = counts[f];
    if (c >= 3 && !hole[f]) {
      // One vertex per corner of the face, then a fan.
      const uint32_t base = uint32_t(out.positions.size());
      Vec3f faceNormal(0, 0, 0);
      for (int32_t k = 1; k + 1 < c; ++k)
        faceNormal += (item3(mesh.points, size_t(indices[first + size_t(k)])) - item3(mesh.points, size_t(indices[first]))).cross(
            item3(mesh.points, size_t(indices[first + size_t(k) + 1])) - item3(mesh.points, size_t(indices[first])));
      if (mesh.leftHanded) faceNormal = -faceNormal;
      faceNormal = faceNormal.norm() > 0 ? Vec3f(faceNormal.normalized()) : Vec3f(0, 0, 1);
      for (int32_t k = 0; k < c; ++k) {
        const size_t corner = first + size_t(k), point = size_t(indices[corner]);
        out.positions.push_back(item3(mesh.points, point));
        if (mesh.normals) out.normals.push_back(item3(*mesh.normals, normalsPerCorner ? corner : point).normalized());
        else out.normals.push_back(mesh.flat ? faceNormal : smooth[point]);
        if (mesh.st) {
          const FloatArray& st = mesh.st->get<FloatArray>();
          const size_t i = stPerCorner ? corner : point;
          out.uvs.emplace_back(st[2 * i], st[2 * i + 1]);
        } else {
          out.uvs.emplace_back(0.0f, 0.0f);
        }
        if (mesh.displayColor || mesh.displayOpacity) {
          Eigen::Vector4f color(1.0f, 1.0f, 1.0f, 1.0f);
          if (mesh.displayColor) color.head<3>() = item3(*mesh.displayColor, corner);
          if (mesh.displayOpacity) color.w() = mesh.displayOpacity->get<FloatArray>()[corner];
          out.colors.push_back(color);
        }
      }
      for (int32_t k = 1; k + 1 < c; ++k) {
        out.indices.push_back(base);
        // leftHanded faces wind clockwise: swap to keep front faces counter-clockwise.
        out.indices.push_back(base + uint32_t(mesh.leftHanded ? k + 1 : k));
        out.indices.push_back(base + uint32_t(mesh.leftHanded ? k : k + 1));
      }
    }
    first += size_t(c);
  }
  MeshPart part;
  part.indexCount = uint32_t(out.indices.size());
  out.parts.push_back(part);
  out.updateBounds();
  return out;
}

}  // namespace sdg
