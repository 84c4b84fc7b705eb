#include "assets/subdivision.h"

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <cstring>
#include <unordered_map>

#include "assets/mesh_loader.h"
#include "core/diagnostics.h"

namespace sdg {
namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

std::span<const int32_t> intsOf(const Value& v) { return v.get<IntArray>().items(); }
std::span<const float> floatsOf(const Value& v) { return v.get<FloatArray>().items(); }

// A primvar value OpenSubdiv blends: N floats.
template <int N>
struct Item {
  float v[N];
  void Clear() { std::memset(v, 0, sizeof v); }
  void AddWithWeight(const Item& src, float weight) {
    for (int k = 0; k < N; ++k) v[k] += weight * src.v[k];
  }
};
using Point = Item<3>;
using Uv = Item<2>;

// OpenSubdiv reports through process-wide callbacks: what it says while this
// thread refines is kept for the error message (meshes may be refined on
// several threads at once).
thread_local std::string osdMessages;
void onOsdError(Far::ErrorType, const char* message) { osdMessages += std::string(osdMessages.empty() ? "" : "; ") + message; }
void onOsdWarning(const char*) {}  // e.g. a crease edge the mesh lacks: the crease is dropped, as in USD's renderers

// Faces refinement produces at its first level, per face of `counts`: an
// n-gon splits into n quads (catmullClark, bilinear), a triangle into four
// triangles (loop); each later level multiplies by four.
double refinedTriangles(std::span<const int32_t> counts, const SubdivisionSurface& s) {
  double faces = 0;
  for (int32_t c : counts)
    if (c >= 3) faces += s.scheme == "loop" ? 4.0 : double(c);
  for (int l = 1; l < s.level; ++l) faces *= 4.0;
  return s.scheme == "loop" ? faces : 2.0 * faces;
}

Sdc::Options sdcOptions(const SubdivisionSurface& s) {
  Sdc::Options o;
  o.SetVtxBoundaryInterpolation(s.interpolateBoundary == "none"       ? Sdc::Options::VTX_BOUNDARY_NONE
                                : s.interpolateBoundary == "edgeOnly" ? Sdc::Options::VTX_BOUNDARY_EDGE_ONLY
                                                                      : Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  const std::string& fv = s.faceVaryingLinearInterpolation;
  o.SetFVarLinearInterpolation(fv == "none"           ? Sdc::Options::FVAR_LINEAR_NONE
                               : fv == "cornersOnly"  ? Sdc::Options::FVAR_LINEAR_CORNERS_ONLY
                               : fv == "cornersPlus2" ? Sdc::Options::FVAR_LINEAR_CORNERS_PLUS2
                               : fv == "boundaries"   ? Sdc::Options::FVAR_LINEAR_BOUNDARIES
                               : fv == "all"          ? Sdc::Options::FVAR_LINEAR_ALL
                                                      : Sdc::Options::FVAR_LINEAR_CORNERS_PLUS1);
  o.SetTriangleSubdivision(s.triangleSubdivisionRule == "smooth" ? Sdc::Options::TRI_SUB_SMOOTH
                                                                 : Sdc::Options::TRI_SUB_CATMARK);
  return o;
}

// The faces OpenSubdiv is given: those with three corners or more (the
// triangulation drops the others too), and for each authored face its new
// index (-1 when dropped), for holeIndices.
struct BaseTopology {
  std::vector<int> counts;
  std::vector<Far::Index> indices;
  std::vector<int32_t> corners;  // the authored corner of each kept face-vertex
  std::vector<int32_t> newFace;
};

BaseTopology baseTopology(const InlineMesh& mesh) {
  BaseTopology t;
  const auto counts = intsOf(mesh.faceVertexCounts);
  const auto indices = intsOf(mesh.faceVertexIndices);
  size_t first = 0;
  for (int32_t c : counts) {
    if (c >= 3) {
      t.newFace.push_back(int32_t(t.counts.size()));
      t.counts.push_back(c);
      for (int32_t k = 0; k < c; ++k) {
        t.indices.push_back(indices[first + size_t(k)]);
        t.corners.push_back(int32_t(first) + k);
      }
    } else {
      t.newFace.push_back(-1);
    }
    first += size_t(c);
  }
  return t;
}

// A face-varying channel (primvars:st; the per-corner colour and opacity):
// one value per distinct (point, value) pair, so that corners of a point
// with the same value stay joined (the importer writes every primvar per
// face-vertex, which would otherwise cut every face loose) and a seam, where
// a point has two values, stays a seam.
template <int N>
struct FaceVaryingChannel {
  std::vector<Item<N>> values;
  std::vector<Far::Index> valueOfCorner;  // per kept face-vertex
};

// `valueAt(corner, point)` gives the N floats of one face-vertex of the
// authored mesh (`corner` its face-vertex index, `point` its point).
template <int N, typename ValueAt>
FaceVaryingChannel<N> faceVaryingChannel(const BaseTopology& t, ValueAt valueAt) {
  FaceVaryingChannel<N> ch;
  std::unordered_map<uint64_t, std::vector<Far::Index>> byPoint;  // point -> its values
  for (size_t i = 0; i < t.indices.size(); ++i) {
    const Item<N> value = valueAt(size_t(t.corners[i]), size_t(t.indices[i]));
    std::vector<Far::Index>& known = byPoint[uint64_t(t.indices[i])];
    Far::Index found = -1;
    for (Far::Index v : known)
      if (std::memcmp(ch.values[size_t(v)].v, value.v, sizeof value.v) == 0) found = v;
    if (found < 0) {
      found = Far::Index(ch.values.size());
      ch.values.push_back(value);
      known.push_back(found);
    }
    ch.valueOfCorner.push_back(found);
  }
  return ch;
}

FaceVaryingChannel<2> uvChannel(const InlineMesh& mesh, const BaseTopology& t) {
  const auto st = floatsOf(*mesh.st);
  // Per face-vertex when the length says so, as the triangulation reads it.
  const bool perCorner = st.size() / 2 == intsOf(mesh.faceVertexIndices).size();
  return faceVaryingChannel<2>(t, [&](size_t corner, size_t point) {
    const size_t item = perCorner ? corner : point;
    return Uv{{st[2 * item], st[2 * item + 1]}};
  });
}

// The per-corner colour and opacity as one channel of 4 (white and opaque
// where one of the two is not authored).
using Rgba = Item<4>;
FaceVaryingChannel<4> colorChannel(const InlineMesh& mesh, const BaseTopology& t) {
  return faceVaryingChannel<4>(t, [&](size_t corner, size_t) {
    Rgba c{{1.0f, 1.0f, 1.0f, 1.0f}};
    if (mesh.displayColor)
      for (int k = 0; k < 3; ++k) c.v[k] = floatsOf(*mesh.displayColor)[3 * corner + size_t(k)];
    if (mesh.displayOpacity) c.v[3] = floatsOf(*mesh.displayOpacity)[corner];
    return c;
  });
}

// Refines a face-varying channel level by level and onto the limit.
template <int N>
std::vector<Item<N>> refineChannel(const Far::TopologyRefiner& refiner, const Far::PrimvarRefiner& primvars,
                                   const FaceVaryingChannel<N>& ch, int channel, int level) {
  std::vector<Item<N>> all(size_t(refiner.GetNumFVarValuesTotal(channel)));
  std::copy(ch.values.begin(), ch.values.end(), all.begin());
  Item<N>* src = all.data();
  for (int l = 1; l <= level; ++l) {
    Item<N>* dst = src + refiner.GetLevel(l - 1).GetNumFVarValues(channel);
    primvars.InterpolateFaceVarying(l, src, dst, channel);
    src = dst;
  }
  std::vector<Item<N>> limit(size_t(refiner.GetLevel(level).GetNumFVarValues(channel)));
  primvars.LimitFaceVarying(src, limit, channel);
  return limit;
}

// A crease chain of USD (creaseIndices split by creaseLengths, one
// sharpness per chain or per edge) as OpenSubdiv's edge pairs and weights.
void creaseEdges(const SubdivisionSurface& s, std::vector<Far::Index>& pairs, std::vector<float>& weights) {
  const auto indices = intsOf(s.creaseIndices);
  const auto lengths = intsOf(s.creaseLengths);
  const auto sharpness = floatsOf(s.creaseSharpnesses);
  const bool perCrease = sharpness.size() == lengths.size();
  size_t first = 0, edge = 0;
  for (size_t c = 0; c < lengths.size(); ++c) {
    for (int32_t k = 0; k + 1 < lengths[c]; ++k, ++edge) {
      pairs.push_back(indices[first + size_t(k)]);
      pairs.push_back(indices[first + size_t(k) + 1]);
      weights.push_back(perCrease ? sharpness[c] : sharpness[edge]);
    }
    first += size_t(lengths[c]);
  }
}

}  // namespace

std::string subdivisionProblem(const InlineMesh& mesh) {
  const SubdivisionSurface& s = mesh.subdivision;
  const size_t points = floatsOf(mesh.points).size() / 3;
  const auto counts = intsOf(mesh.faceVertexCounts);
  const auto lengths = intsOf(s.creaseLengths);
  const auto creaseIndices = intsOf(s.creaseIndices);
  size_t total = 0, edges = 0;
  for (size_t c = 0; c < lengths.size(); ++c) {
    if (lengths[c] < 2)
      return "creaseLengths[" + std::to_string(c) + "] is " + std::to_string(lengths[c]) +
             "; a crease runs through 2 points or more";
    total += size_t(lengths[c]);
    edges += size_t(lengths[c] - 1);
  }
  if (total != creaseIndices.size())
    return "creaseLengths add up to " + std::to_string(total) + " but creaseIndices has " +
           std::to_string(creaseIndices.size()) + " items";
  const size_t sharpnesses = floatsOf(s.creaseSharpnesses).size();
  if (!lengths.empty() && sharpnesses != lengths.size() && sharpnesses != edges)
    return "creaseSharpnesses has " + std::to_string(sharpnesses) + " items; expected one per crease (" +
           std::to_string(lengths.size()) + ") or one per crease edge (" + std::to_string(edges) + ")";
  const auto corners = intsOf(s.cornerIndices);
  if (floatsOf(s.cornerSharpnesses).size() != corners.size())
    return "cornerSharpnesses has " + std::to_string(floatsOf(s.cornerSharpnesses).size()) +
           " items; expected one per cornerIndices item (" + std::to_string(corners.size()) + ")";
  for (const auto& [name, list] : {std::pair{"creaseIndices", creaseIndices}, std::pair{"cornerIndices", corners}})
    for (size_t i = 0; i < list.size(); ++i)
      if (list[i] < 0 || size_t(list[i]) >= points)
        return std::string(name) + "[" + std::to_string(i) + "] is " + std::to_string(list[i]) + ", outside the " +
               std::to_string(points) + " points";
  if (s.scheme == "loop")
    for (size_t f = 0; f < counts.size(); ++f)
      if (counts[f] != 3 && counts[f] >= 3)
        return "subdivisionScheme loop refines triangles only; face " + std::to_string(f) + " has " +
               std::to_string(counts[f]) + " corners (use catmullClark, or render.subdivision_level none)";
  if (const double triangles = refinedTriangles(counts, s); triangles > double(kMaxMeshTriangles))
    return "render.subdivision_level " + std::to_string(s.level) + " refines it to " +
           std::to_string(uint64_t(triangles)) + " triangles, over the limit of " + std::to_string(kMaxMeshTriangles) +
           " per mesh; choose a lower level";
  return "";
}

InlineMesh refineSubdivisionSurface(const InlineMesh& mesh, const std::string& primPath) {
  if (std::string problem = subdivisionProblem(mesh); !problem.empty()) throw RunError(primPath + ": " + problem);
  const SubdivisionSurface& s = mesh.subdivision;
  const BaseTopology base = baseTopology(mesh);
  const auto points = floatsOf(mesh.points);
  const int pointCount = int(points.size() / 3);

  Far::TopologyDescriptor desc;
  desc.numVertices = pointCount;
  desc.numFaces = int(base.counts.size());
  desc.numVertsPerFace = base.counts.data();
  desc.vertIndicesPerFace = base.indices.data();
  std::vector<Far::Index> creasePairs;
  std::vector<float> creaseWeights;
  creaseEdges(s, creasePairs, creaseWeights);
  desc.numCreases = int(creaseWeights.size());
  desc.creaseVertexIndexPairs = creasePairs.data();
  desc.creaseWeights = creaseWeights.data();
  const auto corners = intsOf(s.cornerIndices);
  desc.numCorners = int(corners.size());
  desc.cornerVertexIndices = corners.data();
  desc.cornerWeights = floatsOf(s.cornerSharpnesses).data();
  std::vector<Far::Index> holes;
  for (int32_t f : intsOf(mesh.holeIndices))
    if (base.newFace[size_t(f)] >= 0) holes.push_back(base.newFace[size_t(f)]);
  desc.numHoles = int(holes.size());
  desc.holeIndices = holes.data();
  desc.isLeftHanded = mesh.leftHanded;
  const bool colored = mesh.displayColor || mesh.displayOpacity;
  FaceVaryingChannel<2> uv;
  FaceVaryingChannel<4> color;
  Far::TopologyDescriptor::FVarChannel channels[2];
  int uvIndex = -1, colorIndex = -1;
  if (mesh.st) {
    uv = uvChannel(mesh, base);
    uvIndex = desc.numFVarChannels++;
    channels[uvIndex].numValues = int(uv.values.size());
    channels[uvIndex].valueIndices = uv.valueOfCorner.data();
  }
  if (colored) {
    color = colorChannel(mesh, base);
    colorIndex = desc.numFVarChannels++;
    channels[colorIndex].numValues = int(color.values.size());
    channels[colorIndex].valueIndices = color.valueOfCorner.data();
  }
  desc.fvarChannels = channels;

  const Sdc::SchemeType type = s.scheme == "loop"       ? Sdc::SCHEME_LOOP
                               : s.scheme == "bilinear" ? Sdc::SCHEME_BILINEAR
                                                        : Sdc::SCHEME_CATMARK;
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  osdMessages.clear();
  Far::SetErrorCallback(&onOsdError);
  Far::SetWarningCallback(&onOsdWarning);
  std::unique_ptr<Far::TopologyRefiner> refiner(Factory::Create(desc, Factory::Options(type, sdcOptions(s))));
  if (!refiner) throw RunError(primPath + ": OpenSubdiv cannot refine this mesh: " + osdMessages);
  Far::TopologyRefiner::UniformOptions uniform(s.level);
  uniform.fullTopologyInLastLevel = true;  // the limit projection walks the last level's neighbourhoods
  refiner->RefineUniform(uniform);

  // Points level by level, then onto the limit surface.
  std::vector<Point> all(size_t(refiner->GetNumVerticesTotal()));
  for (int i = 0; i < pointCount; ++i) all[size_t(i)] = Point{{points[3 * size_t(i)], points[3 * size_t(i) + 1], points[3 * size_t(i) + 2]}};
  Far::PrimvarRefiner primvars(*refiner);
  Point* src = all.data();
  for (int level = 1; level <= s.level; ++level) {
    Point* dst = src + refiner->GetLevel(level - 1).GetNumVertices();
    primvars.Interpolate(level, src, dst);
    src = dst;
  }
  const Far::TopologyLevel& last = refiner->GetLevel(s.level);
  std::vector<Point> limit(size_t(last.GetNumVertices()));
  primvars.Limit(src, limit);

  std::vector<Uv> uvLimit;
  if (mesh.st) uvLimit = refineChannel(*refiner, primvars, uv, uvIndex, s.level);
  std::vector<Rgba> colorLimit;
  if (colored) colorLimit = refineChannel(*refiner, primvars, color, colorIndex, s.level);
  if (!osdMessages.empty()) throw RunError(primPath + ": OpenSubdiv cannot refine this mesh: " + osdMessages);

  std::vector<float> outPoints;
  outPoints.reserve(limit.size() * 3);
  for (const Point& p : limit) outPoints.insert(outPoints.end(), {p.v[0], p.v[1], p.v[2]});
  std::vector<int32_t> counts, indices;
  std::vector<float> st, rgb, opacity;
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    if (last.IsFaceHole(f)) continue;
    const Far::ConstIndexArray verts = last.GetFaceVertices(f);
    counts.push_back(verts.size());
    for (int k = 0; k < verts.size(); ++k) indices.push_back(verts[k]);
    if (mesh.st) {
      const Far::ConstIndexArray values = last.GetFaceFVarValues(f, uvIndex);
      for (int k = 0; k < values.size(); ++k) st.insert(st.end(), {uvLimit[size_t(values[k])].v[0], uvLimit[size_t(values[k])].v[1]});
    }
    if (colored) {
      const Far::ConstIndexArray values = last.GetFaceFVarValues(f, colorIndex);
      for (int k = 0; k < values.size(); ++k) {
        const Rgba& c = colorLimit[size_t(values[k])];
        rgb.insert(rgb.end(), {c.v[0], c.v[1], c.v[2]});
        opacity.push_back(c.v[3]);
      }
    }
  }
  InlineMesh out;
  out.points = Value::makeFloatArray(ValueType::Point3fArray, std::move(outPoints));
  out.faceVertexCounts = Value::makeIntArray(std::move(counts));
  out.faceVertexIndices = Value::makeIntArray(std::move(indices));
  if (mesh.st) out.st = Value::makeFloatArray(ValueType::TexCoord2fArray, std::move(st));
  if (mesh.displayColor) out.displayColor = Value::makeFloatArray(ValueType::Color3fArray, std::move(rgb));
  if (mesh.displayOpacity) out.displayOpacity = Value::makeFloatArray(ValueType::FloatArray, std::move(opacity));
  out.leftHanded = mesh.leftHanded;
  return out;
}

}  // namespace sdg
