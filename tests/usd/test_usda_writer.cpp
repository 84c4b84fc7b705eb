// writeUsdaLayer against readUsdaLayer: a layer written as text and read
// back holds the same specs and fields — for a hand-made layer with every
// kind of value and structure, and for every real sample layer (the crate
// layers inside the packages, and the text layers), compared field by
// field. Reading back adds what usda always states (an attribute's custom
// and variability, a prim's `over`), so both sides drop fields equal to
// Sdf's fallbacks before comparing.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "usd/layer_io.h"
#include "usd/samples_dir.h"
#include "usd/usda_writer.h"
#include "usd/usdz_package.h"

using namespace sdg::usd;
using sdg::usd::test::sampleFiles;

namespace {

// A spec's fields without those equal to Sdf's fallbacks (which usda
// writes out, so the reader states them), and with a crate 0.8 single
// payload as the explicit list op Sdf reads it as.
std::map<std::string, Value> normalized(const Spec& spec) {
  std::map<std::string, Value> fields = spec.fields;
  auto dropIf = [&](const char* key, auto pred) {
    if (auto it = fields.find(key); it != fields.end() && pred(it->second)) fields.erase(it);
  };
  dropIf(field::kCustom, [](const Value& v) { return v.kind == Kind::Bool && v.numbers == std::vector<double>{0}; });
  const Variability fallback = spec.type == SpecType::Relationship ? Variability::Uniform : Variability::Varying;
  dropIf(field::kVariability, [&](const Value& v) { return v.kind == Kind::Variability && v.enumValue == int(fallback); });
  dropIf(field::kSpecifier, [](const Value& v) { return v.enumValue == int(Specifier::Over); });
  dropIf(field::kSubLayerOffsets, [](const Value& v) {
    return v.layerOffsets && std::all_of(v.layerOffsets->begin(), v.layerOffsets->end(),
                                         [](const LayerOffset& o) { return o == LayerOffset{}; });
  });
  for (auto it = fields.begin(); it != fields.end();) {
    const Value& v = it->second;
    bool emptyEdit = (v.textListOp && v.textListOp->empty()) || (v.intListOp && v.intListOp->empty()) ||
                     (v.referenceListOp && v.referenceListOp->empty());
    it = emptyEdit ? fields.erase(it) : std::next(it);
  }
  if (auto it = fields.find(field::kPayload); it != fields.end() && it->second.kind == Kind::Payload) {
    Value op;
    op.kind = Kind::PayloadListOp;
    op.referenceListOp = std::make_shared<ListOp<Reference>>();
    op.referenceListOp->isExplicit = true;
    op.referenceListOp->explicitItems = *it->second.references;
    it->second = op;
  }
  return fields;
}

std::string describe(const Value& v) {
  std::string s = std::string(kindName(v.kind)) + (v.isArray ? "[]" : "");
  if (!v.numbers.empty()) s += " numbers[" + std::to_string(v.numbers.size()) + "]";
  if (!v.strings.empty()) s += " '" + v.strings[0] + "'";
  return s;
}

// Every spec of `a` is in `b` with the same type and fields, and no more.
void checkSameLayer(const Layer& a, const Layer& b) {
  for (const auto& [path, spec] : a.specs) {
    INFO("<" << path << ">");
    const Spec* other = b.spec(path);
    REQUIRE(other);
    CHECK(int(other->type) == int(spec.type));
    auto fa = normalized(spec), fb = normalized(*other);
    for (const auto& [key, value] : fa) {
      INFO("field '" << key << "' " << describe(value));
      auto it = fb.find(key);
      REQUIRE(it != fb.end());
      CHECK(it->second == value);
    }
    for (const auto& [key, value] : fb) {
      INFO("field '" << key << "' only after the round trip: " << describe(value));
      CHECK(fa.count(key));
    }
  }
  CHECK(a.specs.size() == b.specs.size());
}

// Written, read back, compared; the text of the read-back layer is the same text.
std::string roundTrip(const Layer& layer) {
  std::string text = writeUsdaLayer(layer);
  INFO(text.substr(0, 4000));
  Layer back = readUsdaLayer(text, layer.identifier + ".written.usda");
  checkSameLayer(layer, back);
  CHECK(writeUsdaLayer(back) == text);
  return text;
}

Value tokens(std::vector<std::string> items) { return Value::textArray(Kind::TokenVector, std::move(items)); }

template <class T>
Value listOp(Kind kind, ListOp<T> op) {
  Value v;
  v.kind = kind;
  if constexpr (std::is_same_v<T, std::string>) v.textListOp = std::make_shared<ListOp<T>>(std::move(op));
  if constexpr (std::is_same_v<T, int64_t>) v.intListOp = std::make_shared<ListOp<T>>(std::move(op));
  if constexpr (std::is_same_v<T, Reference>) v.referenceListOp = std::make_shared<ListOp<T>>(std::move(op));
  return v;
}

Spec spec(SpecType type, std::map<std::string, Value> fields) {
  Spec s;
  s.type = type;
  s.fields = std::move(fields);
  return s;
}


}  // namespace

TEST_CASE("usda writer: every kind of value and structure round-trips", "[usd][usda-writer]") {
  Layer layer;
  layer.identifier = "made.usda";
  Dictionary inner{{"depth", Value::scalar(Kind::Int, {2})}, {"names", Value::textArray(Kind::Token, {"a", "b"})}};
  Dictionary custom{{"creator", Value::text(Kind::String, "sdg \"tests\"\n\ttabbed \\ \x01 ünïcode")},
                    {"nested", Value::dict(inner)},
                    {"weights", Value::array(Kind::Float, {0.1f, 0.25f, -3.0f})},
                    {"on", Value::scalar(Kind::Bool, {1})},
                    {"where", Value::text(Kind::AssetPath, "./a@b.png")}};
  Value offsets;
  offsets.kind = Kind::LayerOffsetVector;
  offsets.layerOffsets = std::make_shared<std::vector<LayerOffset>>(
      std::vector<LayerOffset>{{10, 2}, {0, 1}});
  layer.specs["/"] = spec(SpecType::PseudoRoot,
                          {{field::kDefaultPrim, Value::text(Kind::Token, "World")},
                           {field::kUpAxis, Value::text(Kind::Token, "Z")},
                           {field::kMetersPerUnit, Value::scalar(Kind::Double, {0.01})},
                           {field::kStartTimeCode, Value::scalar(Kind::Double, {1})},
                           {field::kCustomLayerData, Value::dict(custom)},
                           {field::kDocumentation, Value::text(Kind::String, "line one\nline two")},
                           {field::kSubLayers, Value::textArray(Kind::StringVector, {"sub/a.usda", "b.usdc"})},
                           {field::kSubLayerOffsets, offsets},
                           {field::kPrimChildren, tokens({"World", "Base"})}});

  ListOp<Reference> refs;
  Reference r1;
  r1.assetPath = "./parts/bolt.usd";
  r1.primPath = "/Bolt";
  r1.offset = {5, 0.5};
  r1.customData = std::make_shared<Dictionary>(Dictionary{{"note", Value::text(Kind::String, "hi")}});
  Reference r2;
  r2.primPath = "/Base";
  refs.prependedItems = {r1, r2};
  ListOp<Reference> payloads;
  Reference p1;
  p1.assetPath = "heavy.usdc";
  payloads.isExplicit = true;
  payloads.explicitItems = {p1};
  ListOp<std::string> apis;
  apis.prependedItems = {"MaterialBindingAPI"};
  apis.deletedItems = {"Old"};
  ListOp<std::string> inherits;
  inherits.appendedItems = {"/Base"};
  ListOp<std::string> setNames;
  setNames.prependedItems = {"look"};
  Value selection;
  selection.kind = Kind::VariantSelectionMap;
  selection.dictionary = std::make_shared<Dictionary>(Dictionary{{"look", Value::text(Kind::String, "red")}});
  Value permission;
  permission.kind = Kind::Permission;
  permission.enumValue = int(Permission::Private);
  layer.specs["/World"] = spec(SpecType::Prim,
                               {{field::kSpecifier, Value::specifier(Specifier::Def)},
                                {field::kTypeName, Value::text(Kind::Token, "Xform")},
                                {field::kKind, Value::text(Kind::Token, "component")},
                                {field::kActive, Value::scalar(Kind::Bool, {1})},
                                {field::kReferences, listOp(Kind::ReferenceListOp, refs)},
                                {field::kPayload, listOp(Kind::PayloadListOp, payloads)},
                                {field::kApiSchemas, listOp(Kind::TokenListOp, apis)},
                                {field::kInheritPaths, listOp(Kind::PathListOp, inherits)},
                                {field::kVariantSetNames, listOp(Kind::StringListOp, setNames)},
                                {field::kVariantSelection, selection},
                                {field::kPermission, permission},
                                {field::kPrimOrder, tokens({"Mesh"})},
                                {field::kPrimChildren, tokens({"Mesh"})},
                                {field::kProperties, tokens({"size", "rel"})},
                                {field::kVariantSetChildren, tokens({"look"})}});
  layer.specs["/World.size"] = spec(SpecType::Attribute, {{field::kTypeName, Value::text(Kind::Token, "double")},
                                                          {field::kDefault, Value::scalar(Kind::Double, {0.1})},
                                                          {field::kCustom, Value::scalar(Kind::Bool, {1})}});
  ListOp<std::string> targets;
  targets.isExplicit = true;
  targets.explicitItems = {"/World/Mesh", "/World/Mesh.points"};
  ListOp<std::string> moreTargets;
  moreTargets.appendedItems = {"/Base"};
  moreTargets.deletedItems = {"/Gone"};
  layer.specs["/World.rel"] = spec(SpecType::Relationship,
                                   {{field::kTargetPaths, listOp(Kind::PathListOp, targets)},
                                    {field::kVariability, Value::variability(Variability::Uniform)}});
  layer.specs["/World{look=}"] = spec(SpecType::VariantSet, {{field::kVariantChildren, tokens({"red", "blue"})}});
  layer.specs["/World{look=red}"] = spec(SpecType::Variant, {{field::kDocumentation, Value::text(Kind::String, "red")},
                                                             {field::kPrimChildren, tokens({"Extra"})}});
  layer.specs["/World{look=red}Extra"] = spec(SpecType::Prim, {{field::kSpecifier, Value::specifier(Specifier::Over)},
                                                               {field::kProperties, tokens({"color"})}});
  layer.specs["/World{look=red}Extra.color"] =
      spec(SpecType::Attribute, {{field::kTypeName, Value::text(Kind::Token, "color3f")},
                                 {field::kDefault, Value::scalar(Kind::Vec3f, {1, 0.2f, 0})}});
  layer.specs["/World{look=blue}"] = spec(SpecType::Variant, {});

  // The mesh: one attribute per numeric kind (scalars and arrays), text kinds, samples, connections.
  std::map<std::string, Value> meshFields{{field::kSpecifier, Value::specifier(Specifier::Def)},
                                          {field::kTypeName, Value::text(Kind::Token, "Mesh")}};
  std::vector<std::string> properties;
  auto add = [&](const std::string& name, const std::string& typeName, std::map<std::string, Value> fields) {
    fields[field::kTypeName] = Value::text(Kind::Token, typeName);
    layer.specs["/World/Mesh." + name] = spec(SpecType::Attribute, std::move(fields));
    properties.push_back(name);
  };
  const double inf = std::numeric_limits<double>::infinity();
  add("b", "bool", {{field::kDefault, Value::scalar(Kind::Bool, {1})}});
  add("uc", "uchar[]", {{field::kDefault, Value::array(Kind::UChar, {0, 255})}});
  add("i", "int", {{field::kDefault, Value::scalar(Kind::Int, {-2147483648.0})},
                   {field::kVariability, Value::variability(Variability::Uniform)}});
  add("u", "uint", {{field::kDefault, Value::scalar(Kind::UInt, {4294967295.0})}});
  add("i64", "int64[]", {{field::kDefault, Value::array(Kind::Int64, {-9007199254740992.0, 3})}});
  add("u64", "uint64", {{field::kDefault, Value::scalar(Kind::UInt64, {18446744073709551615.0})}});
  add("h", "half[]", {{field::kDefault, Value::array(Kind::Half, {0.0999755859375, -65504, 6.103515625e-05})}});
  add("f", "float[]", {{field::kDefault, Value::array(Kind::Float, {0.1f, 1e-30f, 3.4028234663852886e38, -inf})}});
  add("d", "double[]", {{field::kDefault, Value::array(Kind::Double, {0.1, 1e-300, 2.0 / 3, inf, -0.0})}});
  add("tc", "timecode", {{field::kDefault, Value::scalar(Kind::TimeCode, {24.5})}});
  add("v2i", "int2", {{field::kDefault, Value::scalar(Kind::Vec2i, {1, -2})}});
  add("v3h", "half3[]", {{field::kDefault, Value::array(Kind::Vec3h, {1, 0.5, -2, 0, 0, 0})}});
  add("points", "point3f[]", {{field::kDefault, Value::array(Kind::Vec3f, {0.1f, 0.2f, 0.3f, 1, 2, 3})},
                              {field::kInterpolation, Value::text(Kind::Token, "vertex")},
                              {field::kElementSize, Value::scalar(Kind::Int, {1})}});
  add("v4d", "double4", {{field::kDefault, Value::scalar(Kind::Vec4d, {1, 2, 3, 4})}});
  add("q", "quatf", {{field::kDefault, Value::scalar(Kind::Quatf, {0.9f, 0.1f, 0.2f, 0.3f})}});
  add("qh", "quath[]", {{field::kDefault, Value::array(Kind::Quath, {1, 0, 0, 0})}});
  add("m2", "matrix2d", {{field::kDefault, Value::scalar(Kind::Matrix2d, {1, 2, 3, 4})}});
  add("m4", "matrix4d[]", {{field::kDefault, Value::array(Kind::Matrix4d, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1})}});
  add("s", "string", {{field::kDefault, Value::text(Kind::String, "say \"hi\"\\n")}});
  add("t", "token[]", {{field::kDefault, Value::textArray(Kind::Token, {"a", "b c", ""})}});
  add("tex", "asset", {{field::kDefault, Value::text(Kind::AssetPath, "0/wood@2x.png")},
                       {field::kColorSpace, Value::text(Kind::Token, "raw")}});
  add("texs", "asset[]", {{field::kDefault, Value::textArray(Kind::AssetPath, {"a.png", "b@@@c.png"})}});
  add("blocked", "float", {{field::kDefault, Value::block()}});
  add("empty", "float[]", {{field::kDefault, Value::array(Kind::Float, {})}});
  add("declared", "normal3f[]", {{field::kCustomData, Value::dict({{"x", Value::scalar(Kind::Double, {1})}})}});
  auto samples = std::make_shared<TimeSamples>();
  samples->times = {0, 12.5, 24};
  samples->values = {Value::scalar(Kind::Vec3d, {0, 0, 0}), Value::block(), Value::scalar(Kind::Vec3d, {1, 2, 3})};
  Value sampled;
  sampled.kind = Kind::TimeSamples;
  sampled.timeSamples = samples;
  add("xformOp:translate", "double3", {{field::kTimeSamples, sampled}, {field::kDefault, Value::scalar(Kind::Vec3d, {9, 9, 9})}});
  ListOp<std::string> connections;
  connections.isExplicit = true;
  connections.explicitItems = {"/World/Mesh.points"};
  add("outputs:surface", "token", {{field::kConnectionPaths, listOp(Kind::PathListOp, connections)}});
  meshFields[field::kProperties] = tokens(properties);
  layer.specs["/World/Mesh"] = spec(SpecType::Prim, std::move(meshFields));
  layer.specs["/Base"] = spec(SpecType::Prim, {{field::kSpecifier, Value::specifier(Specifier::Class)}});

  std::string text = roundTrip(layer);
  CHECK_THAT(text, Catch::StartsWith("#usda 1.0\n(\n"));
  CHECK_THAT(text, Catch::Contains("uniform int i = -2147483648\n"));
  CHECK_THAT(text, Catch::Contains("float[] f = [0.1, 1e-30, 3.4028235e+38, -inf]\n"));
  CHECK_THAT(text, Catch::Contains("quatf q = (0.9, 0.1, 0.2, 0.3)\n"));
  CHECK_THAT(text, Catch::Contains("asset tex = @@@0/wood@2x.png@@@ (\n"));
  CHECK_THAT(text, Catch::Contains("string s = \"say \\\"hi\\\"\\\\n\"\n"));
  CHECK_THAT(text, Catch::Contains("prepend references = [@./parts/bolt.usd@</Bolt> (offset = 5; scale = 0.5; customData = {"));
  CHECK_THAT(text, Catch::Contains("double3 xformOp:translate.timeSamples = {\n"));
  CHECK_THAT(text, Catch::Contains("        12.5: None,\n"));
  CHECK_THAT(text, Catch::Contains("variantSet \"look\" = {\n"));

  SECTION("the relationship's other list edits") {
    layer.specs["/World.rel"].fields[field::kTargetPaths] = listOp(Kind::PathListOp, moreTargets);
    roundTrip(layer);
  }
}

TEST_CASE("usda writer: what usda cannot hold", "[usd][usda-writer]") {
  Layer layer;
  layer.identifier = "odd.usdc";
  Value expression;
  expression.kind = Kind::Unsupported;
  expression.strings = {"PathExpression", "/World//*"};
  layer.specs["/"] = spec(SpecType::PseudoRoot, {{"layerRelocates", expression}, {field::kPrimChildren, tokens({"A"})}});
  layer.specs["/A"] = spec(SpecType::Prim, {{field::kSpecifier, Value::specifier(Specifier::Def)},
                                            {"odd", Value::scalar(Kind::Quatd, {1, 0, 0, 0})}});
  std::string text = writeUsdaLayer(layer);
  CHECK_THAT(text, Catch::Contains("# 'layerRelocates' (PathExpression) is not written: usda has no form for it here"));
  CHECK_THAT(text, Catch::Contains("    odd = (1, 0, 0, 0)\n"));  // untyped: reads back as a double4
  Layer back = readUsdaLayer(text, "back.usda");
  CHECK_FALSE(back.spec("/")->field("layerRelocates"));
  CHECK(back.spec("/A")->field("odd")->kind == Kind::Vec4d);

  layer.specs["/A.x"] = spec(SpecType::Attribute, {{field::kDefault, Value::scalar(Kind::Double, {1})}});
  CHECK_THROWS_WITH(writeUsdaLayer(layer), "odd.usdc: cannot write </A.x> as usda: the attribute has no typeName");
}

TEST_CASE("usda writer: every sample layer round-trips, crate and text", "[usd][usda-writer][samples]") {
  size_t layers = 0;
  for (const std::string& path : sampleFiles({".usdz"})) {
    UsdzPackage pkg(path);
    for (const auto& entry : pkg.entries()) {
      if (entry.size() < 5 || entry.substr(entry.size() - 5) != ".usdc") continue;
      INFO(path << "[" << entry << "]");
      Layer layer = readCrateLayer(pkg.read(entry), path + "[" + entry + "]");
      roundTrip(layer);
      ++layers;
    }
  }
  for (const std::string& path : sampleFiles({".usda", ".usd"})) {
    INFO(path);
    Layer layer = readLayerFile(path);
    roundTrip(layer);
    ++layers;
  }
  CHECK(layers >= 20);
}

TEST_CASE("usda writer: text that would grow without bound stops at the limit", "[usd][usda-writer]") {
  // Dictionaries sharing their entries level after level (as a crate file
  // can store them): 2^40 lines if spelled out.
  Value level = Value::dict({{"leaf", Value::scalar(Kind::Int, {1})}});
  for (int i = 0; i < 40; ++i) level = Value::dict({{"a", level}, {"b", level}});
  Layer layer;
  layer.identifier = "dag.usdc";
  layer.specs["/"] = spec(SpecType::PseudoRoot, {{field::kCustomLayerData, level}});
  CHECK_THROWS_WITH(writeUsdaLayer(layer, 1 << 20), "dag.usdc: the usda text would pass 1048576 bytes");
}
