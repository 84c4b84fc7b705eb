// The CPU halves of the renderer's draw path: how items group into
// instanced draws, where shadow maps look and what they may leave out. No GL
// context needed.
#include <catch2/catch.hpp>

#include "render/camera_math.h"
#include "render/raster/instance_batches.h"
#include "render/raster/shadow_casters.h"
#include "render/raster/shadow_frusta.h"

using namespace sdg;

namespace {

RenderItem item(uint32_t id, const std::string& texture = "", bool fromPrim = false, double x = 0) {
  RenderItem it;
  it.instanceId = id;
  it.material.maps.baseColor = texture;
  it.material.fromPrim = fromPrim;
  it.worldFromLocal(0, 3) = x;
  return it;
}

Vec3d clipToNdc(const Matrix4d& m, const Vec3d& p) {
  Eigen::Vector4d c = m * p.homogeneous();
  return c.head<3>() / c.w();
}

bool insideNdc(const Vec3d& ndc) { return (ndc.array().abs() <= 1.0 + 1e-9).all(); }

}  // namespace

TEST_CASE("instance batches: one run per mesh, in order of first appearance", "[render][batches]") {
  RenderList list;
  // Meshes (slots) 5, 2, 5, 7, 2: mesh 5 first, then 2, then 7.
  for (uint32_t id = 1; id <= 5; ++id) list.items.push_back(item(id));
  const std::vector<uint32_t> slots = {5, 2, 5, 7, 2};
  InstanceBatches batches;
  batches.build(list, slots);
  REQUIRE(batches.byMesh().size() == 3);
  CHECK(batches.byMesh()[0].meshSlot == 5);
  CHECK(batches.byMesh()[0].count == 2);
  CHECK(batches.byMesh()[1].meshSlot == 2);
  CHECK(batches.byMesh()[2].meshSlot == 7);
  // Within a mesh, items keep stage order; every item appears once.
  std::vector<uint32_t> ids;
  for (const InstanceRecord& r : batches.records()) ids.push_back(r.id);
  CHECK(ids == std::vector<uint32_t>{1, 3, 2, 5, 4});
  // Translation lands in the record's fourth column.
  list.items[2].worldFromLocal(0, 3) = 4.5;
  batches.build(list, slots);
  CHECK(batches.records()[1].worldFromLocal[12] == 4.5f);
}

TEST_CASE("instance batches: a material source or texture splits a mesh's run", "[render][batches]") {
  RenderList list;
  list.items = {item(1, "a.png", true), item(2, "", false), item(3, "a.png", true), item(4, "b.png", true)};
  InstanceBatches batches;
  batches.build(list, {0, 0, 0, 0});
  REQUIRE(batches.byMesh().size() == 1);
  CHECK(batches.byMesh()[0].count == 4);
  REQUIRE(batches.byMaterial().size() == 3);
  for (const InstanceBatch& b : batches.byMaterial())
    for (uint32_t k = b.first; k < b.first + b.count; ++k) {
      const RenderItem& it = list.items[batches.records()[k].id - 1];
      CHECK(it.material.maps == list.items[b.item].material.maps);
      CHECK(it.material.fromPrim == list.items[b.item].material.fromPrim);
    }
}

TEST_CASE("instance batches: the order does not depend on meshes loaded earlier", "[render][batches]") {
  // The same list with different slot numbers (a shard that loaded its
  // meshes in another order) draws in the same order.
  RenderList list;
  for (uint32_t id = 1; id <= 4; ++id) list.items.push_back(item(id));
  InstanceBatches a, b;
  a.build(list, {0, 1, 0, 1});
  b.build(list, {9, 3, 9, 3});
  REQUIRE(a.records().size() == b.records().size());
  for (size_t k = 0; k < a.records().size(); ++k) CHECK(a.records()[k].id == b.records()[k].id);
}

TEST_CASE("instance batches: coverage masks carry each group's bit", "[render][batches]") {
  RenderList list;
  for (uint32_t id = 1; id <= 6; ++id) list.items.push_back(item(id));
  const std::vector<std::vector<size_t>> groups = {{0, 1}, {2}, {3, 4}, {5}};
  InstanceBatches batches;
  batches.buildMasks(list, {0, 1, 0, 1, 0, 1}, groups, 1, 3);  // groups 1 and 2 only
  REQUIRE(batches.records().size() == 3);
  uint32_t bits = 0;
  for (const InstanceRecord& r : batches.records()) bits |= r.id;
  CHECK(bits == 0b11u);
}

TEST_CASE("shadow frusta: the visible region is the scene inside the camera's view", "[render][shadows]") {
  RenderCamera camera;  // at the origin looking down -Z, 50 mm on 20.955 mm
  camera.worldFromCamera(2, 3) = 10.0;
  camera.nearClip = 0.1f;
  camera.farClip = 1000.0f;
  Eigen::AlignedBox3d scene(Vec3d(-50, -50, -1), Vec3d(50, 50, 2));  // a 100 m floor
  Eigen::AlignedBox3d seen = visibleRegion(camera, 512, 512, scene);
  // At 11 m the view is 11 * 20.955 / 50 = 4.6 m wide: far less than 100 m.
  CHECK(seen.sizes().x() < 6.0);
  CHECK(seen.sizes().x() > 4.0);
  CHECK(seen.min().z() == Approx(-1.0));
  CHECK(scene.contains(seen));
  // Looking up, away from everything: the whole scene (nothing to fit).
  camera.worldFromCamera.block<3, 3>(0, 0) = Eigen::AngleAxisd(M_PI, Vec3d::UnitX()).toRotationMatrix();
  CHECK(visibleRegion(camera, 512, 512, scene).isApprox(scene));
}

TEST_CASE("shadow frusta: every receiver and caster is inside the light's map", "[render][shadows]") {
  const Eigen::AlignedBox3d scene(Vec3d(-20, -20, 0), Vec3d(20, 20, 6));
  const Eigen::AlignedBox3d receivers(Vec3d(-2, -1, 0), Vec3d(3, 2, 1.5));
  auto corners = [](const Eigen::AlignedBox3d& b) {
    std::vector<Vec3d> c;
    for (int i = 0; i < 8; ++i) c.push_back(b.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)));
    return c;
  };
  SECTION("distant light") {
    RenderLight sun;
    sun.kind = LightKind::Distant;
    sun.direction = Vec3d(0.3, 0.2, -1).normalized();
    const Matrix4d m = shadowViewProjection(sun, receivers, scene);
    for (const Vec3d& c : corners(receivers)) CHECK(insideNdc(clipToNdc(m, c)));
    // A caster high above the receivers along the light is inside too.
    CHECK(insideNdc(clipToNdc(m, receivers.center() - sun.direction * 5.0)));
    // The map spans the receivers, not the 40 m scene: a point 10 m to the
    // side is outside.
    CHECK_FALSE(insideNdc(clipToNdc(m, Vec3d(12, 0, 0.5))));
  }
  SECTION("sphere light outside the receivers") {
    RenderLight lamp;
    lamp.kind = LightKind::Sphere;
    lamp.position = Vec3d(0, 0, 4);
    const Matrix4d m = shadowViewProjection(lamp, receivers, scene);
    for (const Vec3d& c : corners(receivers)) CHECK(insideNdc(clipToNdc(m, c)));
    CHECK(insideNdc(clipToNdc(m, Vec3d(0.5, 0.5, 3.0))));  // a caster between lamp and floor
  }
  SECTION("sphere light among the receivers looks down") {
    RenderLight lamp;
    lamp.kind = LightKind::Sphere;
    lamp.position = Vec3d(0, 0, 1);
    const Matrix4d m = shadowViewProjection(lamp, receivers, scene);
    CHECK(insideNdc(clipToNdc(m, Vec3d(0.5, 0.2, 0))));
  }
}

namespace {

// A 2 x 2 plane in local XY (no thickness along Z), placed by `world`.
std::optional<FlatSurface> planeAt(const Eigen::Matrix4f& world) {
  return flatSurface(Eigen::AlignedBox3f(Eigen::Vector3f(-1, -1, 0), Eigen::Vector3f(1, 1, 0)), world.data());
}

RenderLight sunFrom(const Vec3d& towardLight) {
  RenderLight l;
  l.kind = LightKind::Distant;
  l.direction = -towardLight.normalized();
  return l;
}

RenderLight lampAt(const Vec3d& position, LightKind kind = LightKind::Sphere) {
  RenderLight l;
  l.kind = kind;
  l.position = position;
  return l;
}

Eigen::AlignedBox3d box(const Vec3d& low, const Vec3d& high) { return Eigen::AlignedBox3d(low, high); }

}  // namespace

TEST_CASE("shadow casters: only a mesh without thickness is flat, its plane placed by the transform",
          "[render][shadows]") {
  CHECK_FALSE(flatSurface(Eigen::AlignedBox3f(Eigen::Vector3f(-1, -1, -1), Eigen::Vector3f(1, 1, 1)),
                          Eigen::Matrix4f::Identity().eval().data()));
  // Turned 90 degrees about X and lifted: the local +Z normal becomes -Y.
  Eigen::Affine3f world = Eigen::Translation3f(0, 5, 2) * Eigen::AngleAxisf(float(M_PI / 2), Eigen::Vector3f::UnitX());
  const std::optional<FlatSurface> s = planeAt(world.matrix());
  REQUIRE(s);
  CHECK(s->point.isApprox(Vec3d(0, 5, 2)));
  CHECK(std::fabs(std::fabs(s->normal.y()) - 1.0) < 1e-6);
  // Squashed to nothing by its transform: no plane.
  Eigen::Matrix4f squashed = Eigen::Matrix4f::Identity();
  squashed(0, 0) = 0;
  CHECK_FALSE(planeAt(squashed));
}

TEST_CASE("shadow casters: a ground plane under everything shadows nothing, from above only", "[render][shadows]") {
  const FlatSurface floor = *planeAt(Eigen::Matrix4f::Identity());
  std::vector<Eigen::AlignedBox3d> items = {box({-1, -1, 0}, {1, 1, 0}),      // the floor itself
                                            box({0, 0, 0}, {0.5, 0.5, 0.5}),   // a box resting on it
                                            box({2, 2, 3}, {3, 3, 4})};        // one in the air
  CHECK(shadowsNothing(floor, sunFrom({0.3, 0, 1}), items, 1e-6));
  CHECK(shadowsNothing(floor, lampAt({0, 0, 5}), items, 1e-6));
  // Lit from below, the floor stands between the light and everything.
  CHECK_FALSE(shadowsNothing(floor, sunFrom({0, 0, -1}), items, 1e-6));
  CHECK_FALSE(shadowsNothing(floor, lampAt({0, 0, -2}), items, 1e-6));
  // A light in the plane itself, or a light without a shadow map.
  CHECK_FALSE(shadowsNothing(floor, sunFrom({1, 0, 0}), items, 1e-6));
  CHECK_FALSE(shadowsNothing(floor, lampAt({0, 0, 5}, LightKind::Rect), items, 1e-6));
  // Something reaching below the floor by more than the tolerance.
  items.push_back(box({4, 4, -0.01}, {5, 5, 1}));
  CHECK_FALSE(shadowsNothing(floor, sunFrom({0, 0, 1}), items, 1e-6));
  CHECK(shadowsNothing(floor, sunFrom({0, 0, 1}), items, 0.02));
}

TEST_CASE("shadow casters: a card above the ground shadows what lies under it", "[render][shadows]") {
  Eigen::Matrix4f lifted = Eigen::Matrix4f::Identity();
  lifted(2, 3) = 2;
  const FlatSurface card = *planeAt(lifted);
  const std::vector<Eigen::AlignedBox3d> items = {box({-10, -10, 0}, {10, 10, 0}), box({-1, -1, 2}, {1, 1, 2})};
  CHECK_FALSE(shadowsNothing(card, sunFrom({0, 0, 1}), items, 1e-6));
  CHECK_FALSE(shadowsNothing(card, lampAt({0, 0, 5}), items, 1e-6));
}
