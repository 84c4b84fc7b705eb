// Every mesh format loads from the small files tools/make_meshes.cpp made,
// and bad mesh or texture files fail with the file named.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "assets/image.h"
#include "assets/mesh_loader.h"
#include "assets/primitives.h"
#include "core/diagnostics.h"
#include "scratch_name.h"

using namespace sdg;

namespace {
std::string meshPath(const char* name) { return std::string(SDG_SOURCE_DIR "/tests/data/meshes/") + name; }

std::string writeTemp(const std::string& name, const std::string& content) {
  // The name's extension kept last: the loader goes by it.
  auto path = test::uniqueTempPath("sdg").concat("_" + name);
  std::ofstream(path, std::ios::binary) << content;
  return path.string();
}
}  // namespace

TEST_CASE("meshes: every supported format loads with its triangles, bounds and materials", "[render][meshes]") {
  for (const char* file : {"crate.obj", "crate.gltf", "crate.glb", "crate.fbx", "crate.ply", "crate.stl", "crate.dae"}) {
    CAPTURE(file);
    MeshData mesh = loadMeshFile(meshPath(file));
    CHECK(mesh.triangleCount() == 24);
    CHECK(mesh.bounds.min().x() == Approx(-0.21f).margin(1e-4));
    CHECK(mesh.bounds.max().x() == Approx(0.21f).margin(1e-4));
    CHECK(mesh.bounds.max().z() == Approx(0.32f).margin(1e-4));
    CHECK(mesh.normals.size() == mesh.positions.size());
    std::string name(file);
    // PLY and STL carry no materials; the others keep the cardboard colour.
    if (name.ends_with(".obj") || name.ends_with(".gltf") || name.ends_with(".glb") || name.ends_with(".dae")) {
      bool cardboard = false;
      for (const MeshPart& part : mesh.parts) cardboard = cardboard || part.baseColor.isApprox(Vec3f(0.62f, 0.45f, 0.28f), 1e-3f);
      CHECK(cardboard);
    }
  }
}

TEST_CASE("meshes: one sub-mesh by name", "[render][meshes]") {
  for (const char* file : {"crate.obj", "crate.dae"}) {
    CAPTURE(file);
    MeshData lid = loadMeshFile(meshPath(file), "lid");
    CHECK(lid.triangleCount() == 12);
    CHECK(lid.bounds.min().z() == Approx(0.30f).margin(1e-4));
  }
  CHECK_THROWS_WITH(loadMeshFile(meshPath("crate.obj"), "handle"), Catch::Contains("no mesh named 'handle'"));
}

TEST_CASE("meshes: bad files fail with the file named", "[render][meshes]") {
  std::string corrupt = writeTemp("corrupt.glb", "glTF this is not a real binary gltf");
  CHECK_THROWS_WITH(loadMeshFile(corrupt), Catch::Contains(corrupt + ": cannot read the mesh"));
  std::string pointsOnly = writeTemp("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  CHECK_THROWS_AS(loadMeshFile(pointsOnly), RunError);
  std::string nan = writeTemp("nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  CHECK_THROWS_WITH(loadMeshFile(nan), Catch::Contains("not a finite number") || Catch::Contains("cannot read the mesh"));
  CHECK_THROWS_WITH(loadMeshFile("/nonexistent/x.obj"), Catch::Contains("/nonexistent/x.obj"));
}

TEST_CASE("textures: PNG variants load as RGBA8, absurd sizes and corrupt files are refused", "[render][textures]") {
  ImageRgba8 split = loadImageRgba8(SDG_SOURCE_DIR "/tests/data/images/split.png", TextureData::Color);
  CHECK(split.width == 64);
  CHECK(split.pixels.size() == 64u * 64u * 4u);
  CHECK(split.pixels[0] == 220);  // red half
  CHECK(split.pixels[3] == 255);
  for (const char* name : {"grey16.png", "palette.png", "grey_alpha.png"}) {
    CAPTURE(name);
    ImageRgba8 image = loadImageRgba8(std::string(SDG_SOURCE_DIR "/tests/data/images/") + name, TextureData::Color);
    CHECK(image.width == 8);
    CHECK(image.pixels.size() == 8u * 8u * 4u);
  }
  CHECK_THROWS_WITH(loadImageRgba8(SDG_SOURCE_DIR "/tests/data/images/huge_header.png", TextureData::Color),
                    Catch::Contains("declares 100000 x 100000 pixels"));
  std::string corrupt = writeTemp("corrupt.png", "\x89PNG\r\n\x1a\nnot really");
  CHECK_THROWS_WITH(loadImageRgba8(corrupt, TextureData::Color), Catch::Contains(corrupt));
}

TEST_CASE("primitives: USD default sizes and axes", "[render][meshes]") {
  MeshData cube = makeCube(2.0);
  CHECK(cube.bounds.min().isApprox(Vec3f(-1, -1, -1)));
  MeshData cylinder = makeCylinder(1.0, 2.0, 'X');
  CHECK(cylinder.bounds.max().x() == Approx(1.0f));
  CHECK(cylinder.bounds.max().y() == Approx(1.0f).margin(1e-3));
  MeshData capsule = makeCapsule(0.5, 1.0, 'Z');
  CHECK(capsule.bounds.max().z() == Approx(1.0f));  // height/2 + radius
  MeshData plane = makePlane(4.0, 2.0, 'Y');
  CHECK(plane.bounds.max().x() == Approx(2.0f));
  CHECK(plane.bounds.max().z() == Approx(1.0f));
  CHECK(plane.bounds.max().y() == Approx(0.0f));
  MeshData cone = makeCone(1.0, 2.0, 'Z');
  CHECK(cone.bounds.max().z() == Approx(1.0f));
}
