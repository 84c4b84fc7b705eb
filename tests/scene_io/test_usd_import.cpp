// The USD mapping onto the stage (scene_io/usd_import.h) on the hand-written
// layers of tests/data/usd: every xform op form, units and up axis, inline
// meshes and their primvars, GeomSubsets, lights, cameras, time samples,
// inactive and instanceable prims.
#include <catch2/catch.hpp>

#include <cmath>

#include "assets/inline_mesh.h"
#include "assets/mesh_source.h"
#include "scene_io/scene_fixtures.h"
#include "scene_io/scene_writer.h"
#include "scene_io/usd_import.h"

namespace sdg {
namespace {

const std::string kDir = std::string(SDG_SOURCE_DIR) + "/tests/data/usd/";

Scene importFile(const std::string& name, UsdImportReport* out = nullptr) {
  UsdImportReport report;
  Scene scene = importUsdScene(kDir + name, test::testCatalog(), UsdImportOptions{}, report);
  if (out) *out = report;
  return scene;
}

Vec3d worldPoint(const Stage& stage, const std::string& path, const Vec3d& local) {
  const Matrix4d m = stage.worldMatrix(*stage.find(path));
  return (m * local.homogeneous()).head<3>();
}

bool near(const Vec3d& a, const Vec3d& b) { return (a - b).norm() < 1e-5; }

// World bounds of a geometry prim, from its triangulated mesh.
Eigen::AlignedBox3d worldBounds(const Stage& stage, const std::string& path) {
  const Prim& prim = *stage.find(path);
  MeshData mesh = meshDataFor(meshKeyOf(prim, stage.metadata().subdivisionLevel), AssetResolver{}, path);
  const Matrix4d m = stage.worldMatrix(prim);
  Eigen::AlignedBox3d box;
  for (const Vec3f& p : mesh.positions) box.extend((m * p.cast<double>().homogeneous()).head<3>());
  return box;
}

}  // namespace

TEST_CASE("usd import: a cube, a mesh, a camera and lights make a runnable scene", "[usd_import]") {
  Scene scene = importFile("cube_camera.usda");
  REQUIRE(scene.stage.find("/World/Box")->type() == PrimType::Cube);
  CHECK(scene.stage.find("/World/Box")->getDouble("size") == 1.0);
  CHECK(scene.stage.find("/World/Box")->value("primvars:displayColor")->get<Vec3f>().isApprox(Vec3f(0.8f, 0.2f, 0.2f)));
  CHECK(near(worldPoint(scene.stage, "/World/Box", Vec3d::Zero()), Vec3d(0, 0, 0.5)));
  const Prim& cam = *scene.stage.find("/World/Cam");
  CHECK(cam.type() == PrimType::Camera);
  CHECK(cam.getFloat("focalLength") == 35.0f);
  CHECK(cam.value("clippingRange")->get<Vec2f>().isApprox(Vec2f(0.1f, 100.0f)));
  CHECK(scene.stage.find("/World/Sun")->type() == PrimType::DistantLight);
  CHECK(scene.stage.find("/World/Sun")->getFloat("inputs:intensity") == 3000.0f);
  CHECK(scene.stage.find("/World/Sky")->type() == PrimType::DomeLight);
  // Defaults for what a USD stage does not say: the first camera, one writer.
  CHECK(scene.capture.get("cameras").get<std::vector<std::string>>() == std::vector<std::string>{"/World/Cam"});
  REQUIRE(scene.writers.size() == 1);
  CHECK(scene.writers[0].options.getBool("rgb"));
  // The ground is an inline mesh: two triangles spanning 6 x 6 m.
  const Prim& ground = *scene.stage.find("/World/Ground");
  REQUIRE(inlineMeshOf(ground, scene.stage.metadata().subdivisionLevel));
  MeshData mesh = meshDataFor(meshKeyOf(ground, scene.stage.metadata().subdivisionLevel), AssetResolver{}, ground.path());
  CHECK(mesh.triangleCount() == 2);
  CHECK(mesh.bounds.sizes().isApprox(Eigen::Vector3f(6, 6, 0)));
  CHECK(mesh.uvs[2].isApprox(Eigen::Vector2f(1, 1)));
  CHECK(mesh.normals[0].isApprox(Vec3f(0, 0, 1)));
}

TEST_CASE("usd import: a stage without camera or light gets a framing camera and lights", "[usd_import]") {
  Scene scene = importFile("no_camera.usda");
  // The cube: 1 m, standing on the ground 3 m along +X once Y-up cm is Z-up m.
  const Eigen::AlignedBox3d cube = worldBounds(scene.stage, "/Asset/Body");
  CHECK(cube.min().isApprox(Vec3d(2.5, -0.5, 0), 1e-9));
  CHECK(cube.max().isApprox(Vec3d(3.5, 0.5, 1), 1e-9));
  REQUIRE(scene.stage.find("/DefaultCamera_1"));  // the stage's own /DefaultCamera is an Xform
  CHECK(scene.stage.find("/DefaultCamera")->type() == PrimType::Xform);
  const Prim& cam = *scene.stage.find("/DefaultCamera_1");
  CHECK(cam.type() == PrimType::Camera);
  CHECK(scene.capture.get("cameras").get<std::vector<std::string>>() == std::vector<std::string>{"/DefaultCamera_1"});
  CHECK(scene.stage.find("/DefaultLight")->type() == PrimType::DistantLight);
  CHECK(scene.stage.find("/DefaultDome")->type() == PrimType::DomeLight);
  // 60 degrees across; looking at the cube's centre; every corner in view, in front of the near plane.
  const double tanHalf = std::tan(30.0 * 3.14159265358979323846 / 180.0);
  CHECK(cam.getFloat("horizontalAperture") / (2.0 * cam.getFloat("focalLength")) == Approx(tanHalf).epsilon(1e-6));
  const Matrix4d cameraFromWorld = scene.stage.worldMatrix(cam).inverse();
  const Vec3d centre = (cameraFromWorld * cube.center().homogeneous()).head<3>();
  CHECK(std::abs(centre.x()) < 1e-9);
  CHECK(std::abs(centre.y()) < 1e-9);
  const Vec2f clip = cam.value("clippingRange")->get<Vec2f>();
  for (int c = 0; c < 8; ++c) {
    const Vec3d p = (cameraFromWorld * cube.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)).homogeneous()).head<3>();
    CHECK(-p.z() > clip.x());
    CHECK(-p.z() < clip.y());
    CHECK(std::abs(p.x() / p.z()) < tanHalf);
    CHECK(std::abs(p.y() / p.z()) < tanHalf);  // square default resolution: the same field vertically
  }
  // Upright: the camera's up (+Y) has a positive world Z.
  CHECK(scene.stage.worldMatrix(cam)(2, 1) > 0.5);
}

TEST_CASE("usd import: a stage's own camera and lights are kept, nothing added", "[usd_import]") {
  Scene scene = importFile("cube_camera.usda");
  CHECK(!scene.stage.find("/DefaultCamera"));
  CHECK(!scene.stage.find("/DefaultLight"));
  CHECK(!scene.stage.find("/DefaultDome"));
}

TEST_CASE("usd import: every xform op form composes as USD does", "[usd_import]") {
  Scene scene = importFile("xform_ops.usda");
  const Stage& s = scene.stage;
  // orient: a quarter turn about Z takes +X to +Y.
  CHECK(near(worldPoint(s, "/Ops/Orient", Vec3d(1, 0, 0)), Vec3d(0, 1, 0)));
  // transform: USD's row-vector matrix, translation in the last row.
  CHECK(near(worldPoint(s, "/Ops/Matrix", Vec3d::Zero()), Vec3d(1, 2, 3)));
  // A pivot with !invert!: rotate 90 about (1, 0, 0); the pivot stays put.
  CHECK(near(worldPoint(s, "/Ops/Pivot", Vec3d(1, 0, 0)), Vec3d(1, 0, 0)));
  CHECK(near(worldPoint(s, "/Ops/Pivot", Vec3d(2, 0, 0)), Vec3d(1, 1, 0)));
  // !resetXformStack!: the parent's translate (5, 0, 0) no longer applies.
  CHECK(near(worldPoint(s, "/Ops/Parent/Reset", Vec3d::Zero()), Vec3d(0, 1, 0)));
  // Time samples at the stage's start time code (10).
  CHECK(near(worldPoint(s, "/Ops/Animated", Vec3d::Zero()), Vec3d(0, 0, 7)));
  // translate then scale: the scale applies first to a point.
  CHECK(near(worldPoint(s, "/Ops/Scaled", Vec3d(1, 0, 0)), Vec3d(3, 0, 0)));
  // Inactive prims and their subtrees are not on the stage.
  CHECK(s.find("/Ops/Inactive") == nullptr);
  CHECK(s.find("/Ops/Inactive/Hidden") == nullptr);
}

TEST_CASE("usd import: a Y-up centimetre asset stands upright at its size in a Z-up metre stage", "[usd_import]") {
  UsdImportReport report;
  Scene scene = importFile("room_zm.usda", &report);
  const Stage& s = scene.stage;
  // The chair is 40 x 80 x 40 cm, 80 cm tall along its Y: 0.8 m along Z here.
  Eigen::AlignedBox3d box = worldBounds(s, "/Room/Chair/Body");
  CHECK(box.sizes().isApprox(Eigen::Vector3d(0.4, 0.4, 0.8), 1e-5));
  CHECK(box.min().z() == Approx(0).margin(1e-6));
  CHECK(box.center().x() == Approx(2.0));
  // The instanceable reference is expanded like any other.
  Eigen::AlignedBox3d inst = worldBounds(s, "/Room/Instanced/Body");
  CHECK(inst.sizes().isApprox(Eigen::Vector3d(0.4, 0.4, 0.8), 1e-5));
  // The bound GeomSubset is a child mesh of its faces; the rest stays.
  const Prim* seat = s.find("/Room/Chair/Body/Seat");
  REQUIRE(seat);
  CHECK(seat->value("faceVertexCounts")->get<IntArray>().size() == 1);
  CHECK(s.find("/Room/Chair/Body")->value("faceVertexCounts")->get<IntArray>().size() == 5);
  // Indexed faceVarying st and uniform normals, expanded per face-vertex.
  CHECK(s.find("/Room/Chair/Body")->value("primvars:st")->get<FloatArray>().size() == 5 * 4 * 2);
  CHECK(s.find("/Room/Chair/Body")->value("normals")->get<FloatArray>().size() == 5 * 4 * 3);
  // Both layers are reported for the run's identity.
  CHECK(report.layers.size() == 2);
}

TEST_CASE("usd import: every light kind and an orthographic camera", "[usd_import]") {
  Scene scene = importFile("lights.usda");
  const Stage& s = scene.stage;
  CHECK(s.find("/Lights/Distant")->getFloat("inputs:angle") == 1.0f);
  CHECK(s.find("/Lights/Sphere")->getFloat("inputs:radius") == 0.25f);
  CHECK(s.find("/Lights/Sphere")->getBool("treatAsPoint"));
  CHECK(s.find("/Lights/Rect")->getFloat("inputs:height") == 3.0f);
  CHECK(s.find("/Lights/Disk")->getFloat("inputs:radius") == 0.75f);
  CHECK(s.find("/Lights/Cylinder")->getFloat("inputs:length") == 4.0f);
  // The old un-prefixed name of USD before 21.02.
  CHECK(s.find("/Lights/Dome")->getFloat("inputs:intensity") == 0.25f);
  CHECK(s.find("/Lights/Dome")->getFloat("inputs:exposure") == 1.0f);
  CHECK(s.find("/Lights/Ortho")->getString("projection") == "orthographic");
}

TEST_CASE("usd import: inline arrays survive the YAML writer and reader", "[usd_import]") {
  Scene scene = importFile("room_zm.usda");
  const std::string yaml = writeSceneYaml(scene, test::testCatalog());
  Scene again = test::loadText(yaml, test::testCatalog());
  CHECK(again.stage == scene.stage);
}

}  // namespace sdg
