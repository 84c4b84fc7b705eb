// Typed reading: one table of (type, YAML, expected message) rows.
#include <catch2/catch.hpp>

#include "scene_io/raw_node.h"
#include "scene_io/yaml_events.h"
#include "scene_io/value_reader.h"

using namespace sdg;

namespace {
struct Row {
  ValueType type;
  const char* yaml;
  const char* message;  // "" = accepted
};

std::string readOne(ValueType type, const char* yaml) {
  RawNode node = parseYaml(yaml, "v.yaml");
  Diagnostics diag;
  readValue(node, type, "x", diag);
  return diag.hasErrors() ? diag.all().front().format() : "";
}
}  // namespace

TEST_CASE("value reader: shapes, ranges and finiteness", "[scene_io][values]") {
  const Row rows[] = {
      {ValueType::Bool, "true", ""},
      {ValueType::Bool, "yes", "x: expected true or false, found 'yes'"},
      {ValueType::Bool, "\"true\"", "expected true or false, found the string 'true'"},
      {ValueType::Int, "-7", ""},
      {ValueType::Int, "1.5", "expected an integer, found the number 1.5 (not a whole number)"},
      {ValueType::Int, "3000000000", "3000000000 is out of range (-2147483648 to 2147483647)"},
      {ValueType::UInt, "-1", "-1 is out of range (0 to 4294967295)"},
      {ValueType::Float, "1e39", "1e39 is out of range for a 32-bit float"},
      {ValueType::Float, ".nan", "expected a finite number, found '.nan'"},
      {ValueType::Double, "-.inf", "expected a finite number, found '-.inf'"},
      {ValueType::Double, "1e400", "expected a finite number"},
      {ValueType::Double, "[1]", "expected a number, found a list of 1 item"},
      {ValueType::Int2, "[1, 2]", ""},
      {ValueType::Int2, "[1, 2, 3]", "expected a list of 2 integers, found a list of 3 items"},
      {ValueType::Float3, "[1, two, 3]", "x: expected a number, found 'two'"},
      {ValueType::Color3f, "{r: 1}", "expected a list of 3 numbers (r, g, b), found a mapping"},
      {ValueType::Quatd, "[1, 0, 0]", "expected a list of 4 numbers (w, x, y, z)"},
      {ValueType::Matrix4d, "[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0]]", "expected 4 rows of 4 numbers"},
      {ValueType::String, "~", "expected a string, found nothing (null)"},
      {ValueType::AssetArray, "[a.png, [b]]", "expected a string in the list, found a list of 1 item"},
  };
  for (const Row& row : rows) {
    CAPTURE(valueTypeName(row.type), row.yaml);
    std::string message = readOne(row.type, row.yaml);
    if (std::string(row.message).empty()) CHECK(message.empty());
    else CHECK_THAT(message, Catch::Contains(row.message));
  }
}

TEST_CASE("value reader: locations are 1-based line and column", "[scene_io][values]") {
  RawNode doc = parseYaml("a: 1\nb: [1, x]\n", "f.yaml");
  Diagnostics diag;
  readValue(*doc.find("b"), ValueType::Float2, "b", diag);
  REQUIRE(diag.hasErrors());
  CHECK(diag.all().front().format() == "f.yaml:2:8: error: b: expected a number, found 'x'");
}

TEST_CASE("value reader: the matrix layout is USD's row-vector rows", "[scene_io][values]") {
  RawNode node = parseYaml("[[1,0,0,0],[0,1,0,0],[0,0,1,0],[4,5,6,1]]", "m.yaml");
  Diagnostics diag;
  auto v = readValue(node, ValueType::Matrix4d, "m", diag);
  REQUIRE(v);
  const Matrix4d& m = v->get<Matrix4d>();
  CHECK(m(0, 3) == 4);  // translation lands in our column 3
  CHECK(m(2, 3) == 6);
}

TEST_CASE("value reader: floats keep their exact text value", "[scene_io][values]") {
  RawNode node = parseYaml("0.1", "f.yaml");
  Diagnostics diag;
  auto v = readValue(node, ValueType::Float, "f", diag);
  REQUIRE(v);
  CHECK(v->get<float>() == 0.1f);
}
