#pragma once
// Convex hulls of mesh vertices (qhull), in the form ODE's convex collider
// takes: outward planes, the hull's vertices, and one polygon per face with
// its vertices counter-clockwise seen from outside. Coplanar triangles are
// merged into one face, which gives the SAT tests fewer, better contacts.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "stage/math_types.h"

namespace sdg {

struct ConvexHull {
  std::vector<double> planes;        // nx, ny, nz, d per face: n . x = d
  std::vector<double> points;        // x, y, z per hull vertex
  std::vector<unsigned> polygons;    // count, i0, i1, ... per face
  size_t faceCount = 0;
  double volume = 0;
  Vec3d centroid = Vec3d::Zero();    // of the solid

  size_t pointCount() const { return points.size() / 3; }
};

// The hull of `vertices`, or nullopt (with `why` set) when they are flat,
// collinear, too few or otherwise span no volume.
std::optional<ConvexHull> computeConvexHull(std::span<const Vec3f> vertices, std::string* why = nullptr);

}  // namespace sdg
