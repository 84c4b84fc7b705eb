// The studio's text edits keep everything they do not change.
#include <catch2/catch.hpp>

#include "studio/yaml_text_edit.h"

using namespace sdg::studio;

namespace {
const char* kScene =
    "# a comment\n"
    "version: 1\n"
    "prims:\n"
    "  /World: {}   # the root\n"
    "  /World/Box:\n"
    "    type: Cube\n"
    "    size: 0.5   # half a metre\n"
    "    behaviors:\n"
    "      locationRandomizer:\n"
    "        interval: 2\n"
    "        range:maxPosition: [1, 1, 0]\n"
    "      rotationRandomizer:\n"
    "\n"
    "  # the light\n"
    "  /World/Sun: {type: DistantLight, inputs:intensity: 3000}\n";
}  // namespace

TEST_CASE("studio text edit: a value is replaced where it is written", "[studio]") {
  std::string out = applyTextEdit(kScene, {"/World/Box", {"size"}, "0.75"});
  CHECK(out.find("    size: 0.75   # half a metre\n") != std::string::npos);
  out = applyTextEdit(kScene, {"/World/Box", {"behaviors", "locationRandomizer", "range:maxPosition"}, "[2, 2, 0]"});
  CHECK(out.find("        range:maxPosition: [2, 2, 0]\n") != std::string::npos);
  out = applyTextEdit(kScene, {"/World/Sun", {"inputs:intensity"}, "4000.0"});
  CHECK(out.find("  /World/Sun: {type: DistantLight, inputs:intensity: 4000.0}\n") != std::string::npos);
}

TEST_CASE("studio text edit: new keys go into block maps at the siblings' indentation", "[studio]") {
  std::string out = applyTextEdit(kScene, {"/World/Box", {"behaviors", "locationRandomizer", "seed"}, "5"});
  CHECK(out.find("        range:maxPosition: [1, 1, 0]\n        seed: 5\n      rotationRandomizer:\n") != std::string::npos);
  // A key after a block map that ends before a blank line and a comment.
  out = applyTextEdit(kScene, {"/World/Box", {"doubleSided"}, "true"});
  CHECK(out.find("      rotationRandomizer:\n    doubleSided: true\n\n  # the light\n") != std::string::npos);
}

TEST_CASE("studio text edit: a null value becomes a flow map, flow maps take new keys", "[studio]") {
  std::string out = applyTextEdit(kScene, {"/World/Box", {"behaviors", "rotationRandomizer", "interval"}, "3"});
  CHECK(out.find("      rotationRandomizer: {interval: 3}\n") != std::string::npos);
  out = applyTextEdit(kScene, {"/World/Sun", {"inputs:exposure"}, "1.0"});
  CHECK(out.find("{type: DistantLight, inputs:intensity: 3000, inputs:exposure: 1.0}") != std::string::npos);
  out = applyTextEdit(kScene, {"/World", {"behaviors", "lookAtBehavior", "upAxis"}, "[0, 0, 1]"});
  CHECK(out.find("  /World: {behaviors: {lookAtBehavior: {upAxis: [0, 0, 1]}}}   # the root\n") != std::string::npos);
}

TEST_CASE("studio text edit: a prim without an entry gets one at the end of prims", "[studio]") {
  std::string out = applyTextEdit(kScene, {"/World/Asset/Child", {"radius"}, "0.2"});
  CHECK(out.find("inputs:intensity: 3000}\n  /World/Asset/Child: {radius: 0.2}\n") != std::string::npos);
  // Everything else is the same text.
  CHECK(out.substr(0, std::string(kScene).size()) == kScene);
}

TEST_CASE("studio text edit: JSON values as YAML flow, and a line diff", "[studio]") {
  CHECK(yamlFlow("[1, 2.5, true]") == "[1, 2.5, true]");
  CHECK(yamlFlow("2.0") == "2.0");
  CHECK(yamlFlow("\"a: b\"") == "\"a: b\"");
  std::string diff = lineDiff("a\nb\nc\n", "a\nB\nc\n", "s.yaml");
  CHECK(diff.find("-b\n+B\n") != std::string::npos);
}

TEST_CASE("studio text edit: a key is removed with its comma or its lines", "[studio]") {
  std::string out = removeTextKey(kScene, "/World/Box", {"behaviors", "locationRandomizer"});
  CHECK(out.find("    behaviors:\n      rotationRandomizer:\n") != std::string::npos);
  CHECK(out.find("interval: 2") == std::string::npos);
  out = removeTextKey(kScene, "/World/Sun", {"inputs:intensity"});
  CHECK(out.find("  /World/Sun: {type: DistantLight}\n") != std::string::npos);
  out = removeTextKey(kScene, "/World/Sun", {"type"});
  CHECK(out.find("  /World/Sun: {inputs:intensity: 3000}\n") != std::string::npos);
  CHECK(removeTextKey(kScene, "/World/Box", {"behaviors", "lookAtBehavior"}) == kScene);
}
