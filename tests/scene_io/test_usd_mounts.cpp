// USD files in YAML scenes (tests/data/usd/mounts.yaml): `reference:` mounts
// a USD prim and its subtree like a smart asset (units corrected, labels and
// materials imported, variant selections from the reference or --set),
// local overrides apply on top, and `asset: x.usda` on a Mesh reads the
// file's Mesh prims as the mesh asset.
#include <catch2/catch.hpp>

#include <filesystem>

#include "assets/mesh_source.h"
#include "run/scene_setup.h"
#include "scene_io/scene_fixtures.h"
#include "scene_io/usd_mesh_asset.h"

namespace sdg {
namespace {

const std::string kDir = std::string(SDG_SOURCE_DIR) + "/tests/data/usd/";

LoadedScene loadMounts(const std::vector<std::string>& overrides = {}) {
  return loadSceneForRun(SceneRequest{.scenePath = kDir + "mounts.yaml", .overrides = overrides});
}

Eigen::AlignedBox3d worldBounds(const LoadedScene& loaded, const std::string& path) {
  const Prim& prim = *loaded.scene.stage.find(path);
  MeshData mesh = meshDataFor(meshKeyOf(prim, loaded.scene.stage.metadata().subdivisionLevel), loaded.assets, path);
  const Matrix4d m = loaded.scene.stage.worldMatrix(prim);
  Eigen::AlignedBox3d box;
  for (const Vec3f& p : mesh.positions) box.extend((m * p.cast<double>().homogeneous()).head<3>());
  return box;
}

bool near(const Vec3d& a, const Vec3d& b) { return (a - b).norm() < 1e-5; }

std::string loadError(const std::string& yaml, const std::vector<std::string>& overrides = {}) {
  return test::errorsOf(yaml, test::testCatalog(), overrides);
}

}  // namespace

TEST_CASE("usd mounts: a Y-up centimetre chair stands upright at its size, with the scene's overrides",
          "[usd_import][mounts]") {
  const LoadedScene loaded = loadMounts();
  const Stage& stage = loaded.scene.stage;
  REQUIRE(stage.find("/World/Chair/Body"));
  // 40 x 80 x 40 cm, Y up, translated by the scene: 0.4 m wide, 0.8 m tall, at x = 2.
  const Eigen::AlignedBox3d chair = worldBounds(loaded, "/World/Chair/Body");
  CHECK(near(chair.min(), Vec3d(1.8, -0.2, 0.0)));
  CHECK(near(chair.max(), Vec3d(2.2, 0.2, 0.8)));
  const Prim& body = *stage.find("/World/Chair/Body");
  CHECK(body.value("primvars:displayColor")->get<Vec3f>().isApprox(Vec3f(0.1f, 0.8f, 0.1f)));
  CHECK(body.semantics().at("class") == std::vector<std::string>{"chair"});
  // The GeomSubset's faces, a Mesh of their own (its Material has no shader: no binding).
  CHECK(stage.find("/World/Chair/Body/Seat") != nullptr);
  CHECK(stage.find("/World/Chair/Looks/Red") != nullptr);
  // The USD layers are part of the run's identity.
  CHECK(std::find(loaded.mountedFiles.begin(), loaded.mountedFiles.end(), kDir + "chair_ycm.usda") !=
        loaded.mountedFiles.end());
}

TEST_CASE("usd mounts: a named prim, its labels, its material, and a child's transform override",
          "[usd_import][mounts]") {
  const LoadedScene loaded = loadMounts();
  const Stage& stage = loaded.scene.stage;
  const Prim& shade = *stage.find("/World/Lamp/Shade");
  CHECK(shade.semantics().at("class") == std::vector<std::string>{"lamp_shade"});
  CHECK(shade.material()->path == "/World/Lamp/Looks/Red");
  const Prim& red = *stage.find("/World/Lamp/Looks/Red");
  CHECK(red.value("inputs:diffuse_color_constant")->get<Vec3f>().isApprox(Vec3f(0.9f, 0.1f, 0.1f)));
  CHECK(red.getFloat("inputs:reflection_roughness_constant") == Approx(0.1));  // the reference's variant: gloss
  const Prim& post = *stage.find("/World/Lamp/Post");
  REQUIRE(post.xformOps().size() == 1);
  CHECK(near(post.xformOps()[0].value.get<Vec3d>(), Vec3d(0.0, 0.3, 0.0)));
}

TEST_CASE("usd mounts: --set chooses a variant of a mounted prim by its path in the scene", "[usd_import][mounts]") {
  const LoadedScene matte = loadMounts({"/World/Lamp.variants:finish=matte"});
  CHECK(matte.scene.stage.find("/World/Lamp/Looks/Red")->getFloat("inputs:reflection_roughness_constant") ==
        Approx(0.9));
  // A prim that no USD reference brought: the selection has nothing to apply to.
  CHECK_THROWS_WITH(loadMounts({"/World/Cam.variants:finish=matte"}),
                    Catch::Contains("--set[1]:1:1") &&
                        Catch::Contains("/World/Cam is not a prim of a USD file the scene mounts"));
  CHECK_THROWS_WITH(loadMounts({"/World/Lamp.variants:finish=shiny"}),
                    Catch::Contains("variant set 'finish' has no variant 'shiny'"));
}

TEST_CASE("usd mounts: a USD file as a Mesh's asset, whole or one prim's subtree", "[usd_import][mounts]") {
  const LoadedScene loaded = loadMounts();
  const Prim& lamp = *loaded.scene.stage.find("/World/LampMesh");
  const MeshData mesh = meshDataFor(meshKeyOf(lamp, loaded.scene.stage.metadata().subdivisionLevel), loaded.assets, lamp.path());
  CHECK(mesh.triangleCount() == 6);  // the shade's 4 and the post's quad
  REQUIRE(mesh.parts.size() == 2);
  CHECK(mesh.parts[0].baseColor.isApprox(Vec3f(0.9f, 0.1f, 0.1f)));  // the shade's bound material
  CHECK(mesh.parts[1].baseColor.isApprox(Vec3f(0.2f, 0.2f, 0.2f)));  // the post's displayColor
  CHECK(mesh.bounds.max().z() == Approx(1.6f));
  CHECK(mesh.bounds.max().y() == Approx(0.5f));
  CHECK(mesh.bounds.min().y() == Approx(-0.5f));
  const Eigen::AlignedBox3d placed = worldBounds(loaded, "/World/LampMesh");
  CHECK(near(placed.min(), Vec3d(-2.5, -0.5, 0.0)));
  const Prim& shade = *loaded.scene.stage.find("/World/ShadeOnly");
  CHECK(meshDataFor(meshKeyOf(shade, loaded.scene.stage.metadata().subdivisionLevel), loaded.assets, shade.path()).triangleCount() == 4);
  // A Y-up centimetre file comes out in Z-up metres; its GeomSubset is a part of its own.
  const MeshData chair = loadUsdMeshAsset(kDir + "chair_ycm.usda", "");
  CHECK(chair.triangleCount() == 12);
  CHECK(chair.parts.size() == 2);
  CHECK(near(chair.bounds.min().cast<double>(), Vec3d(-0.2, -0.2, 0.0)));
  CHECK(near(chair.bounds.max().cast<double>(), Vec3d(0.2, 0.2, 0.8)));
}

TEST_CASE("usd mounts: a USD asset's behavior script registers before its prims are read", "[usd_import][mounts]") {
  const LoadedScene loaded = loadSceneForRun(SceneRequest{.scenePath = kDir + "scripted_mount.yaml"});
  const Prim& cam = *loaded.scene.stage.find("/World/Rig/Cam");
  CHECK(cam.behaviors() == std::vector<std::string>{"cameraOrbit"});
  const std::string script =
      std::filesystem::canonical(std::string(SDG_SOURCE_DIR) + "/scenes/examples/scripts/camera_orbit.py").string();
  CHECK(std::find(loaded.scriptFiles.begin(), loaded.scriptFiles.end(), script) != loaded.scriptFiles.end());
}

TEST_CASE("usd mounts: bad references and assets are located errors", "[usd_import][mounts]") {
  const std::string header = "version: 1\nprims:\n  /World: {type: Xform}\n";
  CHECK_THAT(loadError(header + "  /World/A: {reference: " + kDir + "missing.usda}\n"),
             Catch::Contains("t.yaml:4:") && Catch::Contains("USD file not found"));
  CHECK_THAT(loadError(header + "  /World/A: {reference: {file: " + kDir + "lamp.usda, prim: /Nope}}\n"),
             Catch::Contains("has no prim /Nope; its root prims: /Lamp"));
  CHECK_THAT(loadError(header + "  /World/A: {reference: {file: " + kDir + "bad_syntax.usda}}\n"),
             Catch::Contains("/World/A.reference: ") && Catch::Contains("bad_syntax.usda:"));
  CHECK_THAT(loadError("version: 1\nprims:\n  /A: {reference: {file: x.yaml, variants: {a: b}}}\n"),
             Catch::Contains("variant selections are for USD files"));
  CHECK_THAT(loadError(header + "  /World/A: {reference: {file: " + kDir + "lamp.usda, variants: {finish: shiny}}}\n"),
             Catch::Contains("variant set 'finish' has no variant 'shiny'"));
  // A USD mesh asset that names no mesh.
  const LoadedScene loaded = loadMounts();
  MeshKey key = meshKeyOf(*loaded.scene.stage.find("/World/ShadeOnly"), loaded.scene.stage.metadata().subdivisionLevel);
  key.submesh = "/Lamp/Looks";
  CHECK_THROWS_WITH(meshDataFor(key, loaded.assets, "/World/ShadeOnly"),
                    Catch::Contains("no Mesh prim with faces at or under /Lamp/Looks"));
}

}  // namespace sdg
