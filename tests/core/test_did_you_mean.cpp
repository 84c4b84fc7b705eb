// "Did you mean" suggests only names a typo away from what was written.
#include <catch2/catch.hpp>

#include "core/text.h"

using namespace sdg;

TEST_CASE("did you mean: close names only", "[core][text]") {
  const std::vector<std::string> variables = {"exposedVar:ns:interval", "exposedVar:ns:speed", "size"};
  // A long shared prefix does not make a different name close.
  CHECK(text::closestMatch("exposedVar:ns:nosuchvar", variables).empty());
  CHECK(text::closestMatch("nosuchvar", std::vector<std::string>{"interval"}).empty());
  CHECK(text::closestMatch("exposedVar:ns:intervl", variables) == "exposedVar:ns:interval");
  CHECK(text::closestMatch("exposedVar:ns:sped", variables) == "exposedVar:ns:speed");
  CHECK(text::closestMatch("sizee", variables) == "size");
  // Typos: a swap counts as one, case is ignored.
  const std::vector<std::string> behaviors = {"locationRandomizer", "rotationRandomizer", "lookAtBehavior"};
  CHECK(text::closestMatch("lcoationRandomizer", behaviors) == "locationRandomizer");
  CHECK(text::closestMatch("LocationRandomiser", behaviors) == "locationRandomizer");
  CHECK(text::closestMatch("fooRandomizer", behaviors).empty());
  CHECK(text::closestMatch("vector3", std::vector<std::string>{"vector3d", "double3"}) == "vector3d");
  CHECK(text::closestMatch("dok", std::vector<std::string>{"doc", "lock"}) == "doc");
  CHECK(text::closestMatch("xy", std::vector<std::string>{"ab"}).empty());  // not a typo: another word
  CHECK(text::closestMatch("SpotLight", std::vector<std::string>{"SphereLight", "RectLight"}) == "RectLight");
  CHECK(text::didYouMean("rgbb", std::vector<std::string>{"rgb"}) == " (did you mean 'rgb'?)");
  CHECK(text::didYouMean("semantic", std::vector<std::string>{"rgb"}).empty());
}
