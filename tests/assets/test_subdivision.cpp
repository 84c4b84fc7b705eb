// Subdivision surfaces refined with OpenSubdiv (assets/subdivision.h): the
// counts of uniform refinement, points on Catmull-Clark's limit surface
// (inside the cage, a cube's corners where the limit masks put them),
// infinitely sharp creases and corners that keep a cage edge, holes, Loop on
// a tetrahedron, face-varying texture coordinates, and the cage kept at
// level 0.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <ctime>

#include "assets/inline_mesh.h"
#include "assets/subdivision.h"
#include "core/diagnostics.h"

using namespace sdg;

namespace {

InlineMesh meshOf(std::vector<float> points, std::vector<int32_t> counts, std::vector<int32_t> indices,
                  const std::string& scheme, int level) {
  InlineMesh m;
  m.points = Value::makeFloatArray(ValueType::Point3fArray, std::move(points));
  m.faceVertexCounts = Value::makeIntArray(std::move(counts));
  m.faceVertexIndices = Value::makeIntArray(std::move(indices));
  m.subdivision.scheme = scheme;
  m.subdivision.level = level;
  return m;
}

// The cube [-1, 1]^3, faces wound counter-clockwise seen from outside.
InlineMesh cube(int level) {
  return meshOf({-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1},
                {4, 4, 4, 4, 4, 4},
                {0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7}, "catmullClark", level);
}

std::vector<Vec3f> pointsOf(const InlineMesh& m) {
  const auto& a = m.points.get<FloatArray>();
  std::vector<Vec3f> out;
  for (size_t i = 0; i + 2 < a.size(); i += 3) out.emplace_back(a[i], a[i + 1], a[i + 2]);
  return out;
}

// The refined point nearest `p`.
Vec3f nearest(const std::vector<Vec3f>& points, const Vec3f& p) {
  Vec3f best = points.front();
  for (const Vec3f& q : points)
    if ((q - p).norm() < (best - p).norm()) best = q;
  return best;
}

}  // namespace

TEST_CASE("subdivision: a Catmull-Clark cube at level 2 has 96 quads on the limit surface inside its cage", "[subdivision]") {
  const InlineMesh refined = refineSubdivisionSurface(cube(2), "/Cube");
  const auto counts = refined.faceVertexCounts.get<IntArray>().items();
  CHECK(counts.size() == 96);  // 6 faces x 4 x 4
  for (int32_t c : counts) CHECK(c == 4);
  const std::vector<Vec3f> points = pointsOf(refined);
  CHECK(points.size() == 98);  // 8 + 12 + 6 at level 1 (26), + 48 edges + 24 faces
  // The limit surface lies inside the convex hull of its cage.
  for (const Vec3f& p : points) CHECK(p.cwiseAbs().maxCoeff() <= 1.0f + 1e-6f);
  // A cube corner of valence 3 goes to (n^2 v + 4 sum(edge neighbours) +
  // sum(face diagonals)) / (n (n + 5)) = (9 + 4 - 1) / 24 = 0.5 per axis.
  CHECK(nearest(points, Vec3f(1, 1, 1)).isApprox(Vec3f(0.5f, 0.5f, 0.5f), 1e-5f));
  CHECK(nearest(points, Vec3f(-1, 1, -1)).isApprox(Vec3f(-0.5f, 0.5f, -0.5f), 1e-5f));
  // Deeper refinement approaches the same limit: level 6's corner point,
  // projected too, agrees; the surface keeps the cube's symmetry.
  const std::vector<Vec3f> fine = pointsOf(refineSubdivisionSurface(cube(6), "/Cube"));
  CHECK(nearest(fine, Vec3f(1, 1, 1)).isApprox(Vec3f(0.5f, 0.5f, 0.5f), 1e-5f));
  const Vec3f faceCentre = nearest(points, Vec3f(0, 0, 2));
  CHECK(faceCentre.head<2>().norm() < 1e-6f);
  CHECK(faceCentre.z() > 0.5f);
  CHECK(faceCentre.z() < 1.0f);

  // Triangulated: 192 triangles with smooth normals pointing outwards.
  const MeshData mesh = triangulateInlineMesh(cube(2), "/Cube");
  CHECK(mesh.triangleCount() == 192);
  for (size_t i = 0; i < mesh.positions.size(); ++i) CHECK(mesh.normals[i].dot(mesh.positions[i]) > 0.0f);
}

TEST_CASE("subdivision: level 0 draws the authored cage", "[subdivision]") {
  const MeshData mesh = triangulateInlineMesh(cube(0), "/Cube");
  CHECK(mesh.triangleCount() == 12);
  for (const Vec3f& p : mesh.positions) CHECK(p.cwiseAbs().isApprox(Vec3f(1, 1, 1)));
}

TEST_CASE("subdivision: infinitely sharp creases and corners keep the cage's edges", "[subdivision]") {
  InlineMesh creased = cube(2);
  // The top face's four edges, one closed chain, and its corners: sharpness
  // 10 is OpenSubdiv's (and USD's) infinitely sharp.
  creased.subdivision.creaseIndices = Value::makeIntArray({4, 5, 6, 7, 4});
  creased.subdivision.creaseLengths = Value::makeIntArray({5});
  creased.subdivision.creaseSharpnesses = Value::makeFloatArray(ValueType::FloatArray, {10});
  creased.subdivision.cornerIndices = Value::makeIntArray({4, 5, 6, 7});
  creased.subdivision.cornerSharpnesses = Value::makeFloatArray(ValueType::FloatArray, {10, 10, 10, 10});
  const std::vector<Vec3f> points = pointsOf(refineSubdivisionSurface(creased, "/Cube"));
  // The creased edges stay straight on the cage's top edges, which
  // separates the top face from the sides: it stays the flat square.
  size_t onTop = 0, onEdges = 0;
  for (const Vec3f& p : points) {
    if (std::abs(p.z() - 1.0f) > 1e-5f) continue;
    ++onTop;
    onEdges += std::abs(std::abs(p.x()) - 1.0f) < 1e-5f || std::abs(std::abs(p.y()) - 1.0f) < 1e-5f;
  }
  CHECK(onTop == 25);    // the top face's 5 x 5 points at level 2
  CHECK(onEdges == 16);  // 4 edges of 5 points, corners shared
  // Each creased edge's points are evenly spread along it, as on the cage.
  for (float x : {-1.0f, -0.5f, 0.0f, 0.5f, 1.0f}) CHECK(nearest(points, Vec3f(x, 1, 1)).isApprox(Vec3f(x, 1, 1), 1e-5f));
  CHECK(nearest(points, Vec3f(1, 1, 1)).isApprox(Vec3f(1, 1, 1)));
  // Without the tags the same corner is rounded off.
  CHECK(nearest(pointsOf(refineSubdivisionSurface(cube(2), "/Cube")), Vec3f(1, 1, 1)).z() < 0.6f);

  // One sharpness per edge works as well as one per crease.
  creased.subdivision.creaseSharpnesses = Value::makeFloatArray(ValueType::FloatArray, {10, 10, 10, 10});
  CHECK(subdivisionProblem(creased).empty());
  creased.subdivision.creaseSharpnesses = Value::makeFloatArray(ValueType::FloatArray, {10, 10});
  CHECK(subdivisionProblem(creased) ==
        "creaseSharpnesses has 2 items; expected one per crease (1) or one per crease edge (4)");
  creased.subdivision.creaseLengths = Value::makeIntArray({4});
  CHECK(subdivisionProblem(creased) == "creaseLengths add up to 4 but creaseIndices has 5 items");
  CHECK_THROWS_WITH(triangulateInlineMesh(creased, "/Cube"),
                    "/Cube: creaseLengths add up to 4 but creaseIndices has 5 items");
}

TEST_CASE("subdivision: holes remove their faces, refined or not", "[subdivision]") {
  InlineMesh holed = cube(2);
  holed.holeIndices = Value::makeIntArray({0, 3});
  CHECK(refineSubdivisionSurface(holed, "/Cube").faceVertexCounts.get<IntArray>().size() == 64);  // 96 - 2 x 16
  CHECK(triangulateInlineMesh(holed, "/Cube").triangleCount() == 128);
  holed.subdivision.level = 0;
  CHECK(triangulateInlineMesh(holed, "/Cube").triangleCount() == 8);
  holed.holeIndices = Value::makeIntArray({6});
  CHECK(inlineMeshProblem(holed) == "holeIndices[0] is 6, outside the 6 faces");
}

TEST_CASE("subdivision: Loop refines a tetrahedron into triangles inside it", "[subdivision]") {
  // A regular tetrahedron; every face counter-clockwise from outside.
  InlineMesh tet = meshOf({1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1}, {3, 3, 3, 3},
                          {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2}, "loop", 2);
  const InlineMesh refined = refineSubdivisionSurface(tet, "/Tet");
  const auto counts = refined.faceVertexCounts.get<IntArray>().items();
  CHECK(counts.size() == 64);
  for (int32_t c : counts) CHECK(c == 3);
  const std::vector<Vec3f> points = pointsOf(refined);
  CHECK(points.size() == 34);  // 4 + 6 at level 1, + 24 edges
  // Inside the tetrahedron: behind each face's plane (normals outwards).
  const std::vector<Vec3f> cage = pointsOf(tet);
  const auto indices = tet.faceVertexIndices.get<IntArray>().items();
  for (size_t f = 0; f < 4; ++f) {
    const Vec3f a = cage[size_t(indices[3 * f])], b = cage[size_t(indices[3 * f + 1])], c = cage[size_t(indices[3 * f + 2])];
    const Vec3f n = (b - a).cross(c - a).normalized();
    for (const Vec3f& p : points) CHECK(n.dot(p - a) < 1e-5f);
  }
  // By symmetry the refined surface stays centred on the origin.
  Vec3f centre = Vec3f::Zero();
  for (const Vec3f& p : points) centre += p / float(points.size());
  CHECK(centre.norm() < 1e-5f);
  CHECK(triangulateInlineMesh(tet, "/Tet").triangleCount() == 64);

  // Loop refines triangles only: a quad is a problem, named.
  InlineMesh quadLoop = cube(2);
  quadLoop.subdivision.scheme = "loop";
  CHECK(subdivisionProblem(quadLoop) ==
        "subdivisionScheme loop refines triangles only; face 0 has 4 corners (use catmullClark, or "
        "render.subdivision_level none)");
}

TEST_CASE("subdivision: bilinear keeps the cube's faces flat", "[subdivision]") {
  InlineMesh box = cube(2);
  box.subdivision.scheme = "bilinear";
  const std::vector<Vec3f> points = pointsOf(refineSubdivisionSurface(box, "/Cube"));
  CHECK(points.size() == 98);
  for (const Vec3f& p : points) CHECK(p.cwiseAbs().maxCoeff() == Approx(1.0f));
}

TEST_CASE("subdivision: texture coordinates refine as face-varying data, seams and all", "[subdivision]") {
  // A 3 x 3 grid of quads over [-1, 1]^2, st = (x + 1) / 2, (y + 1) / 2
  // written per face-vertex (as the USD import writes every primvar).
  std::vector<float> points;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) points.insert(points.end(), {-1 + 2 * float(i) / 3, -1 + 2 * float(j) / 3, 0});
  std::vector<int32_t> counts, indices;
  std::vector<float> st;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      counts.push_back(4);
      for (int corner : {j * 4 + i, j * 4 + i + 1, (j + 1) * 4 + i + 1, (j + 1) * 4 + i}) {
        indices.push_back(corner);
        st.insert(st.end(), {(points[3 * size_t(corner)] + 1) / 2, (points[3 * size_t(corner) + 1] + 1) / 2});
      }
    }
  InlineMesh grid = meshOf(points, counts, indices, "catmullClark", 2);
  grid.st = Value::makeFloatArray(ValueType::TexCoord2fArray, st);
  // The same rules for points and st: st stays the same affine function of
  // the position, which holds only if the corners sharing a point and a
  // value were joined (each face on its own would bend at every edge).
  grid.subdivision.interpolateBoundary = "edgeOnly";
  grid.subdivision.faceVaryingLinearInterpolation = "none";
  const InlineMesh refined = refineSubdivisionSurface(grid, "/Grid");
  const std::vector<Vec3f> out = pointsOf(refined);
  const auto outIndices = refined.faceVertexIndices.get<IntArray>().items();
  const auto& outSt = refined.st->get<FloatArray>();
  REQUIRE(outSt.size() == 2 * outIndices.size());
  for (size_t c = 0; c < outIndices.size(); ++c) {
    const Vec3f& p = out[size_t(outIndices[c])];
    CHECK(outSt[2 * c] == Approx((p.x() + 1) / 2).margin(1e-5));
    CHECK(outSt[2 * c + 1] == Approx((p.y() + 1) / 2).margin(1e-5));
  }
  // A seam: the grid's middle column of faces mapped elsewhere in st keeps
  // its own values along the seam (corners of one point, two st values).
  for (size_t f = 1; f < 9; f += 3)
    for (size_t k = 0; k < 4; ++k) st[2 * (4 * f + k)] += 5.0f;
  grid.st = Value::makeFloatArray(ValueType::TexCoord2fArray, st);
  const InlineMesh seamed = refineSubdivisionSurface(grid, "/Grid");
  size_t shifted = 0;
  const auto& seamSt = seamed.st->get<FloatArray>();
  for (size_t c = 0; c < seamSt.size() / 2; ++c) shifted += seamSt[2 * c] > 2.0f;
  CHECK(shifted == seamSt.size() / 2 / 3);  // exactly the middle column's corners
}

TEST_CASE("subdivision: the refinement's size is limited before it runs", "[subdivision]") {
  InlineMesh big = cube(6);
  std::vector<int32_t> counts(200000, 4), indices;
  for (size_t f = 0; f < counts.size(); ++f) indices.insert(indices.end(), {0, 1, 2, 3});
  big.faceVertexCounts = Value::makeIntArray(counts);
  big.faceVertexIndices = Value::makeIntArray(indices);
  CHECK(subdivisionProblem(big) ==
        "render.subdivision_level 6 refines it to 1638400000 triangles, over the limit of 50000000 per mesh; "
        "choose a lower level");
}

// Not run by default (hidden tag): the refinement's cost on a large mesh,
// for docs/rendering.md. sdg_unit_tests "[subdivision-bench]"
TEST_CASE("subdivision: time to refine a 102,400-quad torus", "[.][subdivision-bench]") {
  const int ring = 320, tube = 320;
  std::vector<float> points;
  for (int i = 0; i < ring; ++i)
    for (int j = 0; j < tube; ++j) {
      const double u = 2 * M_PI * i / ring, v = 2 * M_PI * j / tube;
      points.insert(points.end(), {float((2 + std::cos(v)) * std::cos(u)), float((2 + std::cos(v)) * std::sin(u)),
                                   float(std::sin(v))});
    }
  std::vector<int32_t> counts, indices;
  for (int i = 0; i < ring; ++i)
    for (int j = 0; j < tube; ++j) {
      const int a = i * tube + j, b = ((i + 1) % ring) * tube + j, c = ((i + 1) % ring) * tube + (j + 1) % tube,
                d = i * tube + (j + 1) % tube;
      counts.push_back(4);
      indices.insert(indices.end(), {a, b, c, d});
    }
  for (int level : {1, 2, 3}) {
    // Processor time as well as wall time: the second says what a loaded machine added.
    const InlineMesh torus = meshOf(points, counts, indices, "catmullClark", level);
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpuStart = std::clock();
    const InlineMesh refined = refineSubdivisionSurface(torus, "/Torus");
    const std::clock_t cpuRefined = std::clock();
    const auto refinedAt = std::chrono::steady_clock::now();
    const MeshData mesh = triangulateInlineMesh(torus, "/Torus");
    const std::clock_t cpuEnd = std::clock();
    const auto end = std::chrono::steady_clock::now();
    WARN("level " << level << ": " << refined.faceVertexCounts.get<IntArray>().size() << " quads; refined in "
                  << double(cpuRefined - cpuStart) / CLOCKS_PER_SEC << " s processor ("
                  << std::chrono::duration<double>(refinedAt - start).count() << " s wall); refined and triangulated ("
                  << mesh.triangleCount() << " triangles) in " << double(cpuEnd - cpuRefined) / CLOCKS_PER_SEC
                  << " s processor (" << std::chrono::duration<double>(end - refinedAt).count() << " s wall)");
    CHECK(mesh.triangleCount() == 2 * refined.faceVertexCounts.get<IntArray>().size());
    WARN("level " << level << ": " << refined.faceVertexCounts.get<IntArray>().size() << " quads refined in "
                  << std::chrono::duration<double>(refinedAt - start).count() << " s; refined and triangulated ("
                  << mesh.triangleCount() << " triangles) in " << std::chrono::duration<double>(end - refinedAt).count()
                  << " s");
  }
}
