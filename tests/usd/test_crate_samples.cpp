// The crate reader and the package reader on real files: the .usdz packages
// of ../shared/usd-samples (written by Apple's usdzconvert and Pixar's USD,
// crate version 0.8.0). Tagged [samples]: CTest runs them as usd.samples,
// which skips (exit 77) where the folder is absent.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>

#include "usd/compose.h"
#include "usd/layer_io.h"
#include "usd/samples_dir.h"
#include "usd/usdz_package.h"

using namespace sdg::usd;
using sdg::usd::test::sampleFiles;
using sdg::usd::test::samplesDir;
namespace fs = std::filesystem;

namespace {

std::string package(const char* relative) { return (fs::path(samplesDir()) / relative).string(); }

Layer readEntry(const std::string& packagePath, const std::string& entry) {
  UsdzPackage pkg(packagePath);
  auto bytes = pkg.read(entry);
  return readCrateLayer(bytes, packagePath + "[" + entry + "]");
}

const Value& fieldOf(const Layer& layer, const std::string& path, const std::string& name) {
  const Spec* spec = layer.spec(path);
  INFO(path << " ." << name);
  REQUIRE(spec);
  const Value* v = spec->field(name);
  REQUIRE(v);
  return *v;
}

std::string parentOf(const std::string& path) {
  auto cut = path.find_last_of("/.");
  return cut == 0 ? "/" : path.substr(0, cut);
}

// Every prim spec is listed in its parent's primChildren and every property
// in its prim's properties: the path tree and the fields agree.
void checkNamespace(const Layer& layer) {
  for (const auto& [path, spec] : layer.specs) {
    if (path == "/") continue;
    INFO(layer.identifier << " <" << path << ">");
    const bool isProperty = spec.type == SpecType::Attribute || spec.type == SpecType::Relationship;
    REQUIRE((isProperty || spec.type == SpecType::Prim));
    const std::string parent = parentOf(path);
    const std::string name = path.substr(parent.size() + (parent == "/" ? 0 : 1));
    const Value& list = fieldOf(layer, parent, isProperty ? field::kProperties : field::kPrimChildren);
    REQUIRE(list.kind == Kind::TokenVector);
    CHECK(std::count(list.strings.begin(), list.strings.end(), name) == 1);
    if (!isProperty) {
      CHECK(fieldOf(layer, path, field::kSpecifier).kind == Kind::Specifier);
    }
  }
}

}  // namespace

TEST_CASE("every crate layer in every sample package reads", "[usd][crate][samples]") {
  const std::vector<std::string> packages = sampleFiles({".usdz"});
  int crateLayers = 0;
  for (const auto& path : packages) {
    UsdzPackage pkg(path);
    for (const auto& entry : pkg.entries()) {
      if (fs::path(entry).extension() != ".usdc") continue;
      Layer layer = readEntry(path, entry);
      ++crateLayers;
      CHECK(layer.format == "usdc");
      CHECK(layer.specs.size() > 10);
      REQUIRE(layer.spec("/"));
      CHECK(layer.spec("/")->type == SpecType::PseudoRoot);
      CHECK(fieldOf(layer, "/", field::kDefaultPrim).kind == Kind::Token);
      checkNamespace(layer);
    }
  }
  CHECK(crateLayers == 4);
}

TEST_CASE("BoxAnimated: meshes, materials and animated transforms", "[usd][crate][samples]") {
  Layer layer = readEntry(package("test_assets/USDZ/BoxAnimated/BoxAnimated.usdz"), "BoxAnimated.imported.usdc");
  CHECK(layer.specs.size() == 41);
  CHECK(fieldOf(layer, "/", field::kDefaultPrim).strings == std::vector<std::string>{"BoxAnimated"});
  CHECK(fieldOf(layer, "/", field::kUpAxis).strings == std::vector<std::string>{"Y"});
  CHECK(fieldOf(layer, "/", field::kEndTimeCode).numbers == std::vector<double>{89});
  CHECK(fieldOf(layer, "/", field::kTimeCodesPerSecond).numbers == std::vector<double>{24});
  const Value& creator = fieldOf(layer, "/", "customLayerData");
  REQUIRE(creator.kind == Kind::Dictionary);
  CHECK(creator.dictionary->at("creator").strings == std::vector<std::string>{"usdzconvert preview 0.67"});
  CHECK(creator.dictionary->at("Apple").dictionary->at("preferredIblVersion").numbers == std::vector<double>{2});

  const std::string mesh = "/BoxAnimated/Geom/node_3";
  CHECK(fieldOf(layer, mesh, field::kTypeName).strings == std::vector<std::string>{"Mesh"});
  const Value& points = fieldOf(layer, mesh + ".points", field::kDefault);
  CHECK(points.kind == Kind::Vec3f);
  CHECK(points.isArray);
  CHECK(points.numbers.size() == 224 * 3);
  const Value& indexes = fieldOf(layer, mesh + ".faceVertexIndices", field::kDefault);
  CHECK(indexes.kind == Kind::Int);
  CHECK(indexes.numbers.size() == 576);  // compressed in the file (more than 16 ints)
  CHECK(*std::max_element(indexes.numbers.begin(), indexes.numbers.end()) == 223);
  const Value& counts = fieldOf(layer, mesh + ".faceVertexCounts", field::kDefault);
  CHECK(counts.numbers == std::vector<double>(192, 3.0));
  CHECK(fieldOf(layer, mesh + ".faceVertexCounts", field::kTypeName).strings[0] == "int[]");
  CHECK(fieldOf(layer, mesh + ".doubleSided", field::kVariability).enumValue == int(Variability::Uniform));

  const Value& apiSchemas = fieldOf(layer, mesh, field::kApiSchemas);
  REQUIRE(apiSchemas.kind == Kind::TokenListOp);
  CHECK(apiSchemas.textListOp->prependedItems == std::vector<std::string>{"MaterialBindingAPI"});
  const Value& binding = fieldOf(layer, mesh + ".material:binding", field::kTargetPaths);
  REQUIRE(binding.kind == Kind::PathListOp);
  CHECK(binding.textListOp->isExplicit);
  CHECK(binding.textListOp->explicitItems == std::vector<std::string>{"/BoxAnimated/Materials/outer"});
  CHECK(layer.spec(mesh + ".material:binding")->type == SpecType::Relationship);
  const Value& connection =
      fieldOf(layer, "/BoxAnimated/Materials/inner.outputs:surface", field::kConnectionPaths);
  CHECK(connection.textListOp->explicitItems ==
        std::vector<std::string>{"/BoxAnimated/Materials/inner/surfaceShader.outputs:surface"});
  const Value& color = fieldOf(layer, "/BoxAnimated/Materials/inner/surfaceShader.inputs:diffuseColor", field::kDefault);
  CHECK(color.kind == Kind::Vec3f);
  CHECK_FALSE(color.isArray);
  CHECK(color.numbers[0] == Approx(0.8));

  const Value& translate = fieldOf(layer, "/BoxAnimated/Geom/node_0.xformOp:translate", field::kTimeSamples);
  REQUIRE(translate.kind == Kind::TimeSamples);
  REQUIRE(translate.timeSamples->times.size() == 4);
  CHECK(translate.timeSamples->times[0] == 0);
  CHECK(translate.timeSamples->times[1] == 30);
  CHECK(translate.timeSamples->values[1].kind == Kind::Vec3d);
  CHECK(translate.timeSamples->values[1].numbers[1] == Approx(2.52));
  const Value& orient = fieldOf(layer, "/BoxAnimated/Geom/node_0/node_1/node_2.xformOp:orient", field::kTimeSamples);
  REQUIRE(orient.timeSamples->values.size() == 2);
  // Quaternions are kept real first: a half turn about X at frame 60.
  CHECK(orient.timeSamples->values[1].numbers[0] == Approx(0).margin(1e-6));
  CHECK(orient.timeSamples->values[1].numbers[1] == Approx(1));
}

TEST_CASE("AnimatedCube: texture asset paths resolve inside the package", "[usd][crate][samples]") {
  const std::string path = package("test_assets/USDZ/AnimatedCube/AnimatedCube.usdz");
  UsdzPackage pkg(path);
  CHECK(pkg.entries() == std::vector<std::string>{"AnimatedCube.imported.usdc", "0/AnimatedCube_BaseColor.png",
                                                  "0/AnimatedCube_MetallicRoughness.png"});
  CHECK(pkg.firstLayer() == "AnimatedCube.imported.usdc");
  Layer layer = readEntry(path, pkg.firstLayer());
  CHECK(layer.specs.size() == 42);
  std::vector<std::string> textures;
  for (const auto& [p, spec] : layer.specs)
    if (const Value* v = spec.field(field::kDefault); v && v->kind == Kind::AssetPath) textures.push_back(v->strings[0]);
  CHECK(textures == std::vector<std::string>{"0/AnimatedCube_BaseColor.png", "0/AnimatedCube_MetallicRoughness.png"});
  for (const auto& t : textures) {
    std::string entry = pkg.resolve(pkg.firstLayer(), t);
    CHECK(entry == t);
    auto png = pkg.read(entry);
    REQUIRE(png.size() > 8);
    CHECK(png[1] == 'P');
  }
  CHECK(pkg.resolve(pkg.firstLayer(), "./0/AnimatedCube_BaseColor.png") == "0/AnimatedCube_BaseColor.png");
  CHECK(pkg.resolve(pkg.firstLayer(), "0/missing.png").empty());
  CHECK(pkg.resolve(pkg.firstLayer(), "../AnimatedCube.usdz").empty());

  const Value& st = fieldOf(layer, "/AnimatedCube/Geom/AnimatedCube.primvars:st", field::kDefault);
  CHECK(st.kind == Kind::Vec2f);
  CHECK(st.numbers.size() == 36 * 2);
  CHECK(fieldOf(layer, "/AnimatedCube/Geom/AnimatedCube.primvars:st", field::kInterpolation).strings[0] == "vertex");
  const Value& orient = fieldOf(layer, "/AnimatedCube/Geom/AnimatedCube.xformOp:orient", field::kTimeSamples);
  REQUIRE(orient.timeSamples->times == std::vector<double>{0, 24, 48});
  CHECK(orient.timeSamples->values[0].numbers == std::vector<double>{1, 0, 0, 0});  // identity, real first
}

TEST_CASE("CesiumMan: skeleton animation arrays over time", "[usd][crate][samples]") {
  Layer layer = readEntry(package("test_assets/USDZ/CesiumMan/CesiumMan.usdz"), "CesiumMan.imported.usdc");
  CHECK(layer.specs.size() == 53);
  const std::string anim = "/CesiumMan/Animations/skelAnim_0";
  CHECK(fieldOf(layer, anim, field::kTypeName).strings[0] == "SkelAnimation");
  const Value& joints = fieldOf(layer, anim + ".joints", field::kDefault);
  CHECK(joints.kind == Kind::Token);
  CHECK(joints.isArray);
  CHECK(joints.strings.size() == 19);
  CHECK(joints.strings[1] == "Skeleton_torso_joint_1/Skeleton_torso_joint_2");
  const Value& rotations = fieldOf(layer, anim + ".rotations", field::kTimeSamples);
  REQUIRE(rotations.timeSamples->times.size() == 48);
  CHECK(rotations.timeSamples->times.front() == 1);
  CHECK(rotations.timeSamples->times.back() == 48);
  for (const Value& v : rotations.timeSamples->values) {
    CHECK(v.kind == Kind::Quatf);
    REQUIRE(v.numbers.size() == 19 * 4);
    double norm = 0;
    for (int i = 0; i < 4; ++i) norm += v.numbers[size_t(i)] * v.numbers[size_t(i)];
    CHECK(norm == Approx(1).epsilon(1e-4));
  }
  const Value& scales = fieldOf(layer, anim + ".scales", field::kTimeSamples);
  CHECK(scales.timeSamples->values[0].kind == Kind::Vec3h);
  CHECK(scales.timeSamples->values[0].numbers[0] == 1.0);
  const Value& transform = fieldOf(layer, "/CesiumMan/Geom/Z_UP.xformOp:transform", field::kDefault);
  CHECK(transform.kind == Kind::Matrix4d);
  CHECK(transform.numbers == std::vector<double>{1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1});
}

TEST_CASE("RoughnessTest: many meshes and materials", "[usd][crate][samples]") {
  const std::string path = package("test_assets/RoughnessTest/RoughnessTest.usdz");
  Layer layer = readEntry(path, "RoughnessTest.usdc");
  CHECK(layer.specs.size() == 275);
  std::set<std::string> textures;
  for (const auto& [p, spec] : layer.specs)
    if (const Value* v = spec.field(field::kDefault); v && v->kind == Kind::AssetPath) textures.insert(v->strings[0]);
  CHECK(textures == std::set<std::string>{"0/roughness-spec.png", "0/roughness.tga"});
  UsdzPackage pkg(path);
  CHECK(pkg.read(pkg.resolve("RoughnessTest.usdc", "0/roughness.tga")).size() == 196652);
}

TEST_CASE("sample crate layers cut short or with flipped bits fail cleanly", "[usd][crate][samples]") {
  const std::string path = package("test_assets/USDZ/BoxAnimated/BoxAnimated.usdz");
  UsdzPackage pkg(path);
  const auto bytes = pkg.read("BoxAnimated.imported.usdc");
  auto readsOrFailsCleanly = [](const std::vector<uint8_t>& b) {
    try {
      readCrateLayer(b, "box.usdc");
      return true;
    } catch (const UsdError& e) {
      CHECK(std::string(e.what()).rfind("box.usdc: crate ", 0) == 0);
      return false;
    }
  };
  for (size_t n = 0; n < bytes.size(); n += 3) {
    INFO("prefix of " << n << " bytes");
    CHECK_FALSE(readsOrFailsCleanly(std::vector<uint8_t>(bytes.begin(), bytes.begin() + ptrdiff_t(n))));
  }
  uint64_t state = 12345;  // a fixed sequence of positions, so a failure reproduces
  int parsed = 0;
  for (int i = 0; i < 4000; ++i) {
    state = state * 6364136223846793005u + 1442695040888963407u;
    auto flipped = bytes;
    size_t at = size_t(state >> 33) % bytes.size();
    flipped[at] = uint8_t(flipped[at] ^ (1u << ((state >> 20) & 7)));
    INFO("bit flip at byte " << at);
    parsed += readsOrFailsCleanly(flipped);
  }
  CHECK(parsed > 0);
}

TEST_CASE("readLayerFile on sample packages and their entries", "[usd][usdz][samples]") {
  const std::string cube = package("test_assets/USDZ/AnimatedCube/AnimatedCube.usdz");
  Layer root = readLayerFile(cube);
  CHECK(root.format == "usdc");
  CHECK(root.identifier == cube + "[AnimatedCube.imported.usdc]");
  CHECK(root.realPath == cube);
  CHECK(root.specs.size() == 42);
  CHECK(readLayerFile(cube + "[AnimatedCube.imported.usdc]").specs.size() == 42);
  CHECK_THROWS_WITH(readLayerFile(cube + "[0/AnimatedCube_BaseColor.png]"),
                    cube + "[0/AnimatedCube_BaseColor.png]: neither a crate layer (\"PXR-USDC\") nor a usda layer "
                           "(\"#usda\")");
  // A package whose root layer is text.
  const std::string normals = package("test_assets/NormalsTextureBiasAndScale/NormalsTextureBiasAndScale.usdz");
  Layer text = readLayerFile(normals);
  CHECK(text.format == "usda");
  CHECK(text.identifier == normals + "[NormalsTextureBiasAndScale.usda]");
  CHECK(text.specs.size() > 10);
}

TEST_CASE("every sample package composes, its textures resolved inside it", "[usd][usdz][samples]") {
  LayerReader reader = [](const std::string& identifier) { return readLayerFile(identifier); };
  size_t textures = 0;
  for (const std::string& path : sampleFiles({".usdz"})) {
    INFO(path);
    ComposedStage stage = composeStage(path, reader);
    CHECK(stage.prims.size() > 5);
    CHECK_FALSE(stage.defaultPrim.empty());
    UsdzPackage pkg(path);
    for (const ComposedPrim& prim : stage.prims) {
      for (const ComposedProperty& property : prim.properties) {
        for (const std::string& asset : property.resolvedAssets) {
          INFO(prim.path << "." << property.name << " = " << asset);
          auto [packagePath, entry] = splitPackagePath(asset);
          CHECK(packagePath == path);
          CHECK(pkg.contains(entry));
          ++textures;
        }
      }
    }
  }
  CHECK(textures >= 10);
}
