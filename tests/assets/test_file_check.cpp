// The asset resolver's search list and the file checks `validate` runs.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "assets/asset_resolver.h"
#include "assets/file_check.h"
#include "scene_io/usd_mesh_asset.h"

using namespace sdg;
namespace fs = std::filesystem;

namespace {

fs::path scratchFolder(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("sdg_file_check_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void writeFile(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace

TEST_CASE("asset resolver: each folder is searched and listed once", "[assets]") {
  AssetResolver r = makeSceneResolver("scenes", {".", "props", "./props/"}, {"scenes/props"});
  CHECK(r.roots() == std::vector<std::string>{"scenes", "scenes/props"});
  CHECK(r.candidates("a.png") == std::vector<std::string>{"scenes/a.png", "scenes/props/a.png"});
  CHECK(r.describeSearch("a.png") == "searched: scenes/a.png, scenes/props/a.png");
}

TEST_CASE("asset resolver: Isaac paths are tried below the Isaac root first", "[assets]") {
  AssetResolver r({"scenes"}, "/data/isaac");
  std::vector<std::string> c = r.candidates("/Isaac/Props/box.glb");
  REQUIRE(c.size() == 4);
  CHECK(c[0] == "/data/isaac/Isaac/Props/box.glb");
  CHECK(c[1] == "/data/isaac/Props/box.glb");  // the root may be Isaac/ itself
  CHECK(c[2] == "/Isaac/Props/box.glb");
  CHECK(c[3] == "scenes/Isaac/Props/box.glb");
  CHECK(AssetResolver({"scenes"}).candidates("/Isaac/Props/box.glb").size() == 2);
}

TEST_CASE("file problems: URL, USD, missing, empty, fine", "[assets]") {
  fs::path dir = scratchFolder("problems");
  writeFile(dir / "empty.png", "");
  writeFile(dir / "box.glb", "glTF");
  fs::copy_file(SDG_SOURCE_DIR "/tests/data/images/formats/pattern.png", dir / "ok.png");
  AssetResolver r({dir.string()});
  CHECK(fileProblem("https://example.com/a.png", FileKind::Image, r)->find("is a URL") != std::string::npos);
  // USD files are mesh assets (scene_io/usd_mesh_asset.cpp): looked for and sniffed like the others.
  CHECK(fileProblem("props/box.usd", FileKind::Mesh, r)->find("mesh 'props/box.usd' not found") == 0);
  writeFile(dir / "fake.usda", "not usd at all");
  CHECK(fileProblem("fake.usda", FileKind::Mesh, r)->ends_with("not a USD file: it starts with neither '#usda' (text), "
                                                              "'PXR-USDC' (crate) nor a zip header (usdz)"));
  // A USD mesh is composed and read (through the reader scene_io installs): a layer without a
  // mesh, or one that does not parse, fails here at its file:line:col rather than in the run.
  registerUsdMeshAssets();
  writeFile(dir / "real.usda", "#usda 1.0\ndef Mesh \"M\" {\n  point3f[] points = [(0,0,0), (1,0,0), (0,1,0)]\n"
                               "  int[] faceVertexCounts = [3]\n  int[] faceVertexIndices = [0, 1, 2]\n}\n");
  CHECK_FALSE(fileProblem("real.usda", FileKind::Mesh, r));
  writeFile(dir / "empty.usda", "#usda 1.0\ndef Xform \"X\" {}\n");
  CHECK(fileProblem("empty.usda", FileKind::Mesh, r)->ends_with("no Mesh prim with faces in the USD file"));
  writeFile(dir / "broken.usda", "#usda 1.0\ndef Mesh \"M\" {\n  point3f[] points = [(0,0)]\n}\n");
  CHECK_THAT(*fileProblem("broken.usda", FileKind::Mesh, r),
             Catch::Contains("cannot read the USD mesh: ") && Catch::Contains("broken.usda:3:"));
  std::string missing = *fileProblem("nope.png", FileKind::Image, r);
  CHECK(missing.find("texture 'nope.png' not found; searched: " + (dir / "nope.png").string()) == 0);
  CHECK(fileProblem("empty.png", FileKind::Image, r)->find("cannot be read: it is empty") != std::string::npos);
  CHECK_FALSE(fileProblem("ok.png", FileKind::Image, r));
  CHECK_FALSE(fileProblem("box.glb#carton", FileKind::Mesh, r));  // '#label' is not part of the name
  CHECK(fileProblem("/Isaac/x.png", FileKind::Image, r)->find("none is set") != std::string::npos);
}

TEST_CASE("file problems: a texture is any image whose header reads, whatever its name says", "[assets]") {
  fs::path dir = scratchFolder("images");
  const std::string images = SDG_SOURCE_DIR "/tests/data/images/";
  fs::copy_file(images + "formats/pattern.jpg", dir / "photo.JPG");
  fs::copy_file(images + "formats/pattern_half.exr", dir / "sky.exr");
  fs::copy_file(images + "formats/pattern.png", dir / "named_wrong.jpg");  // the bytes decide
  fs::copy_file(images + "corrupt/huge_header.png", dir / "huge.png");
  fs::copy_file(images + "corrupt/truncated.png", dir / "truncated.png");
  writeFile(dir / "fake.exr", "not an image");
  writeFile(dir / "notes.txt", "not an image either");
  AssetResolver r({dir.string()});
  for (const char* fine : {"photo.JPG", "sky.exr", "named_wrong.jpg"}) {
    CAPTURE(fine);
    CHECK_FALSE(fileProblem(fine, FileKind::Image, r));
  }
  // Only the header is read: the cut-off pixel data is found by a run.
  CHECK_FALSE(fileProblem("truncated.png", FileKind::Image, r));
  const std::string fake = (dir / "fake.exr").string();
  CHECK(*fileProblem("fake.exr", FileKind::Image, r) ==
        "texture 'fake.exr' (" + fake + "): not a readable OpenEXR image: \"" + fake + "\" is not an OpenEXR file");
  CHECK(fileProblem("notes.txt", FileKind::Image, r)->find("(" + (dir / "notes.txt").string() +
                                                           "): not an image sdgbehave can read") != std::string::npos);
  CHECK(fileProblem("huge.png", FileKind::Image, r)->find("declares 20000 x 20000 pixels") != std::string::npos);
  // Other kinds of file are not opened as images.
  CHECK_FALSE(fileProblem("notes.txt", FileKind::Any, r));
}

TEST_CASE("file entries: Isaac defaults nobody wrote are left out without a root", "[assets]") {
  AttributeSpec spec;
  spec.type = ValueType::String;
  spec.files = FileKind::Image;
  Attribute attr;
  attr.value = Value::makeString("/Isaac/a.jpg, textures/b.png ,/Isaac/c.jpg");

  SECTION("a default, no root: only the project's own entry") {
    CHECK(fileEntriesOf(attr, spec, AssetResolver({"."}), "/P.x") == std::vector<std::string>{"textures/b.png"});
  }
  SECTION("a default, with a root: every entry") {
    CHECK(fileEntriesOf(attr, spec, AssetResolver({"."}, "/isaac"), "/P.x").size() == 3);
  }
  SECTION("written by the user: every entry, so a missing one is an error") {
    attr.loc = SourceLoc{"scene.yaml", 3, 5};
    CHECK(fileEntriesOf(attr, spec, AssetResolver({"."}), "/P.x").size() == 3);
  }
  SECTION("asset[] values") {
    AttributeSpec arraySpec;
    arraySpec.type = ValueType::AssetArray;
    Attribute list;
    list.value = Value::makeAssetArray({"a.png", "", "b.png"});
    CHECK(fileEntriesOf(list, arraySpec, AssetResolver({"."}), "/P.x") == std::vector<std::string>{"a.png", "b.png"});
  }
}

TEST_CASE("file problems: a mesh is a file of a format the loader reads, by extension and first bytes", "[assets]") {
  fs::path dir = scratchFolder("meshes");
  const std::string meshes = SDG_SOURCE_DIR "/tests/data/meshes/";
  for (const char* name : {"crate.obj", "crate.glb", "crate.gltf", "crate.fbx", "crate.ply", "crate.stl", "crate.dae"})
    fs::copy_file(meshes + name, dir / name);
  // A binary STL: 80-byte header (that may itself say "solid"), count, 50 bytes a triangle.
  std::string stl(84 + 50, '\0');
  stl.replace(0, 5, "solid");
  stl[80] = 1;
  writeFile(dir / "binary.stl", stl);
  writeFile(dir / "binary_fbx.fbx", std::string("Kaydara FBX Binary  \0\x1a\0", 23));
  fs::copy_file(SDG_SOURCE_DIR "/tests/data/images/formats/pattern.png", dir / "picture.png");
  fs::copy_file(SDG_SOURCE_DIR "/tests/data/images/formats/pattern.png", dir / "picture.glb");
  writeFile(dir / "accounts", "root:x:0:0:root:/root:/bin/bash\n");
  writeFile(dir / "accounts.obj", "# a comment\nv 0 0 0\nroot:x:0:0:root:/root:/bin/bash\n");
  writeFile(dir / "page.gltf", "<html></html>");
  writeFile(dir / "page.dae", "<?xml version=\"1.0\"?>\n<html></html>");
  writeFile(dir / "odd.stl", std::string(100, 'x'));
  writeFile(dir / "odd.ply", "PLY?\n");
  writeFile(dir / "odd.fbx", "binary junk\x01\x02");
  AssetResolver r({dir.string()});
  for (const char* fine : {"crate.obj", "crate.glb", "crate.gltf", "crate.fbx", "crate.ply", "crate.stl", "crate.dae",
                           "binary.stl", "binary_fbx.fbx", "crate.glb#crate"}) {
    CAPTURE(fine);
    CHECK_FALSE(fileProblem(fine, FileKind::Mesh, r));
  }
  auto problem = [&](const char* entry) {
    std::optional<std::string> p = fileProblem(entry, FileKind::Mesh, r);
    return p ? *p : std::string("(none)");
  };
  // A wrong extension is refused without opening the file.
  CHECK(problem("picture.png") == "mesh 'picture.png' is not a mesh format sdgbehave reads; mesh files end in .obj, "
                                  ".glb, .gltf, .fbx, .ply, .stl, .dae, .usd, .usda, .usdc, .usdz");
  CHECK(problem("accounts").starts_with("mesh 'accounts' is not a mesh format sdgbehave reads"));
  CHECK(problem("/etc/passwd").starts_with("mesh '/etc/passwd' is not a mesh format sdgbehave reads"));
  // The right extension on the wrong bytes.
  auto at = [&](const char* name) { return "(" + (dir / name).string() + "): "; };
  CHECK(problem("picture.glb") == "mesh 'picture.glb' " + at("picture.glb") + "not a binary glTF: it does not start with 'glTF'");
  CHECK(problem("accounts.obj") ==
        "mesh 'accounts.obj' " + at("accounts.obj") + "not a Wavefront OBJ: line 3 starts with 'root:x:0:0:root:/root:/bin/bash'");
  CHECK(problem("page.gltf").ends_with("not a glTF (JSON) file: it does not start with '{'"));
  CHECK(problem("page.dae").ends_with("not a COLLADA (.dae) file: no <COLLADA element at its start"));
  CHECK(problem("odd.stl").ends_with("not an STL: neither text starting with 'solid' nor a binary STL (84 + 50 bytes per triangle)"));
  CHECK(problem("odd.ply").ends_with("not a PLY: it does not start with 'ply'"));
  CHECK(problem("odd.fbx").ends_with("not an FBX: neither 'Kaydara FBX Binary' nor an ASCII FBX's '; FBX' at its start"));
  CHECK(readableExtensions(FileKind::Mesh) ==
        std::vector<std::string>{".obj", ".glb", ".gltf", ".fbx", ".ply", ".stl", ".dae", ".usd", ".usda", ".usdc", ".usdz"});
}

TEST_CASE("file problems: a confined resolver opens nothing outside its roots", "[assets]") {
  fs::path dir = scratchFolder("confined");
  writeFile(dir / "scene" / "props" / "crate.glb", "glTF");
  writeFile(dir / "library" / "crate.glb", "glTF");
  writeFile(dir / "outside" / "crate.glb", "glTF");
  AssetResolver open({(dir / "scene").string(), (dir / "library").string()});
  AssetResolver confined = open;
  confined.confineToRoots();
  const std::string outside = (dir / "outside" / "crate.glb").string();
  for (const std::string& entry : {std::string("../outside/crate.glb"), outside}) {
    CAPTURE(entry);
    CHECK_FALSE(fileProblem(entry, FileKind::Mesh, open));
    CHECK_FALSE(confined.resolve(entry));
    CHECK(confined.leavesRoots(entry));
    CHECK(fileProblem(entry, FileKind::Mesh, confined)->starts_with(
        "mesh '" + entry + "' is outside the scene's folder and asset roots (" + (dir / "scene").string() + ", " +
        (dir / "library").string() + "), where the studio opens no file"));
  }
  // Inside any root, through '..' or not, is fine.
  for (const char* entry : {"props/crate.glb", "crate.glb", "props/../props/crate.glb", "../library/crate.glb"}) {
    CAPTURE(entry);
    CHECK_FALSE(fileProblem(entry, FileKind::Mesh, confined));
  }
  CHECK_FALSE(open.leavesRoots("../outside/crate.glb"));
  CHECK(fileProblem("missing.glb", FileKind::Mesh, confined)->find("not found") != std::string::npos);
}
