// Crate files crafted by hand (crate_builder.h), one feature at a time: every
// value type the crate stores, inlined and out of line, plain and compressed
// arrays, and what each format version changes (array sizes and ranks before
// 0.7.0/0.5.0, compression from 0.5.0/0.6.0, payload layer offsets from
// 0.8.0, TimeCode in 0.9.0, path expressions in 0.10.0, relocates in 0.11.0).
#include <catch2/catch.hpp>

#include "usd/crate_builder.h"
#include "usd/layer_io.h"

using namespace sdg::usd;
using namespace sdg::usd::test;
using T = CrateType;

namespace {

const Spec& specAt(const Layer& layer, const std::string& path) {
  const Spec* spec = layer.spec(path);
  INFO(path);
  REQUIRE(spec);
  return *spec;
}

Layer finishAndRead(CrateBuilder& b) {
  auto bytes = b.finish();
  return readCrateLayer(bytes, "test.usdc");
}

// An attribute </P.a> whose field `name` holds `valueRep`: the decoded value.
Value readBack(CrateBuilder& b, uint64_t valueRep, const std::string& name = "default") {
  b.spec("/", SpecType::PseudoRoot, {});
  b.spec("/P.a", SpecType::Attribute, {b.field(name, valueRep)});
  Layer layer = finishAndRead(b);
  return specAt(layer, "/P.a").fields.at(name);
}

std::vector<double> nums(std::initializer_list<double> v) { return v; }

uint16_t half(float f) {  // exact for the values used here
  uint32_t bits;
  std::memcpy(&bits, &f, 4);
  if ((bits & 0x7fffffff) == 0) return uint16_t(bits >> 16);
  uint32_t exponent = ((bits >> 23) & 0xff) - 112;
  return uint16_t(((bits >> 16) & 0x8000) | (exponent << 10) | ((bits >> 13) & 0x3ff));
}

}  // namespace

TEST_CASE("crate scalars held in the value rep", "[usd][crate]") {
  struct Case {
    uint64_t rep;
    Kind kind;
    std::vector<double> numbers;
  };
  float f = -2.5f;
  uint32_t fbits;
  std::memcpy(&fbits, &f, 4);
  int8_t vec[4] = {1, -2, 3, 0};
  uint32_t vbits;
  std::memcpy(&vbits, vec, 4);
  const Case cases[] = {
      {rep(T::Bool, 1), Kind::Bool, {1}},
      {rep(T::UChar, 200), Kind::UChar, {200}},
      {rep(T::Int, uint32_t(-7)), Kind::Int, {-7}},
      {rep(T::UInt, 4000000000u), Kind::UInt, {4e9}},
      {rep(T::Half, half(-2.5f)), Kind::Half, {-2.5}},
      {rep(T::Float, fbits), Kind::Float, {-2.5}},
      {inlined(T::Int64, uint32_t(-5)), Kind::Int64, {-5}},
      {inlined(T::UInt64, 3000000000u), Kind::UInt64, {3e9}},
      {inlined(T::Double, fbits), Kind::Double, {-2.5}},
      {inlined(T::Vec3f, vbits), Kind::Vec3f, {1, -2, 3}},
      {inlined(T::Vec2i, vbits), Kind::Vec2i, {1, -2}},
      {inlined(T::Vec4h, vbits), Kind::Vec4h, {1, -2, 3, 0}},
      {inlined(T::Matrix2d, vbits), Kind::Matrix2d, {1, 0, 0, -2}},
      {inlined(T::Matrix4d, 0x01010101), Kind::Matrix4d, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}},
  };
  for (const auto& c : cases) {
    CrateBuilder b;
    Value v = readBack(b, c.rep);
    INFO(int(c.kind));
    CHECK(v.kind == c.kind);
    CHECK_FALSE(v.isArray);
    CHECK(v.numbers == c.numbers);
  }
}

TEST_CASE("crate enums, text and blocks in the value rep", "[usd][crate]") {
  {
    CrateBuilder b;
    Value v = readBack(b, rep(T::Specifier, 2), "specifier");
    CHECK(v.kind == Kind::Specifier);
    CHECK(v.enumValue == int(Specifier::Class));
  }
  {
    CrateBuilder b;  // the legacy "config" variability reads as uniform
    Value v = readBack(b, rep(T::Variability, 2), "variability");
    CHECK(v.enumValue == int(Variability::Uniform));
  }
  {
    CrateBuilder b;
    Value v = readBack(b, rep(T::Permission, 1), "permission");
    CHECK(v.kind == Kind::Permission);
    CHECK(v.enumValue == int(Permission::Private));
  }
  {
    CrateBuilder b;
    Value v = readBack(b, rep(T::Token, b.token("hello")));
    CHECK(v.kind == Kind::Token);
    CHECK(v.strings == std::vector<std::string>{"hello"});
  }
  {
    CrateBuilder b;
    Value v = readBack(b, rep(T::String, b.string("a \"quoted\"\nstring")));
    CHECK(v.kind == Kind::String);
    CHECK(v.strings[0] == "a \"quoted\"\nstring");
  }
  {
    CrateBuilder b;  // a scalar asset path holds a token index
    Value v = readBack(b, rep(T::AssetPath, b.token("./textures/wood.png")));
    CHECK(v.kind == Kind::AssetPath);
    CHECK(v.strings[0] == "./textures/wood.png");
  }
  {
    CrateBuilder b;
    CHECK(readBack(b, rep(T::ValueBlock, 0)).kind == Kind::ValueBlock);
  }
  {
    CrateBuilder b;
    Value v = readBack(b, inlined(T::Dictionary, 0), "customData");
    CHECK(v.kind == Kind::Dictionary);
    CHECK(v.dictionary->empty());
  }
}

TEST_CASE("crate scalars stored out of line", "[usd][crate]") {
  SECTION("int64, uint64, double, TimeCode") {
    CrateBuilder b(9);
    uint64_t big = b.put<int64_t>(-(int64_t(1) << 40));
    uint64_t ubig = b.put<uint64_t>(uint64_t(1) << 50);
    uint64_t d = b.put(0.1);
    uint64_t tc = b.put(12.5);
    b.spec("/", SpecType::PseudoRoot, {});
    b.spec("/P.a", SpecType::Attribute,
           {b.field("i", rep(T::Int64, big)), b.field("u", rep(T::UInt64, ubig)), b.field("d", rep(T::Double, d)),
            b.field("t", rep(T::TimeCode, tc))});
    Layer layer = finishAndRead(b);
    const Spec& s = specAt(layer, "/P.a");
    CHECK(s.fields.at("i").numbers == nums({-1099511627776.0}));
    CHECK(s.fields.at("u").numbers == nums({1125899906842624.0}));
    CHECK(s.fields.at("d").numbers == nums({0.1}));
    CHECK(s.fields.at("t").kind == Kind::TimeCode);
    CHECK(s.fields.at("t").numbers == nums({12.5}));
  }
  SECTION("vectors, quaternions (stored imaginary first) and matrices") {
    CrateBuilder b;
    uint64_t v3d = b.putAll(std::vector<double>{0.5, 1.5, -2.25});
    uint64_t v2h = b.putAll(std::vector<uint16_t>{half(0.5f), half(-8.0f)});
    uint64_t qf = b.putAll(std::vector<float>{0.1f, 0.2f, 0.3f, 0.9f});  // i, j, k, real
    uint64_t qh = b.putAll(std::vector<uint16_t>{half(0.5f), 0, 0, half(-0.5f)});
    uint64_t qd = b.putAll(std::vector<double>{1, 2, 3, 4});
    std::vector<double> m3{1, 2, 3, 4, 5, 6, 7, 8, 9.5};
    uint64_t m = b.putAll(m3);
    b.spec("/", SpecType::PseudoRoot, {});
    b.spec("/P.a", SpecType::Attribute,
           {b.field("v3d", rep(T::Vec3d, v3d)), b.field("v2h", rep(T::Vec2h, v2h)), b.field("qf", rep(T::Quatf, qf)),
            b.field("qh", rep(T::Quath, qh)), b.field("qd", rep(T::Quatd, qd)), b.field("m", rep(T::Matrix3d, m))});
    Layer layer = finishAndRead(b);
    const Spec& s = specAt(layer, "/P.a");
    CHECK(s.fields.at("v3d").numbers == nums({0.5, 1.5, -2.25}));
    CHECK(s.fields.at("v2h").numbers == nums({0.5, -8}));
    CHECK(s.fields.at("qf").kind == Kind::Quatf);
    CHECK(s.fields.at("qf").numbers == std::vector<double>{0.9f, 0.1f, 0.2f, 0.3f});
    CHECK(s.fields.at("qh").numbers == nums({-0.5, 0.5, 0, 0}));
    CHECK(s.fields.at("qd").numbers == nums({4, 1, 2, 3}));
    CHECK(s.fields.at("m").kind == Kind::Matrix3d);
    CHECK(s.fields.at("m").numbers == m3);
  }
}

TEST_CASE("crate arrays, plain and compressed", "[usd][crate]") {
  CrateBuilder b;
  std::vector<float> points{0, 1, 2, 3.5f, 4, 5};
  b.align(8);
  uint64_t pts = b.put<uint64_t>(2);
  b.putAll(points);
  uint64_t shortInts = b.put<uint64_t>(3);  // fewer than 16: never compressed, even when flagged
  b.putAll(std::vector<int32_t>{-1, 0, 7});
  std::vector<int32_t> ints;
  for (int i = 0; i < 100; ++i) ints.push_back(i * i - 50);
  uint64_t manyInts = b.put<uint64_t>(ints.size());
  b.putCompressed(ints);
  std::vector<uint64_t> wide;
  for (uint64_t i = 0; i < 40; ++i) wide.push_back(i << 40);
  uint64_t manyWide = b.put<uint64_t>(wide.size());
  b.putCompressed(wide);
  std::vector<int32_t> floatsAsInts;  // floats that are all integers: code 'i'
  for (int i = 0; i < 20; ++i) floatsAsInts.push_back(i % 3 - 1);
  uint64_t intFloats = b.put<uint64_t>(floatsAsInts.size());
  b.put('i');
  b.putCompressed(floatsAsInts);
  std::vector<double> table{0.25, -1e300};  // few distinct doubles: code 't', a table and indexes
  std::vector<uint32_t> indexes;
  for (int i = 0; i < 30; ++i) indexes.push_back(uint32_t(i % 7 == 0));
  uint64_t lut = b.put<uint64_t>(indexes.size());
  b.put('t');
  b.put<uint32_t>(uint32_t(table.size()));
  b.putAll(table);
  b.putCompressed(indexes);
  uint64_t halves = b.put<uint64_t>(17);
  b.put('i');
  b.putCompressed(std::vector<int32_t>(17, 2));
  uint64_t bools = b.put<uint64_t>(3);
  b.putAll(std::vector<uint8_t>{1, 0, 1});
  uint64_t quats = b.put<uint64_t>(1);
  b.putAll(std::vector<float>{0, 0, 1, 0.5f});
  uint64_t mats = b.put<uint64_t>(1);
  b.putAll(std::vector<double>{2, 0, 0, 2});
  uint64_t tokens = b.put<uint64_t>(2);
  b.putAll(std::vector<uint32_t>{b.token("x"), b.token("y")});
  uint64_t strings = b.put<uint64_t>(2);
  b.putAll(std::vector<uint32_t>{b.string("one"), b.string("two")});
  uint64_t assets = b.put<uint64_t>(1);  // array elements are string indexes (a scalar's a token index)
  b.put<uint32_t>(b.string("@tex.png"));

  b.spec("/", SpecType::PseudoRoot, {});
  b.spec("/P.a", SpecType::Attribute,
         {b.field("points", rep(T::Vec3f, pts, true)), b.field("short", rep(T::Int, shortInts, true, false, true)),
          b.field("ints", rep(T::Int, manyInts, true, false, true)),
          b.field("wide", rep(T::UInt64, manyWide, true, false, true)),
          b.field("intFloats", rep(T::Float, intFloats, true, false, true)),
          b.field("lut", rep(T::Double, lut, true, false, true)),
          b.field("halves", rep(T::Half, halves, true, false, true)), b.field("bools", rep(T::Bool, bools, true)),
          b.field("quats", rep(T::Quatf, quats, true)), b.field("mats", rep(T::Matrix2d, mats, true)),
          b.field("tokens", rep(T::Token, tokens, true)), b.field("strings", rep(T::String, strings, true)),
          b.field("assets", rep(T::AssetPath, assets, true)), b.field("empty", rep(T::Float, 0, true))});
  Layer layer = finishAndRead(b);
  const auto& f = specAt(layer, "/P.a").fields;
  CHECK(f.at("points").kind == Kind::Vec3f);
  CHECK(f.at("points").isArray);
  CHECK(f.at("points").numbers == nums({0, 1, 2, 3.5, 4, 5}));
  CHECK(f.at("short").numbers == nums({-1, 0, 7}));
  CHECK(f.at("ints").numbers == std::vector<double>(ints.begin(), ints.end()));
  CHECK(f.at("wide").numbers == std::vector<double>(wide.begin(), wide.end()));
  CHECK(f.at("intFloats").numbers == std::vector<double>(floatsAsInts.begin(), floatsAsInts.end()));
  std::vector<double> expected;
  for (auto i : indexes) expected.push_back(table[i]);
  CHECK(f.at("lut").numbers == expected);
  CHECK(f.at("halves").numbers == std::vector<double>(17, 2.0));
  CHECK(f.at("bools").numbers == nums({1, 0, 1}));
  CHECK(f.at("quats").numbers == nums({0.5, 0, 0, 1}));
  CHECK(f.at("mats").numbers == nums({2, 0, 0, 2}));
  CHECK(f.at("tokens").strings == std::vector<std::string>{"x", "y"});
  CHECK(f.at("strings").strings == std::vector<std::string>{"one", "two"});
  CHECK(f.at("assets").kind == Kind::AssetPath);
  CHECK(f.at("assets").strings == std::vector<std::string>{"@tex.png"});
  CHECK(f.at("empty").isArray);
  CHECK(f.at("empty").numbers.empty());
}

TEST_CASE("crate dictionaries, list ops, references and vectors", "[usd][crate]") {
  CrateBuilder b;
  // A dictionary: count, then per entry a key (string index), an offset to
  // the entry's value rep, and the rep; values may nest.
  uint64_t inner = b.put<uint64_t>(1);
  b.put(b.string("depth"));
  b.put<int64_t>(8);
  b.put(rep(T::Int, 2));
  std::vector<double> doubles{1.5, 2.5};
  uint64_t arr = b.put<uint64_t>(doubles.size());
  b.putAll(doubles);
  uint64_t dict = b.put<uint64_t>(3);
  b.put(b.string("name"));
  b.put<int64_t>(8);
  b.put(rep(T::String, b.string("wood")));
  b.put(b.string("nested"));
  b.put<int64_t>(8);
  b.put(rep(T::Dictionary, inner));
  b.put(b.string("values"));
  b.put<int64_t>(8);
  b.put(rep(T::Double, arr, true));

  uint64_t tokenOp = b.put<uint8_t>(1 << 5 | 1 << 6 | 1 << 3);  // prepended, appended, deleted
  b.put<uint64_t>(1), b.put(b.token("A"));
  b.put<uint64_t>(2), b.put(b.token("B")), b.put(b.token("C"));
  b.put<uint64_t>(1), b.put(b.token("D"));
  uint64_t pathOp = b.put<uint8_t>(1 | 1 << 1);  // explicit, with items
  b.put<uint64_t>(1), b.put(b.path("/Target.out"));
  uint64_t stringOp = b.put<uint8_t>(1 << 2 | 1 << 4);  // added, ordered (the old forms)
  b.put<uint64_t>(1), b.put(b.string("s1"));
  b.put<uint64_t>(1), b.put(b.string("s2"));
  uint64_t intOp = b.put<uint8_t>(1 << 5);
  b.put<uint64_t>(2), b.put<int32_t>(-3), b.put<int32_t>(9);
  uint64_t uint64Op = b.put<uint8_t>(1 << 6);
  b.put<uint64_t>(1), b.put<uint64_t>(uint64_t(1) << 40);
  uint64_t uintOp = b.put<uint8_t>(1 << 6);
  b.put<uint64_t>(1), b.put<uint32_t>(4000000000u);
  uint64_t int64Op = b.put<uint8_t>(1 << 3);
  b.put<uint64_t>(1), b.put<int64_t>(-(int64_t(1) << 35));

  // References: asset path (string), prim path, layer offset, custom data.
  uint64_t refOp = b.put<uint8_t>(1 << 5);
  b.put<uint64_t>(2);
  b.put(b.string("./parts/bolt.usd")), b.put(b.path("/Bolt")), b.put(10.0), b.put(2.0);
  b.put<uint64_t>(1), b.put(b.string("note")), b.put<int64_t>(8), b.put(rep(T::Token, b.token("hi")));
  b.put(b.string("")), b.put(b.emptyPath()), b.put(0.0), b.put(1.0), b.put<uint64_t>(0);
  uint64_t payloadOp = b.put<uint8_t>(1 | 1 << 1);
  b.put<uint64_t>(1), b.put(b.string("heavy.usdc")), b.put(b.path("/Heavy")), b.put(0.0), b.put(1.0);
  uint64_t payload = b.put(b.string("single.usd"));
  b.put(b.path("/Single")), b.put(5.0), b.put(1.0);

  uint64_t pathVec = b.put<uint64_t>(2);
  b.put(b.path("/A")), b.put(b.path("/A/B"));
  uint64_t tokenVec = b.put<uint64_t>(1);
  b.put(b.token("child"));
  uint64_t stringVec = b.put<uint64_t>(2);
  b.put(b.string("sub1.usda")), b.put(b.string("sub2.usdc"));
  uint64_t doubleVec = b.put<uint64_t>(2);
  b.put(0.5), b.put(-1.0);
  uint64_t offsets = b.put<uint64_t>(2);
  b.put(0.0), b.put(1.0), b.put(24.0), b.put(0.5);
  uint64_t variants = b.put<uint64_t>(1);
  b.put(b.string("shadingVariant")), b.put(b.string("red"));
  uint64_t wrapped = b.put<int64_t>(8);  // a VtValue holding a value: offset, rep
  b.put(rep(T::Float, 0x3f800000));

  b.spec("/", SpecType::PseudoRoot,
         {b.field("subLayers", rep(T::StringVector, stringVec)),
          b.field("subLayerOffsets", rep(T::LayerOffsetVector, offsets))});
  b.spec("/A", SpecType::Prim,
         {b.field("customData", rep(T::Dictionary, dict)), b.field("apiSchemas", rep(T::TokenListOp, tokenOp)),
          b.field("references", rep(T::ReferenceListOp, refOp)), b.field("payload", rep(T::PayloadListOp, payloadOp)),
          b.field("variantSelection", rep(T::VariantSelectionMap, variants)),
          b.field("primChildren", rep(T::TokenVector, tokenVec)), b.field("specifier", rep(T::Specifier, 0))});
  b.spec("/A/B", SpecType::Prim,
         {b.field("payload", rep(T::Payload, payload)), b.field("specifier", rep(T::Specifier, 1)),
          b.field("intOp", rep(T::IntListOp, intOp)), b.field("uint64Op", rep(T::UInt64ListOp, uint64Op)),
          b.field("uintOp", rep(T::UIntListOp, uintOp)), b.field("int64Op", rep(T::Int64ListOp, int64Op)),
          b.field("stringOp", rep(T::StringListOp, stringOp)), b.field("paths", rep(T::PathVector, pathVec)),
          b.field("doubles", rep(T::DoubleVector, doubleVec)), b.field("wrapped", rep(T::Value, wrapped))});
  b.spec("/A/B.rel", SpecType::Relationship, {b.field("targetPaths", rep(T::PathListOp, pathOp))});
  Layer layer = finishAndRead(b);

  const auto& root = specAt(layer, "/").fields;
  CHECK(root.at("subLayers").strings == std::vector<std::string>{"sub1.usda", "sub2.usdc"});
  REQUIRE(root.at("subLayerOffsets").layerOffsets->size() == 2);
  CHECK(root.at("subLayerOffsets").layerOffsets->at(1) == LayerOffset{24.0, 0.5});

  const auto& a = specAt(layer, "/A").fields;
  const Dictionary& d = *a.at("customData").dictionary;
  CHECK(d.at("name").strings == std::vector<std::string>{"wood"});
  CHECK(d.at("nested").dictionary->at("depth").numbers == nums({2}));
  CHECK(d.at("values").numbers == doubles);
  const auto& tok = *a.at("apiSchemas").textListOp;
  CHECK_FALSE(tok.isExplicit);
  CHECK(tok.prependedItems == std::vector<std::string>{"A"});
  CHECK(tok.appendedItems == std::vector<std::string>{"B", "C"});
  CHECK(tok.deletedItems == std::vector<std::string>{"D"});
  const auto& refs = *a.at("references").referenceListOp;
  REQUIRE(refs.prependedItems.size() == 2);
  CHECK(refs.prependedItems[0].assetPath == "./parts/bolt.usd");
  CHECK(refs.prependedItems[0].primPath == "/Bolt");
  CHECK(refs.prependedItems[0].offset == LayerOffset{10.0, 2.0});
  REQUIRE(refs.prependedItems[0].customData);
  CHECK(refs.prependedItems[0].customData->at("note").strings == std::vector<std::string>{"hi"});
  CHECK(refs.prependedItems[1].assetPath.empty());  // an internal reference to the default prim
  CHECK(refs.prependedItems[1].primPath.empty());
  CHECK_FALSE(refs.prependedItems[1].customData);
  const auto& payloads = *a.at("payload").referenceListOp;
  CHECK(a.at("payload").kind == Kind::PayloadListOp);
  CHECK(payloads.isExplicit);
  CHECK(payloads.explicitItems.at(0).assetPath == "heavy.usdc");
  CHECK(a.at("variantSelection").kind == Kind::VariantSelectionMap);
  CHECK(a.at("variantSelection").dictionary->at("shadingVariant").strings == std::vector<std::string>{"red"});

  const auto& ab = specAt(layer, "/A/B").fields;
  CHECK(ab.at("payload").kind == Kind::Payload);
  CHECK(ab.at("payload").references->at(0).primPath == "/Single");
  CHECK(ab.at("payload").references->at(0).offset.offset == 5.0);
  CHECK(ab.at("specifier").enumValue == int(Specifier::Over));
  CHECK(ab.at("intOp").intListOp->prependedItems == std::vector<int64_t>{-3, 9});
  CHECK(ab.at("uint64Op").intListOp->appendedItems == std::vector<int64_t>{int64_t(1) << 40});
  CHECK(ab.at("uintOp").intListOp->appendedItems == std::vector<int64_t>{4000000000});
  CHECK(ab.at("int64Op").intListOp->deletedItems == std::vector<int64_t>{-(int64_t(1) << 35)});
  CHECK(ab.at("stringOp").textListOp->addedItems == std::vector<std::string>{"s1"});
  CHECK(ab.at("stringOp").textListOp->orderedItems == std::vector<std::string>{"s2"});
  CHECK(ab.at("paths").strings == std::vector<std::string>{"/A", "/A/B"});
  CHECK(ab.at("doubles").kind == Kind::DoubleVector);
  CHECK(ab.at("doubles").numbers == nums({0.5, -1}));
  CHECK(ab.at("wrapped").kind == Kind::Float);
  CHECK(ab.at("wrapped").numbers == nums({1}));
  const auto& targets = *specAt(layer, "/A/B.rel").fields.at("targetPaths").textListOp;
  CHECK(targets.isExplicit);
  CHECK(targets.explicitItems == std::vector<std::string>{"/Target.out"});
}

TEST_CASE("crate time samples", "[usd][crate]") {
  CrateBuilder b;
  uint64_t times = b.put<uint64_t>(3);
  b.putAll(std::vector<double>{1, 2, 10});
  uint64_t v1 = b.putAll(std::vector<double>{1, 2, 3});
  // Offset to the times rep, the rep, offset to the values, count, reps.
  uint64_t samples = b.put<int64_t>(8);
  b.put(rep(T::DoubleVector, times));
  b.put<int64_t>(8);
  b.put<uint64_t>(3);
  b.put(rep(T::Vec3d, v1));
  b.put(rep(T::ValueBlock, 0));
  b.put(inlined(T::Vec3d, 0x00ff0102));
  Value v = readBack(b, rep(T::TimeSamples, samples), "timeSamples");
  REQUIRE(v.kind == Kind::TimeSamples);
  CHECK(v.timeSamples->times == nums({1, 2, 10}));
  REQUIRE(v.timeSamples->values.size() == 3);
  CHECK(v.timeSamples->values[0].numbers == nums({1, 2, 3}));
  CHECK(v.timeSamples->values[1].kind == Kind::ValueBlock);
  CHECK(v.timeSamples->values[2].numbers == nums({2, 1, -1}));
}

TEST_CASE("crate paths: properties, variants, targets", "[usd][crate]") {
  CrateBuilder b;
  const std::vector<std::string> paths{"/World",
                                       "/World/Cube",
                                       "/World/Cube.size",
                                       "/World/Cube.material:binding",
                                       "/World/Cube.material:binding[/World/Looks/Red]",
                                       "/World/Cube.material:binding[/World/Looks/Red].weight",
                                       "/World{look=red}",
                                       "/World{look=red}Extra",
                                       "/World{look=red}Extra.color",
                                       "/World/Looks",
                                       "/World/Looks/Red"};
  b.spec("/", SpecType::PseudoRoot, {});
  for (const auto& p : paths) b.spec(p, SpecType::Prim, {});
  Layer layer = finishAndRead(b);
  CHECK(layer.specs.size() == paths.size() + 1);
  for (const auto& p : paths) CHECK(layer.spec(p));
}

TEST_CASE("crate versions: what each one changes", "[usd][crate]") {
  auto arrayOfInts = [](uint8_t minor, bool rank, bool wide, bool compressedFlag) {
    CrateBuilder b(minor);
    uint64_t at = b.tell();
    if (rank) b.put<uint32_t>(1);
    wide ? b.put<uint64_t>(20) : b.put<uint32_t>(20);
    std::vector<int32_t> v(20);
    for (int i = 0; i < 20; ++i) v[size_t(i)] = i * 3;
    b.putAll(v);
    Value value = readBack(b, rep(T::Int, at, true, false, compressedFlag));
    return value.numbers;
  };
  std::vector<double> expected;
  for (int i = 0; i < 20; ++i) expected.push_back(i * 3);
  // 0.4.0: a rank before each array, 32-bit sizes, no compression (the bit is ignored).
  CHECK(arrayOfInts(4, true, false, true) == expected);
  // 0.5.0 and 0.6.0: no rank, 32-bit sizes.
  CHECK(arrayOfInts(6, false, false, false) == expected);
  // 0.7.0 on: 64-bit sizes.
  CHECK(arrayOfInts(7, false, true, false) == expected);
  CHECK(arrayOfInts(10, false, true, false) == expected);

  SECTION("floats are compressed from 0.6.0: before, the compressed bit is ignored") {
    CrateBuilder b(5);
    uint64_t at = b.put<uint32_t>(16);
    b.putAll(std::vector<float>(16, 0.5f));
    CHECK(readBack(b, rep(T::Float, at, true, false, true)).numbers == std::vector<double>(16, 0.5));
  }
  SECTION("payloads have layer offsets from 0.8.0") {
    CrateBuilder b(7);
    uint64_t at = b.put(b.string("old.usd"));
    b.put(b.path("/Old"));
    Value v = readBack(b, rep(T::Payload, at), "payload");
    CHECK(v.references->at(0).assetPath == "old.usd");
    CHECK(v.references->at(0).offset == LayerOffset{});
  }
  SECTION("0.9.0: timecode and timecode[]") {
    CrateBuilder b(9);
    uint64_t one = b.put(24.0);
    uint64_t many = b.put<uint64_t>(2);
    b.putAll(std::vector<double>{1, 100});
    b.spec("/", SpecType::PseudoRoot, {});
    b.spec("/P.a", SpecType::Attribute,
           {b.field("default", rep(T::TimeCode, one)), b.field("list", rep(T::TimeCode, many, true))});
    Layer layer = finishAndRead(b);
    CHECK(specAt(layer, "/P.a").fields.at("default").kind == Kind::TimeCode);
    CHECK(specAt(layer, "/P.a").fields.at("default").numbers == nums({24}));
    CHECK(specAt(layer, "/P.a").fields.at("list").isArray);
    CHECK(specAt(layer, "/P.a").fields.at("list").numbers == nums({1, 100}));
  }
  SECTION("0.10.0: path expressions are kept, uninterpreted") {
    CrateBuilder b(10);
    uint64_t at = b.put(b.string("/World//Cube*"));
    Value v = readBack(b, rep(T::PathExpression, at));
    CHECK(v.kind == Kind::Unsupported);
    CHECK(v.enumValue == int(T::PathExpression));
    CHECK(v.strings == std::vector<std::string>{"PathExpression", "/World//Cube*"});
  }
  SECTION("0.11.0: relocates are kept, uninterpreted") {
    CrateBuilder b(11);
    uint64_t at = b.put<uint64_t>(1);
    b.put(b.path("/A/B")), b.put(b.path("/A/C"));
    Value v = readBack(b, rep(T::Relocates, at), "layerRelocates");
    CHECK(v.kind == Kind::Unsupported);
    CHECK(v.strings == std::vector<std::string>{"Relocates", "/A/B", "/A/C"});
  }
  SECTION("a type newer than this reader is kept as unsupported") {
    CrateBuilder b(11);
    Value v = readBack(b, rep(CrateType(99), 1234), "futureField");
    CHECK(v.kind == Kind::Unsupported);
    CHECK(v.enumValue == 99);
    CHECK(v.strings == std::vector<std::string>{"unknown"});
  }
  SECTION("versions outside 0.4.0 to 0.11.x are refused") {
    for (uint8_t minor : {uint8_t(3), uint8_t(12)}) {
      CrateBuilder b(minor);
      b.spec("/", SpecType::PseudoRoot, {});
      auto bytes = b.finish();
      CHECK_THROWS_WITH(readCrateLayer(bytes, "v.usdc"),
                        Catch::Contains("v.usdc: crate bootstrap: version 0." + std::to_string(minor) +
                                        ".0 is not supported (this reader reads 0.4.0 to 0.11.x)"));
    }
  }
}

TEST_CASE("crate structural fields must hold their type", "[usd][crate]") {
  CrateBuilder b;
  b.spec("/", SpecType::PseudoRoot, {});
  b.spec("/P", SpecType::Prim, {b.field("specifier", rep(CrateType(99), 0))});
  auto bytes = b.finish();
  CHECK_THROWS_WITH(readCrateLayer(bytes, "s.usdc"),
                    "s.usdc: crate spec 1 </P> field 'specifier' (unknown): holds an unsupported type, "
                    "expected a specifier");
}
