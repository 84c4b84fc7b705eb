#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "scene_fixtures.h"

using namespace sdg;
using sdg::test::errorsOf;
using sdg::test::loadText;

TEST_CASE("loader: a minimal scene builds the stage in document order", "[scene_io][loader]") {
  Scene scene = loadText(R"(
version: 1
prims:
  /Root:
  /Root/B: {type: Cube, size: 3, translate: [1, 2, 3], rotateZYX: [0, 0, 90], semantics: {class: box}}
  /Root/A: {type: Sphere}
)");
  const Prim* root = scene.stage.find("/Root");
  REQUIRE(root);
  CHECK(root->type() == PrimType::Xform);  // default type
  REQUIRE(root->children().size() == 2);
  CHECK(root->children()[0]->path() == "/Root/B");
  const Prim* b = scene.stage.find("/Root/B");
  CHECK(b->getDouble("size") == 3.0);
  REQUIRE(b->xformOps().size() == 2);
  CHECK(b->xformOps()[1].kind == XformOpKind::RotateZYX);
  CHECK(b->semantics().at("class") == std::vector<std::string>{"box"});
}

TEST_CASE("loader: children may be listed before their parents", "[scene_io][loader]") {
  Scene scene = loadText("version: 1\nprims:\n  /R/C: {type: Cube}\n  /R: {}\n");
  CHECK(scene.stage.find("/R/C")->parent()->path() == "/R");
}

TEST_CASE("loader: settings are typed and defaults filled", "[scene_io][loader]") {
  Scene scene = loadText(R"(
version: 1
render: {resolution: [640, 480]}
capture: {frames: 12}
writer: {type: BasicWriter, rgb: true}
events:
  - {publish: volumeStackRandomizer.in, payload: {action: setup, count: 3, all: true}, wait_for: {state_name: SETUP}, max_updates: 500}
prims: {}
)");
  CHECK(scene.render.get("resolution").get<Vec2i>() == Vec2i(640, 480));
  CHECK(scene.render.getUInt("subframes") == 1);
  CHECK(scene.capture.getUInt("frames") == 12);
  REQUIRE(scene.writers.size() == 1);
  CHECK(scene.writers[0].options.getBool("rgb"));
  CHECK(scene.writers[0].options.getBool("colorize_semantic_segmentation"));  // Replicator's default
  CHECK(scene.writers[0].options.getUInt("frame_padding") == 4);
  REQUIRE(scene.events.size() == 1);
  CHECK(scene.events[0].waitEvent == "volumeStackRandomizer.out");
  CHECK(scene.events[0].payload.getString("action") == "setup");
  CHECK(*scene.events[0].payload.find("count") == PayloadValue(3.0));
  CHECK(*scene.events[0].payload.find("all") == PayloadValue(true));
  CHECK(scene.events[0].maxUpdates == 500);
}

TEST_CASE("loader: every problem of a file is reported at once, in line order", "[scene_io][loader]") {
  std::string errors = errorsOf(R"(version: 1
render: {resolution: [1, 2], subframe: 3}
prims:
  /Root: {type: Xfrom}
  /Root/Cam: {type: Camera, focalLength: abc}
)");
  CHECK_THAT(errors, Catch::Contains("t.yaml:2:30: error: render: unknown key 'subframe' (did you mean 'subframes'?)"));
  CHECK_THAT(errors, Catch::Contains("t.yaml:4:17: error: /Root.type: unknown prim type 'Xfrom'"));
  CHECK_THAT(errors, Catch::Contains("(did you mean 'Xform'?)"));
  CHECK(errors.find("2:30") < errors.find("4:17"));
}

TEST_CASE("loader: structural errors name the key and what was expected", "[scene_io][loader]") {
  struct Case {
    const char* yaml;
    const char* message;
  } cases[] = {
      {"version: 1\nprims: []\n", "t.yaml:2:8: error: prims: expected a mapping from prim path to prim, found a list"},
      {"version: 1\nprims:\n  /A: 5\n", "t.yaml:3:7: error: /A: expected a mapping (the prim's type and attributes)"},
      {"version: 1\nprims:\n  /A: {type: Scope, translate: [0, 0, 0]}\n", "/A.translate: Scope prims have no transform"},
      {"version: 1\nprims:\n  /A: {orient: [0, 0, 0, 0]}\n", "/A.orient: the quaternion must not be zero"},
      {"version: 1\nprims:\n  /A: {semantics: {class: \"\"}}\n", "/A.semantics.class: labels must not be empty"},
      {"version: 1\nprims:\n  /A: {attributes: {w: {type: float3, value: 1}}}\n",
       "/A.w: expected a list of 3 numbers, found '1'"},
      {"version: 1\nprims:\n  /A: {attributes: {w: {type: vec3, value: 1}}}\n", "unknown value type 'vec3'"},
      {"version: 1\nprims:\n  /A: {attributes: {size: {type: float, value: 1}}}\n", ""},
      {"version: 1\nprims:\n  /A: {type: Cube, attributes: {size: {type: float, value: 1}}}\n",
       "'size' is a built-in attribute of the prim"},
      {"version: 1\nprims:\n  /A: {type: Mesh}\n", "/A: a Mesh needs `asset:`"},
      {"version: 1\nprims:\n  /A: {behaviors: {spin: {}}}\n", "/A: unknown behavior 'spin'"},
      {"version: 1\nwriter: [{type: BasicWriter}, {type: BasicWriter}]\nprims: {}\n", "a second BasicWriter"},
      {"version: 1\nevents: [{publish: go, wait_for: {done: true}}]\nprims: {}\n", "wait_for needs wait_event"},
      {"version: 1\nrender: {resolution: [20000, 10]}\nprims: {}\n", "each side is limited to 16384 pixels"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.yaml);
    std::string errors = errorsOf(c.yaml);
    if (std::string(c.message).empty()) CHECK(errors.empty());
    else CHECK_THAT(errors, Catch::Contains(c.message));
  }
}

TEST_CASE("loader: a deeply nested prim tree is refused by the path limit", "[scene_io][loader]") {
  std::string yaml = "version: 1\nprims:\n";
  std::string path;
  for (int i = 0; i < 300; ++i) {
    path += "/p";
    yaml += "  " + path + ": {}\n";
  }
  CHECK_THAT(errorsOf(yaml), Catch::Contains("prims may be nested at most 256 levels deep"));
}

TEST_CASE("loader: yaml nesting beyond the parser's depth guard is an error, not a crash", "[scene_io][loader]") {
  std::string yaml = "version: 1\nprims: " + std::string(5000, '[') + std::string(5000, ']') + "\n";
  CHECK_THAT(errorsOf(yaml), Catch::Contains("not valid YAML"));
}

TEST_CASE("loader: an alias inside its own anchor is refused, not followed forever", "[scene_io][loader]") {
  CHECK_THAT(errorsOf("version: 1\nprims:\n  /World:\n    a: &loop [1, *loop]\n"),
             Catch::Contains("4:18: error: an alias used inside its own anchor"));
}

TEST_CASE("loader: aliases cannot nest a document deeper than the limit", "[scene_io][loader]") {
  // Each anchor nests 300 levels, within the parser's guard, around an alias
  // of the one before: four of them are 1,200 levels.
  auto nest = [](const std::string& inner) { return std::string(300, '[') + inner + std::string(300, ']'); };
  std::string yaml = "version: 1\nprims: {}\na: &a " + nest("1") + "\nb: &b " + nest("*a") + "\nc: &c " +
                     nest("*b") + "\nd: " + nest("*c") + "\n";
  CHECK_THAT(errorsOf(yaml), Catch::Contains("t.yaml:6:") &&
                                 Catch::Contains("nests more than 1000 levels deep, counting through aliases"));
}

TEST_CASE("loader: the copies nested anchors keep count against the node limit", "[scene_io][loader]") {
  // 400 anchors, each around the next, around a list of 10,000 items: a
  // 44 KB document whose anchor copies would hold 4 million nodes.
  std::string yaml = "version: 1\nprims: {}\nx: ";
  for (int i = 0; i < 400; ++i) yaml += "&a" + std::to_string(i) + " [";
  for (int i = 0; i < 10000; ++i) yaml += "1,";
  yaml += "1" + std::string(400, ']') + "\n";
  CHECK_THAT(errorsOf(yaml), Catch::Contains("the document has more than 2000000 nodes"));
}

TEST_CASE("loader: a document of more than 2,000,000 plain nodes is refused while it is read", "[scene_io][loader]") {
  std::string yaml = "version: 1\nprims: {}\nx: [";
  for (int i = 0; i < 2'000'000; ++i) yaml += "1,";
  yaml += "1]\n";
  CHECK_THAT(errorsOf(yaml), Catch::Contains("t.yaml:3:") && Catch::Contains("the document has more than 2000000 nodes"));
}

TEST_CASE("loader: every input the fuzzer crashed on now loads or fails cleanly", "[scene_io][loader][fuzz]") {
  // Each file is a crash make fuzz once found, kept byte for byte (comments
  // in it are the fuzzer's mutated leftovers of seed scenes, not
  // expectations); the harness's own call is replayed.
  const std::filesystem::path dir = SDG_SOURCE_DIR "/tests/data/fuzz_regressions";
  int replayed = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    INFO(entry.path().filename().string());
    try {
      loadText(text.str(), sdg::test::testCatalog());
    } catch (const sdg::SceneError&) {
    } catch (const sdg::RunError&) {
    }
    ++replayed;
  }
  CHECK(replayed > 0);
}
