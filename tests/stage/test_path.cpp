#include <catch2/catch.hpp>

#include "stage/path.h"

using namespace sdg;

TEST_CASE("prim paths: valid and invalid forms", "[stage][path]") {
  CHECK(path::isValid("/Root"));
  CHECK(path::isValid("/Root/Pallet_01/_hidden2"));
  CHECK_THAT(path::whyInvalid(""), Catch::Contains("must not be empty"));
  CHECK_THAT(path::whyInvalid("Root/A"), Catch::Contains("absolute"));
  CHECK_THAT(path::whyInvalid("/"), Catch::Contains("pseudo-root"));
  CHECK_THAT(path::whyInvalid("/Root/"), Catch::Contains("end with '/'"));
  CHECK_THAT(path::whyInvalid("/Root//A"), Catch::Contains("'//'"));
  CHECK_THAT(path::whyInvalid("/Root/1a"), Catch::Contains("not an identifier"));
  CHECK_THAT(path::whyInvalid("/Root/a-b"), Catch::Contains("not an identifier"));
  CHECK_THAT(path::whyInvalid("/Root/a.b"), Catch::Contains("not an identifier"));
}

TEST_CASE("prim paths: hostile sizes are refused with the limit named", "[stage][path]") {
  std::string deep;
  for (size_t i = 0; i < path::kMaxDepth + 1; ++i) deep += "/a";
  CHECK_THAT(path::whyInvalid(deep), Catch::Contains("nested at most 256"));
  std::string huge = "/" + std::string(1 << 20, 'a');
  CHECK_THAT(path::whyInvalid(huge), Catch::Contains("limited to 4096 characters"));
}

TEST_CASE("prim paths: parent, name, ancestry", "[stage][path]") {
  CHECK(path::parent("/A/B/C") == "/A/B");
  CHECK(path::parent("/A") == "/");
  CHECK(path::parent("/") == "");
  CHECK(path::name("/A/B") == "B");
  CHECK(path::isAtOrBelow("/A/B", "/A"));
  CHECK(path::isAtOrBelow("/A", "/A"));
  CHECK_FALSE(path::isAtOrBelow("/AB", "/A"));
  CHECK(path::depth("/A/B") == 2);
}
