// USD's anchoring rules inside packages, on packages written here with
// libzip: a layer's relative paths resolve from its own folder in its
// package (not the package root), packages nest ("a.usdz[b.usdz[c.png]]")
// for sublayers, references, payloads and texture values alike, and a path
// that climbs out of a package continues from the package's place. Also
// Git LFS pointer files (a clone without `git lfs`) named as such, at the
// line of the arc that names them.
#include <catch2/catch.hpp>

#include <zip.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "usd/asset_paths.h"
#include "usd/compose.h"
#include "usd/layer_io.h"
#include "usd/usdz_package.h"
#include "scratch_name.h"

using namespace sdg::usd;
namespace fs = std::filesystem;

namespace {

const fs::path& scratch() {
  static const sdg::test::ScratchFolder dir("sdg_anchoring_test");
  return dir.path();
}

using Entries = std::vector<std::pair<std::string, std::string>>;  // name, bytes (stored, as usdz wants)

std::string zipBytes(const Entries& entries) {
  const fs::path path = scratch() / "building.zip";
  fs::remove(path);
  int error = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_EXCL, &error);
  REQUIRE(z);
  for (const auto& [name, bytes] : entries) {
    zip_source_t* src = zip_source_buffer(z, bytes.data(), bytes.size(), 0);
    const zip_int64_t index = zip_file_add(z, name.c_str(), src, 0);
    REQUIRE(index >= 0);
    zip_set_file_compression(z, zip_uint64_t(index), ZIP_CM_STORE, 0);
  }
  REQUIRE(zip_close(z) == 0);
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  std::string bytes(size_t(in.tellg()), '\0');
  in.seekg(0);
  in.read(bytes.data(), std::streamsize(bytes.size()));
  return bytes;
}

std::string writeFile(const std::string& name, const std::string& bytes) {
  const fs::path path = scratch() / name;
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
  return path.string();
}

const char* kLfsPointer =
    "version https://git-lfs.github.com/spec/v1\n"
    "oid sha256:4d7a214614ab2935c943f9e0ff69d22eadbb8f32b1258daaa5e2ca24d17e2393\n"
    "size 12345\n";

ComposedStage compose(const std::string& root) {
  return composeStage(root, [](const std::string& id) { return readLayerFile(id); });
}

const ComposedProperty& property(const ComposedStage& stage, const std::string& prim, const std::string& name) {
  INFO(prim + "." + name);
  const ComposedPrim* p = stage.prim(prim);
  REQUIRE(p);
  const ComposedProperty* prop = p->property(name);
  REQUIRE(prop);
  return *prop;
}

std::string composeError(const std::string& root) {
  try {
    compose(root);
  } catch (const UsdError& e) {
    return e.what();
  }
  return "(no error)";
}

// A package nested in a package: its layer in a folder references a layer
// beside it and names a texture from its own folder.
std::string innerPackage() {
  return zipBytes({
      {"geo/model.usda", "#usda 1.0\n(\n    defaultPrim = \"Model\"\n)\n"
                         "def Xform \"Model\" (\n    references = @./shape.usda@</Shape>\n)\n{\n"
                         "    asset tex = @maps/wood.png@\n}\n"},
      {"geo/shape.usda", "#usda 1.0\ndef Xform \"Shape\"\n{\n    asset shapeTex = @../maps/top.png@\n}\n"},
      {"geo/maps/wood.png", "wood"},
      {"maps/top.png", "top"},
  });
}

}  // namespace

TEST_CASE("anchoring: package-relative paths split, join and anchor as USD's do", "[usd][anchoring]") {
  CHECK(splitPackagePathInner("a.usdz[b.usdz[c/d.png]]") == std::make_pair(std::string("a.usdz[b.usdz]"), std::string("c/d.png")));
  CHECK(splitPackagePathInner("a.usdz[c.png]") == std::make_pair(std::string("a.usdz"), std::string("c.png")));
  CHECK(splitPackagePathInner("plain/x.usda") == std::make_pair(std::string("plain/x.usda"), std::string()));
  CHECK(joinPackagePath("a.usdz[b.usdz]", "c.png") == "a.usdz[b.usdz[c.png]]");
  CHECK(joinPackagePath("/p/a.usdz", "c.png") == "/p/a.usdz[c.png]");
  CHECK(namesPackage("a.usdz[sub/b.USDZ]"));
  CHECK(!namesPackage("a.usdz[b.usdc]"));

  // A layer in a folder of the package: its folder, not the package root.
  CHECK(resolveAssetPath("0/logo.png", "/p/x.usdz[x.usdz_FILES/scene.usdc]") == "/p/x.usdz[x.usdz_FILES/0/logo.png]");
  CHECK(resolveAssetPath("0/logo.png", "/p/x.usdz[scene.usdc]") == "/p/x.usdz[0/logo.png]");
  // Nested packages anchor in the innermost one.
  CHECK(resolveAssetPath("c.png", "a.usdz[b.usdz[dir/l.usda]]") == "a.usdz[b.usdz[dir/c.png]]");
  CHECK(resolveAssetPath("inner.usdz[m.usda]", "a.usdz[dir/l.usda]") == "a.usdz[dir/inner.usdz[m.usda]]");
  CHECK(resolveAssetPath("./c.png", "a.usdz[b.usdz]") == "a.usdz[b.usdz[c.png]]");  // a package: at its root
  // Climbing out of the inner package continues in the outer one, then beside it.
  CHECK(resolveAssetPath("../../c.png", "/p/a.usdz[sub/b.usdz[dir/l.usda]]") == "/p/a.usdz[sub/c.png]");
  CHECK(resolveAssetPath("../../../../c.png", "/p/a.usdz[sub/b.usdz[dir/l.usda]]") == "/p/c.png");
  // URLs stay as written (file checks say that they are not local files).
  CHECK(resolveAssetPath("dynamic://mandelbrot", "/p/a.usda") == "dynamic://mandelbrot");
}

TEST_CASE("anchoring: a package whose root layer sits in a folder, with a nested package", "[usd][anchoring]") {
  const std::string root = "#usda 1.0\n(\n    subLayers = [@more/extra.usda@]\n)\n"
                           "def Xform \"World\"\n{\n    asset logo = @0/logo.png@\n"
                           "    def Xform \"Part\" (\n        prepend references = @../parts/inner.usdz@\n    )\n    {\n    }\n"
                           "    def Xform \"Loaded\" (\n        prepend payload = @../parts/inner.usdz[geo/shape.usda]@</Shape>\n"
                           "    )\n    {\n    }\n}\n";
  const std::string extra = "#usda 1.0\nover \"World\"\n{\n    asset extraTex = @0/extra.png@\n}\n";
  const std::string pkg = writeFile("outer.usdz", zipBytes({{"x.usdz_FILES/scene.usda", root},
                                                            {"x.usdz_FILES/more/extra.usda", extra},
                                                            {"x.usdz_FILES/0/logo.png", "logo"},
                                                            {"x.usdz_FILES/more/0/extra.png", "extra"},
                                                            {"parts/inner.usdz", innerPackage()}}));
  const ComposedStage stage = compose(pkg);
  CHECK(stage.rootLayer == pkg + "[x.usdz_FILES/scene.usda]");
  const UsdzPackage package(pkg);
  auto readable = [&](const std::string& resolved) {
    auto [file, entry] = splitPackagePath(resolved);
    CHECK(file == pkg);
    return std::string(package.read(entry).size(), '.');
  };
  // The root layer's texture, from the root layer's folder in the package.
  CHECK(property(stage, "/World", "logo").resolvedAssets.at(0) == pkg + "[x.usdz_FILES/0/logo.png]");
  // A sublayer's, from the sublayer's folder.
  CHECK(property(stage, "/World", "extraTex").resolvedAssets.at(0) == pkg + "[x.usdz_FILES/more/0/extra.png]");
  // A reference to a package inside the package: its root layer, whose paths
  // anchor inside the inner package (a reference and a texture).
  const ComposedProperty& wood = property(stage, "/World/Part", "tex");
  CHECK(wood.resolvedAssets.at(0) == pkg + "[parts/inner.usdz[geo/maps/wood.png]]");
  CHECK(readable(wood.resolvedAssets.at(0)).size() == 4);
  const ComposedProperty& top = property(stage, "/World/Part", "shapeTex");
  CHECK(top.resolvedAssets.at(0) == pkg + "[parts/inner.usdz[maps/top.png]]");
  CHECK(readable(top.resolvedAssets.at(0)).size() == 3);
  // A payload naming an entry of the nested package.
  CHECK(property(stage, "/World/Loaded", "shapeTex").resolvedAssets.at(0) == pkg + "[parts/inner.usdz[maps/top.png]]");
  CHECK(std::find(stage.layers.begin(), stage.layers.end(), pkg + "[parts/inner.usdz[geo/shape.usda]]") !=
        stage.layers.end());
}

TEST_CASE("anchoring: a missing entry of a nested package is named with its package", "[usd][anchoring]") {
  const std::string root = "#usda 1.0\ndef Xform \"A\" (\n    references = @inner.usdz[geo/none.usda]@</X>\n)\n{\n}\n";
  const std::string pkg = writeFile("missing.usdz", zipBytes({{"scene.usda", root}, {"inner.usdz", innerPackage()}}));
  const std::string error = composeError(pkg);
  CHECK_THAT(error, Catch::StartsWith(pkg + "[scene.usda]:3:18: reference @inner.usdz[geo/none.usda]@</X>"));
  CHECK_THAT(error, Catch::Contains("entry 'geo/none.usda' does not exist"));
}

TEST_CASE("anchoring: Git LFS pointers are named as such at the arc that names them", "[usd][anchoring][lfs]") {
  const std::string pointer = writeFile("lfs/big.usd", kLfsPointer);
  // Opened directly: the file named, the fix said.
  const std::string direct = [&] {
    try {
      readLayerFile(pointer);
    } catch (const UsdError& e) {
      CHECK(e.loc().file == pointer);
      return std::string(e.what());
    }
    return std::string("(no error)");
  }();
  CHECK(direct == pointer + " is a Git LFS pointer, not a USD layer: run git lfs pull in its repository (the clone "
                            "was made without Git LFS)");

  // A sublayer, a reference and a payload: each at its own line and column, the file said once.
  const std::string sub = writeFile("lfs/sub.usda", "#usda 1.0\n(\n    doc = \"x\"\n    subLayers = [\n"
                                                    "        @./ok.usda@,\n        @big.usd@\n    ]\n)\n");
  writeFile("lfs/ok.usda", "#usda 1.0\n");
  std::string error = composeError(sub);
  CHECK_THAT(error, Catch::StartsWith(scratch().string() + "/lfs/sub.usda:6:9: sublayer @big.usd@: " + pointer +
                          " is a Git LFS pointer, not a USD layer: run git lfs pull"));
  CHECK(error.find(pointer, error.find(pointer) + 1) == std::string::npos);  // named once

  const std::string ref = writeFile("lfs/ref.usda", "#usda 1.0\ndef Xform \"A\"\n{\n    def Xform \"B\" (\n"
                                                    "        payload = @./big.usd@\n    )\n    {\n    }\n}\n");
  error = composeError(ref);
  CHECK_THAT(error, Catch::StartsWith(scratch().string() + "/lfs/ref.usda:5:19: payload @./big.usd@: " + pointer +
                          " is a Git LFS pointer"));

  // Inside a package too.
  const std::string pkg = writeFile("lfs/pkg.usdz", zipBytes({{"scene.usda", "#usda 1.0\n(\n    subLayers = [@big.usda@]\n)\n"},
                                                              {"big.usda", kLfsPointer}}));
  error = composeError(pkg);
  CHECK_THAT(error, Catch::StartsWith(pkg + "[scene.usda]:3:18: sublayer @big.usda@: " + pkg + "[big.usda] is a Git LFS pointer"));
}
