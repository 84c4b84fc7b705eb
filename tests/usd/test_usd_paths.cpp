// USD path strings: building, taking apart, prefixes, anchoring, syntax.
#include <catch2/catch.hpp>

#include "usd/sdf_path.h"

using namespace sdg::usd;

TEST_CASE("usd paths: children, properties, variants, parents", "[usda]") {
  CHECK(path::child("/", "A") == "/A");
  CHECK(path::child("/A", "B") == "/A/B");
  CHECK(path::child("/A{v=x}", "B") == "/A{v=x}B");
  CHECK(path::property("/A", "points") == "/A.points");
  CHECK(path::variantSet("/A", "v") == "/A{v=}");
  CHECK(path::variant("/A", "v", "x") == "/A{v=x}");
  CHECK(path::parent("/A/B") == "/A");
  CHECK(path::parent("/A") == "/");
  CHECK(path::parent("/A{v=x}B") == "/A{v=x}");
  CHECK(path::parent("/A{v=x}") == "/A");
  CHECK(path::name("/A{v=x}B") == "B");
  CHECK(path::depth("/") == 0);
  CHECK(path::depth("/A{v=x}B/C.x") == 3);
  CHECK(path::primPart("/A/B.x[/C.y]") == "/A/B");
  CHECK(path::primPart("/A{v=1.5}B.x") == "/A{v=1.5}B");
  CHECK(path::propertyName("/A.inputs:x.connect") == "inputs:x");
  CHECK(path::stripVariants("/A{v=x}{w=y}B.c") == "/A/B.c");
  CHECK(path::stripVariants("/A{v=x}") == "/A");
}

TEST_CASE("usd paths: prefixes and their replacement", "[usda]") {
  CHECK(path::hasPrefix("/A/B", "/A"));
  CHECK(path::hasPrefix("/A.x", "/A"));
  CHECK(path::hasPrefix("/A", "/A"));
  CHECK_FALSE(path::hasPrefix("/AB", "/A"));
  CHECK(path::hasPrefix("/AB", "/"));
  CHECK(path::replacePrefix("/Asset/Geom.x", "/Asset", "/World/A") == "/World/A/Geom.x");
  CHECK(path::replacePrefix("/Asset", "/Asset", "/World/A") == "/World/A");
  CHECK(path::replacePrefix("/X/Y", "/", "/World") == "/World/X/Y");
  CHECK(path::replacePrefix("/X/Y", "/X", "/") == "/Y");
}

TEST_CASE("usd paths: syntax and anchoring", "[usda]") {
  for (const char* good : {"/", "/A", "/A/B_1", "/A.x", "/A.inputs:x", "/A{v=x}B", "/A{v=x}", "/A.rel[/B.c]",
                           "/A.rel[/B].attr", "B", "B/C", "../B", "../../B.x", ".x", "..", "../.x"})
    CHECK(path::isValidPath(good));
  for (const char* bad : {"", "//", "/A/", "/1A", "/A.", "/A.x.", "tlm/Material[X", "/A[", "/A{v}", "/A.r[/B[/C]]",
                          "/A B", "...", "./A"})
    CHECK_FALSE(path::isValidPath(bad));
  CHECK(path::makeAbsolute("/A/B", "C") == "/A/B/C");
  CHECK(path::makeAbsolute("/A/B", "../C.x") == "/A/C.x");
  CHECK(path::makeAbsolute("/A/B", ".x") == "/A/B.x");
  CHECK(path::makeAbsolute("/A/B", "../..") == "/");
  CHECK(path::makeAbsolute("/A", "../../C").empty());
  CHECK(path::makeAbsolute("/A", "/Z") == "/Z");
  // Linear in the lengths: a long relative path against a deep anchor.
  std::string deep = "/A";
  for (int i = 0; i < 20000; ++i) deep += "/A";
  std::string up;
  for (int i = 0; i < 20000; ++i) up += "../";
  CHECK(path::makeAbsolute(deep, up + "B") == "/A/B");
}
