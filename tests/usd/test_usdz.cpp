// .usdz packages: archives written here with libzip (stored entries as usdz
// requires, a deflated one, folders, a package inside a package), read
// back through UsdzPackage; asset paths resolved inside them; and broken
// archives (not a zip, cut short, corrupt data, lying sizes, nesting past
// the limit), each a UsdError naming the package.
#include <catch2/catch.hpp>

#include <zip.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "usd/crate_builder.h"
#include "usd/layer_io.h"
#include "usd/usdz_package.h"
#include "scratch_name.h"

using namespace sdg::usd;
using namespace sdg::usd::test;
namespace fs = std::filesystem;

namespace {

struct ZipEntry {
  std::string name;
  std::vector<uint8_t> bytes;
  bool deflate = false;
};

// A scratch folder for this test run, removed at exit.
const fs::path& scratch() {
  static const sdg::test::ScratchFolder dir("sdg_usdz_test");
  return dir.path();
}

fs::path writeZip(const std::string& name, const std::vector<ZipEntry>& entries) {
  fs::path path = scratch() / name;
  fs::remove(path);
  int error = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_EXCL, &error);
  REQUIRE(z);
  for (const auto& e : entries) {
    if (e.name.back() == '/') {
      REQUIRE(zip_dir_add(z, e.name.c_str(), 0) >= 0);
      continue;
    }
    zip_source_t* src = zip_source_buffer(z, e.bytes.data(), e.bytes.size(), 0);
    zip_int64_t index = zip_file_add(z, e.name.c_str(), src, 0);
    REQUIRE(index >= 0);
    zip_set_file_compression(z, zip_uint64_t(index), e.deflate ? ZIP_CM_DEFLATE : ZIP_CM_STORE, 0);
  }
  REQUIRE(zip_close(z) == 0);
  return path;
}

std::vector<uint8_t> fileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

fs::path writeBytes(const std::string& name, const std::vector<uint8_t>& bytes) {
  fs::path path = scratch() / name;
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  return path;
}

std::vector<uint8_t> crateLayer(const std::string& texture) {
  CrateBuilder b;
  b.spec("/", SpecType::PseudoRoot, {b.field("defaultPrim", rep(CrateType::Token, b.token("Model")))});
  b.spec("/Model.tex", SpecType::Attribute, {b.field("default", rep(CrateType::AssetPath, b.token(texture)))});
  return b.finish();
}

std::vector<uint8_t> text(const std::string& s) { return {s.begin(), s.end()}; }

std::string errorOf(auto&& f) {
  try {
    f();
  } catch (const UsdError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("usdz: entries, the root layer, reading, resolving", "[usd][usdz]") {
  auto inner = fileBytes(writeZip("inner.usdz", {{"model.usdc", crateLayer("tex/wood.png")},
                                                 {"tex/wood.png", text("PNG inner")}}));
  auto layer = crateLayer("textures/a.png");
  auto path = writeZip("outer.usdz", {{"textures/", {}},
                                      {"textures/a.png", text("PNG a")},
                                      {"scene/root.usdc", layer},
                                      {"scene/notes.txt", text(std::string(5000, 'n')), true},
                                      {"parts/inner.usdz", inner}});
  UsdzPackage pkg(path.string());
  CHECK(pkg.identifier() == path.string());
  CHECK(pkg.entries() == std::vector<std::string>{"textures/a.png", "scene/root.usdc", "scene/notes.txt",
                                                  "parts/inner.usdz"});
  CHECK(pkg.firstLayer() == "scene/root.usdc");
  CHECK(pkg.read("scene/root.usdc") == layer);
  CHECK(pkg.read("scene/notes.txt") == text(std::string(5000, 'n')));  // deflated: libzip inflates it
  CHECK(pkg.read("parts/inner.usdz") == inner);
  CHECK(pkg.read("parts/inner.usdz[tex/wood.png]") == text("PNG inner"));

  Layer fromPackage = readCrateLayer(pkg.read("scene/root.usdc"), "root.usdc");
  const std::string asset = fromPackage.spec("/Model.tex")->fields.at("default").strings.at(0);
  CHECK(pkg.resolve("scene/root.usdc", "../" + asset) == "textures/a.png");
  CHECK(pkg.resolve("scene/root.usdc", asset).empty());  // scene/textures/a.png is not there
  CHECK(pkg.resolve("textures/a.png", "./a.png") == "textures/a.png");
  CHECK(pkg.resolve("scene/root.usdc", "../../textures/a.png").empty());  // climbs out of the package
  CHECK(pkg.resolve("scene/root.usdc", "/textures/a.png").empty());       // absolute: not in the package
  CHECK(pkg.resolve("scene/root.usdc", "../parts/inner.usdz") == "parts/inner.usdz");
  CHECK(pkg.resolve("parts/inner.usdz[model.usdc]", "tex/wood.png") == "parts/inner.usdz[tex/wood.png]");
  CHECK(pkg.resolve("parts/inner.usdz[model.usdc]", "tex/missing.png").empty());
  Layer nested = readCrateLayer(pkg.read("parts/inner.usdz[model.usdc]"), "model.usdc");
  CHECK(nested.spec("/Model.tex")->fields.at("default").strings.at(0) == "tex/wood.png");

  CHECK_THAT(errorOf([&] { pkg.read("nope.usdc"); }),
             Catch::Equals(path.string() + ": usdz package: entry 'nope.usdc' does not exist"));
  CHECK_THAT(errorOf([&] { pkg.read("textures/"); }), Catch::Contains("entry 'textures/' does not exist"));
  CHECK(errorOf([&] { pkg.read("parts/inner.usdz[nope]"); }) ==
        path.string() + "[parts/inner.usdz]: usdz package: entry 'nope' does not exist");
}

TEST_CASE("usdz: limits on entry sizes and nesting", "[usd][usdz]") {
  auto level2 = fileBytes(writeZip("l2.usdz", {{"deep.usdc", crateLayer("x.png")}}));
  auto level1 = fileBytes(writeZip("l1.usdz", {{"l2.usdz", level2}}));
  auto path = writeZip("l0.usdz", {{"l1.usdz", level1}, {"big.bin", std::vector<uint8_t>(4096, 7)}});
  UsdzPackage pkg(path.string());
  CHECK(pkg.firstLayer().empty());
  CHECK(pkg.read("l1.usdz[l2.usdz[deep.usdc]]").size() > 88);
  ReadLimits shallow;
  shallow.maxNesting = 1;
  UsdzPackage limited(path.string(), shallow);
  CHECK_THAT(errorOf([&] { limited.read("l1.usdz[l2.usdz[deep.usdc]]"); }),
             Catch::Contains("[l1.usdz]: usdz package: packages nest deeper than the limit"));
  ReadLimits small;
  small.maxFileBytes = 1000;
  UsdzPackage tight(path.string(), small);
  CHECK_THAT(errorOf([&] { tight.read("big.bin"); }),
             Catch::Contains("entry 'big.bin' has 4096 bytes, more than the limit of 1000"));
}

TEST_CASE("usdz: broken archives fail cleanly", "[usd][usdz]") {
  auto missing = (scratch() / "missing.usdz").string();
  CHECK_THAT(errorOf([&] { UsdzPackage p(missing); }),
             Catch::StartsWith(missing + ": usdz package: cannot open it as a zip archive: "));
  auto notZip = writeBytes("notzip.usdz", text("#usda 1.0\n"));
  CHECK_THAT(errorOf([&] { UsdzPackage p(notZip.string()); }),
             Catch::Contains("notzip.usdz: usdz package: cannot open it as a zip archive: Not a zip archive"));

  const std::vector<uint8_t> payload = crateLayer("t.png");
  auto good = fileBytes(writeZip("good.usdz", {{"a.usdc", payload}, {"b.txt", text(std::string(300, 'b')), true}}));

  // Every truncation: the archive does not open, or an entry does not read.
  for (size_t n = 0; n < good.size(); ++n) {
    auto cut = writeBytes("cut.usdz", std::vector<uint8_t>(good.begin(), good.begin() + ptrdiff_t(n)));
    INFO("prefix of " << n << " bytes");
    std::string error = errorOf([&] {
      UsdzPackage p(cut.string());
      p.read("a.usdc");
      p.read("b.txt");
    });
    CHECK_THAT(error, Catch::StartsWith(cut.string() + ": usdz package: "));
  }

  // Every flipped byte (the whole archive, sampled bits): opens and reads
  // the same bytes, or fails with a UsdError.
  int failed = 0;
  for (size_t i = 0; i < good.size(); ++i) {
    auto bad = good;
    bad[i] = uint8_t(bad[i] ^ (1u << (i % 8)));
    auto path = writeBytes("flip.usdz", bad);
    INFO("flipped byte " << i);
    try {
      UsdzPackage p(path.string());
      for (const auto& e : p.entries()) p.read(e);
    } catch (const UsdError& e) {
      ++failed;
      CHECK_THAT(std::string(e.what()), Catch::StartsWith(path.string() + ": usdz package: "));
    }
  }
  CHECK(failed > 0);

  // A stored entry whose data was damaged: the CRC check catches it.
  auto corrupt = good;
  auto at = std::search(corrupt.begin(), corrupt.end(), payload.begin(), payload.begin() + 8);
  REQUIRE(at != corrupt.end());
  at[100] = uint8_t(at[100] ^ 0xff);
  auto corruptPath = writeBytes("corrupt.usdz", corrupt);
  UsdzPackage p(corruptPath.string());
  CHECK_THAT(errorOf([&] { p.read("a.usdc"); }), Catch::Contains("entry 'a.usdc': cannot read it: CRC error"));
}

TEST_CASE("usdz: readPackagedLayer and readLayerFile on packages", "[usd][usdz]") {
  auto inner = fileBytes(writeZip("inner2.usdz", {{"model.usdc", crateLayer("tex/wood.png")}}));
  auto path = writeZip("layers.usdz", {{"root.usda", text("#usda 1.0\n(\n    defaultPrim = \"Root\"\n)\n\ndef Xform \"Root\"\n{\n}\n")},
                                       {"sub/inner.usdz", inner},
                                       {"notes.txt", text("not a layer")}});
  Layer root = readPackagedLayer(path.string(), "");
  CHECK(root.format == "usda");
  CHECK(root.identifier == path.string() + "[root.usda]");
  CHECK(root.realPath == path.string());
  CHECK(root.spec("/Root"));
  Layer nested = readPackagedLayer(path.string(), "sub/inner.usdz[model.usdc]");
  CHECK(nested.format == "usdc");
  CHECK(nested.identifier == path.string() + "[sub/inner.usdz[model.usdc]]");
  CHECK(nested.spec("/Model.tex"));
  CHECK(readLayerFile(path.string()).identifier == root.identifier);
  CHECK(readLayerFile(path.string() + "[sub/inner.usdz[model.usdc]]").format == "usdc");
  CHECK(errorOf([&] { readPackagedLayer(path.string(), "notes.txt"); }) ==
        path.string() + "[notes.txt]: neither a crate layer (\"PXR-USDC\") nor a usda layer (\"#usda\")");
  auto empty = writeZip("empty.usdz", {{"readme.txt", text("x")}});
  CHECK(errorOf([&] { readPackagedLayer(empty.string(), ""); }) ==
        empty.string() + ": usdz package: holds no .usd, .usda or .usdc layer");
}
