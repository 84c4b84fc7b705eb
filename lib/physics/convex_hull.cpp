#include "physics/convex_hull.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <unordered_map>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace sdg {
namespace {

// qhull reports through a FILE*; a memory stream keeps its text for our
// message instead of letting it reach stderr.
class MemoryStream {
 public:
  MemoryStream() { file_ = open_memstream(&buffer_, &size_); }
  ~MemoryStream() {
    if (file_) std::fclose(file_);
    std::free(buffer_);
  }
  MemoryStream(const MemoryStream&) = delete;
  MemoryStream& operator=(const MemoryStream&) = delete;
  FILE* file() const { return file_; }
  std::string text() {
    if (file_) std::fflush(file_);
    return buffer_ ? std::string(buffer_, size_) : std::string();
  }

 private:
  FILE* file_ = nullptr;
  char* buffer_ = nullptr;
  size_t size_ = 0;
};

// Volume and centroid of the solid from the faces (a fan of tetrahedra from
// the first hull vertex, which is inside or on the hull).
void computeMassProperties(ConvexHull& hull) {
  auto point = [&](unsigned i) { return Vec3d(hull.points[3 * i], hull.points[3 * i + 1], hull.points[3 * i + 2]); };
  const Vec3d apex = point(0);
  double volume = 0;
  Vec3d moment = Vec3d::Zero();
  size_t at = 0;
  for (size_t f = 0; f < hull.faceCount; ++f) {
    unsigned count = hull.polygons[at];
    const unsigned* idx = &hull.polygons[at + 1];
    for (unsigned k = 1; k + 1 < count; ++k) {
      Vec3d a = point(idx[0]), b = point(idx[k]), c = point(idx[k + 1]);
      double v = (a - apex).dot((b - apex).cross(c - apex)) / 6.0;
      volume += v;
      moment += v * (apex + a + b + c) / 4.0;
    }
    at += count + 1;
  }
  hull.volume = volume;
  hull.centroid = volume > 0 ? Vec3d(moment / volume) : apex;
}

}  // namespace

std::optional<ConvexHull> computeConvexHull(std::span<const Vec3f> vertices, std::string* why) {
  auto fail = [&](std::string reason) -> std::optional<ConvexHull> {
    if (why) *why = std::move(reason);
    return std::nullopt;
  };
  if (vertices.size() < 4) return fail("fewer than 4 vertices");
  std::vector<coordT> coords;
  coords.reserve(vertices.size() * 3);
  for (const Vec3f& v : vertices)
    for (int k = 0; k < 3; ++k) coords.push_back(coordT(v[k]));

  MemoryStream errors;
  qhT qhData;
  qhT* qh = &qhData;
  qh_zero(qh, errors.file());
  // Plain "qhull": coplanar facets are merged, so a box has 6 faces.
  char command[] = "qhull";
  int exitCode = qh_new_qhull(qh, 3, int(vertices.size()), coords.data(), False, command, nullptr, errors.file());
  std::optional<ConvexHull> result;
  if (exitCode != 0) {
    std::string text = errors.text();
    size_t line = text.find('\n');
    result = fail("qhull: " + text.substr(0, line == std::string::npos ? text.size() : line));
  } else {
    ConvexHull hull;
    std::unordered_map<int, unsigned> indexOfPoint;
    vertexT* vertex;
    FORALLvertices {
      int id = qh_pointid(qh, vertex->point);
      indexOfPoint[id] = unsigned(hull.points.size() / 3);
      for (int k = 0; k < 3; ++k) hull.points.push_back(vertex->point[k]);
    }
    facetT* facet;
    FORALLfacets {
      setT* ordered = qh_facet3vertex(qh, facet);  // vertices in order around the face
      std::vector<unsigned> ring;
      vertexT** vertexp;
      FOREACHvertex_(ordered) ring.push_back(indexOfPoint[qh_pointid(qh, vertex->point)]);
      qh_settempfree(qh, &ordered);
      Vec3d normal(facet->normal[0], facet->normal[1], facet->normal[2]);
      // Newell's normal of the ring tells its winding; ODE wants it outward.
      Vec3d newell = Vec3d::Zero();
      for (size_t i = 0; i < ring.size(); ++i) {
        const double* p = &hull.points[3 * ring[i]];
        const double* q = &hull.points[3 * ring[(i + 1) % ring.size()]];
        newell += Vec3d((p[1] - q[1]) * (p[2] + q[2]), (p[2] - q[2]) * (p[0] + q[0]), (p[0] - q[0]) * (p[1] + q[1]));
      }
      if (newell.dot(normal) < 0) std::reverse(ring.begin(), ring.end());
      hull.planes.insert(hull.planes.end(), {normal.x(), normal.y(), normal.z(), -facet->offset});
      hull.polygons.push_back(unsigned(ring.size()));
      hull.polygons.insert(hull.polygons.end(), ring.begin(), ring.end());
      ++hull.faceCount;
    }
    computeMassProperties(hull);
    if (!(hull.volume > 0)) result = fail("the vertices span no volume");
    else result = std::move(hull);
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  return result;
}

}  // namespace sdg
