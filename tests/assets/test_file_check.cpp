// The asset resolver's search list and the file checks `validate` runs.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "assets/asset_resolver.h"
#include "assets/file_check.h"

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

TEST_CASE("file problems: URL, USD, non-PNG texture, missing, empty, fine", "[assets]") {
  fs::path dir = scratchFolder("problems");
  writeFile(dir / "ok.png", "\x89PNG");
  writeFile(dir / "empty.png", "");
  writeFile(dir / "box.glb", "glTF");
  AssetResolver r({dir.string()});
  CHECK(fileProblem("https://example.com/a.png", FileKind::Image, r)->find("is a URL") != std::string::npos);
  CHECK(fileProblem("props/box.usd", FileKind::Mesh, r)->find("is a USD file, which sdgbehave cannot read") !=
        std::string::npos);
  CHECK(fileProblem("a.JPG", FileKind::Image, r)->find("reads PNG textures only, found a '.jpg'") != std::string::npos);
  std::string missing = *fileProblem("nope.png", FileKind::Image, r);
  CHECK(missing.find("texture 'nope.png' not found; searched: " + (dir / "nope.png").string()) == 0);
  CHECK(fileProblem("empty.png", FileKind::Image, r)->find("cannot be read: it is empty") != std::string::npos);
  CHECK_FALSE(fileProblem("ok.png", FileKind::Image, r));
  CHECK_FALSE(fileProblem("box.glb#carton", FileKind::Mesh, r));  // '#label' is not part of the name
  CHECK(fileProblem("/Isaac/x.png", FileKind::Image, r)->find("none is set") != std::string::npos);
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
