// The writer registry and the annotator table: one source of truth with the
// scene's option tables, and an unknown writer type is a located error.
#include <catch2/catch.hpp>

#include <algorithm>

#include "core/diagnostics.h"
#include "writers/annotator_table.h"
#include "writers/writer_registry.h"

using namespace sdg;

TEST_CASE("writer registry: the types the scene accepts are the types it can make", "[writers][registry]") {
  std::vector<std::string_view> scene;
  for (const WriterTypeInfo& t : writerTypes()) scene.push_back(t.name);
  CHECK(scene == registeredWriterTypes());
}

TEST_CASE("writer registry: an unknown type is a located error with the nearest name", "[writers][registry]") {
  WriterConfig config{"BasicWritter", OptionSet(findWriterType("BasicWriter")->options), SourceLoc{"scene.yaml", 7, 3}};
  try {
    makeWriters({config}, WriterSetup{{"Camera"}, 1, 8, 8, nullptr, nullptr, {}}, SourceLoc{"scene.yaml", 0, 0});
    FAIL("no error");
  } catch (const SceneError& e) {
    const std::string text = e.what();
    CHECK_THAT(text, Catch::Contains("scene.yaml:7:3"));
    CHECK_THAT(text, Catch::Contains("unknown writer 'BasicWritter'"));
    CHECK_THAT(text, Catch::Contains("did you mean 'BasicWriter'"));
  }
  CHECK_THROWS_WITH(makeWriters({}, WriterSetup{}, SourceLoc{"scene.yaml", 0, 0}), Catch::Contains("has no writer"));
}

TEST_CASE("writer registry: needs are derived from the annotators a writer turns on", "[writers][registry]") {
  OptionSet options(findWriterType("BasicWriter")->options);
  options.set("rgb", Value::makeBool(true));
  const SourceLoc here{"scene.yaml", 1, 1};
  WriterSet rgbOnly = makeWriters({{"BasicWriter", options, here}}, WriterSetup{{"Camera"}, 1, 8, 8, nullptr, nullptr, {}}, here);
  CHECK_FALSE(rgbOnly.needs.labels);
  CHECK_FALSE(rgbOnly.needs.passes().ids);
  options.set("bounding_box_2d_loose", Value::makeBool(true));
  options.set("distance_to_image_plane", Value::makeBool(true));
  WriterSet boxes = makeWriters({{"BasicWriter", options, here}}, WriterSetup{{"Camera"}, 1, 8, 8, nullptr, nullptr, {}}, here);
  CHECK((boxes.needs.labels && boxes.needs.coverage && boxes.needs.passes().ids && boxes.needs.passes().imagePlane));
  CHECK_FALSE(boxes.needs.passes().normals);
  // COCO alone: a BasicWriter writing its images, then COCO, which needs the labels.
  WriterSet coco = makeWriters({{"CocoWriter", OptionSet(findWriterType("CocoWriter")->options), here}},
                               WriterSetup{{"Camera"}, 1, 8, 8, nullptr, nullptr, {}}, here);
  CHECK(coco.writers.size() == 2);
  CHECK(coco.needs.labels);
  CHECK(coco.parts.cocoFile == "coco_instances.json");
}

TEST_CASE("annotator table: every annotator is a BasicWriter option that turns it on", "[writers][registry]") {
  const auto& specs = findWriterType("BasicWriter")->options;
  for (const AnnotatorInfo& a : annotatorTable()) {
    CAPTURE(a.name);
    auto spec = std::find_if(specs.begin(), specs.end(), [&a](const AttributeSpec& s) { return s.name == a.name; });
    REQUIRE(spec != specs.end());
    CHECK(spec->type == ValueType::Bool);
    CHECK(findAnnotator(a.name) == &a);
  }
}
