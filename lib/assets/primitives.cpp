#include "assets/primitives.h"

#include <cmath>
#include <numbers>

namespace sdg {

void MeshData::updateBounds() {
  bounds.setEmpty();
  for (const Vec3f& p : positions) bounds.extend(p);
}

namespace {
constexpr int kSegments = 48;  // around an axis
constexpr int kRings = 24;     // pole to pole
constexpr float kPi = std::numbers::pi_v<float>;

struct Builder {
  MeshData mesh;
  uint32_t vertex(const Vec3f& p, const Vec3f& n, float u, float v) {
    mesh.positions.push_back(p);
    mesh.normals.push_back(n.normalized());
    mesh.uvs.emplace_back(u, v);
    return static_cast<uint32_t>(mesh.positions.size() - 1);
  }
  void triangle(uint32_t a, uint32_t b, uint32_t c) { mesh.indices.insert(mesh.indices.end(), {a, b, c}); }
  void quad(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    triangle(a, b, c);
    triangle(a, c, d);
  }
  // Surface of revolution about +Z from a profile of (radius, z, normal r, normal z).
  void revolve(const std::vector<Eigen::Vector4f>& profile) {
    uint32_t start = static_cast<uint32_t>(mesh.positions.size());
    for (size_t i = 0; i < profile.size(); ++i)
      for (int s = 0; s <= kSegments; ++s) {
        float a = 2 * kPi * float(s) / kSegments;
        float c = std::cos(a), sn = std::sin(a);
        const Eigen::Vector4f& p = profile[i];
        vertex({p[0] * c, p[0] * sn, p[1]}, {p[2] * c, p[2] * sn, p[3]}, float(s) / kSegments,
               float(i) / float(profile.size() - 1));
      }
    for (size_t i = 0; i + 1 < profile.size(); ++i)
      for (int s = 0; s < kSegments; ++s) {
        uint32_t a = start + uint32_t(i * (kSegments + 1) + s), b = a + 1;
        uint32_t c = a + kSegments + 1, d = c + 1;
        quad(a, b, d, c);
      }
  }
  void disk(float radius, float z, bool up) {
    uint32_t centre = vertex({0, 0, z}, {0, 0, up ? 1.0f : -1.0f}, 0.5f, 0.5f);
    uint32_t first = static_cast<uint32_t>(mesh.positions.size());
    for (int s = 0; s <= kSegments; ++s) {
      float a = 2 * kPi * float(s) / kSegments;
      vertex({radius * std::cos(a), radius * std::sin(a), z}, {0, 0, up ? 1.0f : -1.0f}, 0.5f + 0.5f * std::cos(a),
             0.5f + 0.5f * std::sin(a));
    }
    for (int s = 0; s < kSegments; ++s) {
      if (up) triangle(centre, first + s, first + s + 1);
      else triangle(centre, first + s + 1, first + s);
    }
  }
  // Shapes are built along +Z; a cyclic permutation turns Z into the axis.
  MeshData finish(char axis) {
    auto permute = [axis](Vec3f& v) {
      if (axis == 'X') v = Vec3f(v.z(), v.x(), v.y());
      else if (axis == 'Y') v = Vec3f(v.y(), v.z(), v.x());
    };
    for (Vec3f& p : mesh.positions) permute(p);
    for (Vec3f& n : mesh.normals) permute(n);
    MeshPart whole;
    whole.indexCount = static_cast<uint32_t>(mesh.indices.size());
    mesh.parts = {whole};
    mesh.updateBounds();
    return std::move(mesh);
  }
};

}  // namespace

MeshData makeCube(double size) {
  Builder b;
  const float h = float(size) / 2;
  const Vec3f normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const Vec3f& n : normals) {
    // Two tangents spanning the face, right-handed with n.
    Vec3f t1 = std::fabs(n.z()) > 0.5f ? Vec3f(1, 0, 0) : Vec3f(0, 0, 1);
    Vec3f t2 = n.cross(t1);
    t1 = t2.cross(n);
    uint32_t a = b.vertex(h * (n - t1 - t2), n, 0, 0);
    uint32_t c = b.vertex(h * (n + t1 - t2), n, 1, 0);
    uint32_t d = b.vertex(h * (n + t1 + t2), n, 1, 1);
    uint32_t e = b.vertex(h * (n - t1 + t2), n, 0, 1);
    b.quad(a, c, d, e);
  }
  return b.finish('Z');
}

MeshData makeSphere(double radius) {
  Builder b;
  std::vector<Eigen::Vector4f> profile;
  for (int i = 0; i <= kRings; ++i) {
    float polar = -kPi / 2 + kPi * float(i) / kRings;
    float r = std::cos(polar), z = std::sin(polar);
    profile.emplace_back(float(radius) * r, float(radius) * z, r, z);
  }
  b.revolve(profile);
  return b.finish('Z');
}

MeshData makeCylinder(double radius, double height, char axis) {
  Builder b;
  float r = float(radius), h = float(height) / 2;
  b.revolve({{r, -h, 1, 0}, {r, h, 1, 0}});
  b.disk(r, h, true);
  b.disk(r, -h, false);
  return b.finish(axis);
}

MeshData makeCone(double radius, double height, char axis) {
  Builder b;
  float r = float(radius), h = float(height) / 2;
  // The side normal leans up by the slope of the cone.
  Vec3f n = Vec3f(float(height), 0, r).normalized();
  b.revolve({{r, -h, n.x(), n.z()}, {0, h, n.x(), n.z()}});
  b.disk(r, -h, false);
  return b.finish(axis);
}

MeshData makeCapsule(double radius, double height, char axis) {
  Builder b;
  float r = float(radius), h = float(height) / 2;
  std::vector<Eigen::Vector4f> profile;
  for (int i = 0; i <= kRings / 2; ++i) {  // bottom cap: south pole to equator
    float polar = -kPi / 2 + (kPi / 2) * float(i) / (kRings / 2);
    profile.emplace_back(r * std::cos(polar), -h + r * std::sin(polar), std::cos(polar), std::sin(polar));
  }
  for (int i = 0; i <= kRings / 2; ++i) {  // top cap: equator to north pole
    float polar = (kPi / 2) * float(i) / (kRings / 2);
    profile.emplace_back(r * std::cos(polar), h + r * std::sin(polar), std::cos(polar), std::sin(polar));
  }
  b.revolve(profile);
  return b.finish(axis);
}

MeshData makePlane(double width, double length, char axis) {
  Builder b;
  float w = float(width) / 2, l = float(length) / 2;
  // Built in XY with +Z normal, then mapped: X -> (Y, Z), Y -> (X, Z).
  Vec3f n(0, 0, 1);
  uint32_t a = b.vertex({-w, -l, 0}, n, 0, 0);
  uint32_t c = b.vertex({w, -l, 0}, n, 1, 0);
  uint32_t d = b.vertex({w, l, 0}, n, 1, 1);
  uint32_t e = b.vertex({-w, l, 0}, n, 0, 1);
  b.quad(a, c, d, e);
  if (axis == 'Y') {
    // (x, y, z) -> (x, z, -y) keeps width on X, length on Z and a +Y normal.
    for (Vec3f& p : b.mesh.positions) p = Vec3f(p.x(), p.z(), -p.y());
    for (Vec3f& q : b.mesh.normals) q = Vec3f(q.x(), q.z(), -q.y());
    return b.finish('Z');
  }
  return b.finish(axis == 'X' ? 'X' : 'Z');
}

}  // namespace sdg
