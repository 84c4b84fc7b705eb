// Syntax errors name file:line:col with what was expected and what was
// found; hostile text (deep nesting, huge arrays, unterminated tokens,
// binary junk) is a clean UsdError, never a crash.
#include <catch2/catch.hpp>

#include "usd/layer_io.h"

using namespace sdg::usd;

namespace {

// The error message of parsing `text` as "bad.usda" ("" when it parses).
std::string errorOf(const std::string& text, const ReadLimits& limits = {}) {
  try {
    readUsdaLayer(text, "bad.usda", limits);
  } catch (const UsdError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("usda errors: located at file:line:col with expected and found", "[usda]") {
  CHECK(errorOf("#sdf 1.0\n") == "bad.usda:1:1: not a usda text layer: expected '#usda 1.0' as the first line");
  CHECK(errorOf("#usda one\n") == "bad.usda:1:7: expected a version such as 1.0 after '#usda', found 'one'");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    flaot x = 1\n}\n") ==
        "bad.usda:3:5: unknown attribute type 'flaot' (did you mean 'float'?)");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    float3 x = (1, 2)\n}\n") ==
        "bad.usda:3:21: expected ',' and 1 more numbers in a float3 value, found ')'");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    string s = \"abc\n}\n") ==
        "bad.usda:3:16: unterminated string: expected \" before the end of the line");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    asset a = @abc\n}\n") ==
        "bad.usda:3:15: unterminated asset path: expected '@'");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    rel r = </abc\n}\n") ==
        "bad.usda:3:13: unterminated path: expected '>'");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    float a = 1 float b = 2\n}\n") ==
        "bad.usda:3:17: expected ';' or a new line after the property, found 'float'");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    int i = 1.5\n}\n") == "bad.usda:3:13: expected an int, found the number 1.5");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    uchar c = 300\n}\n") ==
        "bad.usda:3:15: expected an uchar, found the number 300 (out of range)");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n}\ndef \"A\" {\n}\n") ==
        "bad.usda:4:5: duplicate prim /A (first defined at bad.usda:2:1)");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    float a = 1\n") ==
        "bad.usda:4:1: expected '}' to close /A, found the end of the file");
  CHECK(errorOf("#usda 1.0\ndef \"A\" (\n    kind = component\n) {}\n") ==
        "bad.usda:3:12: expected a quoted token for 'kind', found 'component'");
  CHECK(errorOf("#usda 1.0\ndef \"A\" (\n    prepend kind = \"x\"\n) {}\n") ==
        "bad.usda:3:13: 'kind' is not a list: 'prepend' does not apply to it");
  CHECK(errorOf("#usda 1.0\ndef \"A\" (references = @@) {}\n") ==
        "bad.usda:2:23: a reference's asset path must not be empty (write only the <path> for an internal reference)");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    float a = 1\n    float a = 2\n}\n") ==
        "bad.usda:4:15: attribute 'a' has a second default value");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    float a\n    double a.timeSamples = {}\n}\n") ==
        "bad.usda:4:5: attribute 'a' is declared as float at bad.usda:3:5 and as double here");
  CHECK(errorOf("#usda 1.0\ndef \"1A\" {}\n") == "bad.usda:2:5: '1A' is not a valid prim name");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    float a = 1 ( interpolation = \"vertex\"\n}\n") ==
        "bad.usda:4:1: expected a metadata key, a quoted comment or ')', found '}'");
  CHECK(errorOf("#usda 1.0\ndef \"A\" { float a = $ }\n") == "bad.usda:2:21: unexpected '$'");
  CHECK(errorOf("#usda 1.0\n/* open comment\ndef \"A\" {}\n") == "bad.usda:2:1: unterminated /* comment");
  CHECK(errorOf("#usda 1.0\ndef \"A\" ( subLayers = [@a.usda@] ) {}\n") ==
        "bad.usda:2:11: 'subLayers' is metadata of the layer; it cannot appear on a prim");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    matrix2d m = ((1, 0), (0, 1, 2))\n}\n") ==
        "bad.usda:3:34: expected ')' after 2 numbers in a matrix2d row, found the number 2");
}

TEST_CASE("usda errors: hostile input fails cleanly within the limits", "[usda]") {
  SECTION("deeply nested prims stop at the nesting limit") {
    std::string text = "#usda 1.0\n";
    for (int i = 0; i < 100000; ++i) text += "def \"A\" {\n";
    std::string error = errorOf(text);
    CHECK_THAT(error, Catch::Contains("prims nested deeper than the limit of 256 levels"));
    CHECK_THAT(error, Catch::StartsWith("bad.usda:258:1:"));  // the 257th prim
  }
  SECTION("deeply nested dictionaries") {
    std::string text = "#usda 1.0\ndef \"A\" ( customData = ";
    for (int i = 0; i < 100000; ++i) text += "{ dictionary d = ";
    CHECK_THAT(errorOf(text), Catch::Contains("dictionaries nested deeper than the limit"));
  }
  SECTION("nested tuples and lists in untyped metadata") {
    CHECK_THAT(errorOf("#usda 1.0\ndef \"A\" ( x = " + std::string(100000, '(') + " ) {}\n"),
               Catch::Contains("expected a double number, found '('"));
    CHECK_THAT(errorOf("#usda 1.0\ndef \"A\" ( x = " + std::string(100000, '[') + " ) {}\n"),
               Catch::Contains("expected strings, numbers, asset paths or paths in the untyped list"));
  }
  SECTION("arrays beyond the element limit") {
    ReadLimits limits;
    limits.maxArrayElements = 4;
    CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    int[] a = [1, 2, 3, 4, 5]\n}\n", limits) ==
          "bad.usda:3:28: the int[] array has more than 4 elements, the limit");
    CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    int[] a = [1, 2, 3, 4]\n}\n", limits).empty());
  }
  SECTION("more specs than the limit") {
    ReadLimits limits;
    limits.maxSpecs = 3;
    CHECK_THAT(errorOf("#usda 1.0\ndef \"A\" {}\ndef \"B\" {}\ndef \"C\" {}\n", limits),
               Catch::Contains("more than 3 specs"));
  }
  SECTION("a file larger than the limit") {
    ReadLimits limits;
    limits.maxFileBytes = 16;
    CHECK_THAT(errorOf("#usda 1.0\ndef \"A\" {}\n", limits), Catch::Contains("beyond the limit of 16"));
  }
  SECTION("unterminated tokens at the end of the file") {
    CHECK_THAT(errorOf("#usda 1.0\ndef \"A\" ( doc = \"\"\"never closed"), Catch::Contains("unterminated string"));
    CHECK_THAT(errorOf("#usda 1.0\ndef \"A\" { asset a = @@@never"), Catch::Contains("unterminated asset path"));
    CHECK_THAT(errorOf("#usda 1.0\ndef \"A"), Catch::Contains("unterminated string"));
    CHECK_THAT(errorOf("#usda 1.0\ndef"), Catch::Contains("found the end of the file"));
    CHECK(errorOf("#usda 1.0").empty());  // the header alone is an empty layer
  }
  SECTION("malformed relative paths (found by fuzz_usda: one looped forever)") {
    CHECK(errorOf("#usda 1.0\ndef \"A\" (\n    references = @./x.usda@<tlm/Material[X>\n) {}\n") ==
          "bad.usda:3:28: the path <tlm/Material[X> is not a valid path");
    CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    rel r = <../../B>\n}\n") ==
          "bad.usda:3:13: the path <../../B> climbs above the root");
  }
  SECTION("binary junk and numbers that do not fit") {
    CHECK_THAT(errorOf(std::string("#usda 1.0\n\0\xff\x01", 14)), Catch::Contains("unexpected byte 0x00"));
    CHECK_THAT(errorOf("#usda 1.0\ndef \"A\" { int i = 99999999999999999999999 }\n"), Catch::Contains("out of range"));
    CHECK(errorOf("#usda 1.0\ndef \"A\" {\n double d = 1e999\n}\n").empty());  // inf, as Sdf reads it
  }
}

TEST_CASE("usda errors: inside long arrays, located exactly", "[usda]") {
  std::string many;
  for (int i = 0; i < 1000; ++i) many += "(1, 2, 3), ";
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    int[] i = [1, 2,\n        3, 4.5, 5]\n}\n") ==
        "bad.usda:4:12: expected an int, found the number 4.5");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    uchar[] c = [1, 256]\n}\n") ==
        "bad.usda:3:21: expected an uchar, found the number 256 (out of range)");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    float3[] p = [" + many + "(1, 2)]\n}\n") ==
        "bad.usda:3:11024: expected ',' and 1 more numbers in a float3 value, found ')'");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    float3[] p = [" + many + "(1, 2, 3) (4, 5, 6)]\n}\n") ==
        "bad.usda:3:11029: expected ',' or ']' in the float3[] array, found '('");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    float[] f = [1, 2.5.3]\n}\n") ==
        "bad.usda:3:24: expected ',' or ']' in the float[] array, found the number .3");
  CHECK(errorOf("#usda 1.0\ndef \"A\" {\n    float[] f = [1, 2\n") ==
        "bad.usda:4:1: expected ',' or ']' in the float[] array, found the end of the file");
}
