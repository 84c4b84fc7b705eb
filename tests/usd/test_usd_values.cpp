// The layer model's values: kinds and type names, builders and accessors,
// list ops (Sdf's ApplyOperations), time samples held at a time.
#include <catch2/catch.hpp>

#include "usd/layer.h"
#include "usd/value.h"

using namespace sdg::usd;

namespace {
std::vector<std::string> items(std::initializer_list<const char*> list) { return {list.begin(), list.end()}; }
}  // namespace

TEST_CASE("usd values: kinds, type names, role types", "[usda]") {
  CHECK(std::string(kindName(Kind::Vec3f)) == "float3");
  CHECK(std::string(kindName(Kind::AssetPath)) == "asset");
  CHECK(componentCount(Kind::Double) == 1);
  CHECK(componentCount(Kind::Quatf) == 4);
  CHECK(componentCount(Kind::Matrix3d) == 9);
  CHECK(componentCount(Kind::Token) == 0);
  CHECK(isNumeric(Kind::Vec2h));
  CHECK(isText(Kind::AssetPath));
  CHECK_FALSE(isText(Kind::Dictionary));
  auto points = valueTypeForName("point3f[]");
  REQUIRE(points);
  CHECK(points->kind == Kind::Vec3f);
  CHECK(points->isArray);
  CHECK(valueTypeForName("color4d")->kind == Kind::Vec4d);
  CHECK(valueTypeForName("texCoord2h")->kind == Kind::Vec2h);
  CHECK(valueTypeForName("frame4d")->kind == Kind::Matrix4d);
  CHECK_FALSE(valueTypeForName("flaot"));
  CHECK_FALSE(valueTypeForName("dictionary"));
  CHECK(std::find(valueTypeNames().begin(), valueTypeNames().end(), "normal3f") != valueTypeNames().end());
}

TEST_CASE("usd values: builders and accessors", "[usda]") {
  Value v = Value::scalar(Kind::Vec3f, {1, 2, 3});
  CHECK(v.elementCount() == 1);
  Value a = Value::array(Kind::Vec2d, {1, 2, 3, 4, 5, 6});
  CHECK(a.elementCount() == 3);
  CHECK_THROWS_AS(Value::array(Kind::Vec2d, {1, 2, 3}), std::invalid_argument);
  CHECK_THROWS_AS(Value::scalar(Kind::Token, {1}), std::invalid_argument);
  CHECK(Value::text(Kind::Token, "x").asString() == "x");
  CHECK(Value::textArray(Kind::String, items({"a", "b"})).elementCount() == 2);
  CHECK(Value::textArray(Kind::TokenVector, items({"a"})).asStrings() == items({"a"}));
  CHECK(Value::scalar(Kind::Bool, {1}).asBool());
  CHECK(Value::scalar(Kind::Float, {0.5}).asDouble() == 0.5);
  CHECK_THROWS_WITH(v.asDouble(), "expected a number, found float3");
  CHECK_THROWS_WITH(a.asString(), "expected a string, token or asset, found double2[]");
  CHECK(Value::specifier(Specifier::Class).enumValue == int(Specifier::Class));
  CHECK(Value::block().kind == Kind::ValueBlock);
  CHECK(Value::dict({{"k", Value::text(Kind::String, "v")}}).dictionary->at("k").asString() == "v");
  CHECK(Value::scalar(Kind::Int, {3}) == Value::scalar(Kind::Int, {3}));
  CHECK_FALSE(Value::scalar(Kind::Int, {3}) == Value::scalar(Kind::Float, {3}));
}

TEST_CASE("usd values: list ops apply as Sdf's ApplyOperations", "[usda]") {
  ListOp<std::string> op;
  op.prependedItems = items({"p1", "p2", "p1"});
  op.appendedItems = items({"x", "a1", "x"});
  op.deletedItems = items({"gone"});
  op.addedItems = items({"added", "w1"});
  CHECK(op.applyTo(items({"w1", "gone", "x", "w2"})) == items({"p1", "p2", "w1", "w2", "added", "a1", "x"}));
  ListOp<std::string> expl;
  expl.isExplicit = true;
  expl.explicitItems = items({"a", "b", "a"});
  CHECK(expl.applyTo(items({"z"})) == items({"a", "b"}));
  ListOp<std::string> reorder;
  reorder.orderedItems = items({"c", "a"});
  CHECK(reorder.applyTo(items({"a", "b", "c"})) == items({"c", "b", "a"}));
  ListOp<int64_t> ints;
  ints.appendedItems = {3, 1};
  CHECK(ints.applyTo({1, 2}) == std::vector<int64_t>{2, 3, 1});
  ListOp<Reference> refs;
  refs.deletedItems = {Reference{"a.usda", "/A", {}, nullptr, {}}};
  CHECK(refs.applyTo({Reference{"a.usda", "/A", {}, nullptr, {}}, Reference{"b.usda", "", {}, nullptr, {}}}).size() == 1);
  // 200,000 items apply in linear time (quadratic would take minutes).
  ListOp<std::string> big;
  for (int i = 0; i < 200000; ++i) big.prependedItems.push_back(std::to_string(i));
  big.deletedItems = items({"7"});
  CHECK(big.applyTo(big.prependedItems).size() == 200000);  // "7" deleted from the weaker list, prepended again
}

TEST_CASE("usd values: time samples held at a time", "[usda]") {
  TimeSamples ts;
  ts.times = {0, 10};
  ts.values = {Value::scalar(Kind::Double, {1}), Value::scalar(Kind::Double, {2})};
  CHECK(ts.heldAt(-5)->asDouble() == 1);
  CHECK(ts.heldAt(0)->asDouble() == 1);
  CHECK(ts.heldAt(9.9)->asDouble() == 1);
  CHECK(ts.heldAt(10)->asDouble() == 2);
  CHECK(ts.heldAt(100)->asDouble() == 2);
  CHECK(TimeSamples{}.heldAt(0) == nullptr);
  Layer empty;
  CHECK_THROWS_AS(empty.pseudoRoot(), UsdError);
}
