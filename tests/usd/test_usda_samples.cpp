// The usda parser on real files (../shared/usd-samples): every text layer
// there parses, and a few known values come out as written.
#include <catch2/catch.hpp>
#include <algorithm>

#include "usd/layer_io.h"
#include "usd/samples_dir.h"

using namespace sdg::usd;
using sdg::usd::test::sampleFiles;
using sdg::usd::test::samplesDir;

TEST_CASE("usda samples: every text layer parses", "[samples]") {
  std::vector<std::string> files = sampleFiles({".usda", ".usd"});
  REQUIRE(files.size() >= 20);
  size_t text = 0;
  for (const std::string& file : files) {
    std::string bytes = readFileBytes(file);
    if (bytes.compare(0, 5, "#usda") != 0) continue;
    ++text;
    INFO(file);
    Layer layer = readTextLayerFile(file);
    CHECK(layer.pseudoRoot().type == SpecType::PseudoRoot);
    CHECK(!layer.pseudoRoot().fields.empty());  // every sample has layer metadata
  }
  CHECK(text == files.size());  // the samples' .usd files are all text
}

TEST_CASE("usda samples: known values of the teapot and the bolt", "[samples]") {
  Layer teapot = readTextLayerFile(samplesDir() + "/full_assets/Teapot/Teapot.usd");
  CHECK(teapot.pseudoRoot().field("defaultPrim")->asString() == "Teapot");
  CHECK(teapot.pseudoRoot().field("upAxis")->asString() == "Y");
  const Value* payload = teapot.spec("/Teapot")->field("payload");
  REQUIRE(payload);
  REQUIRE(payload->referenceListOp->prependedItems.size() == 1);
  CHECK(payload->referenceListOp->prependedItems[0].assetPath == "./Teapot_Payload.usd");
  const Value* extents = teapot.spec("/Teapot{modelVariant=Fancy}.extentsHint")->field("default");
  REQUIRE(extents);
  CHECK(extents->kind == Kind::Vec3f);
  CHECK(extents->elementCount() == 2);
  CHECK(extents->numbers[0] == double(-0.1526284f));

  Layer utah = readTextLayerFile(samplesDir() + "/full_assets/Teapot/geo/UtahTeapot.usd");
  const Spec* mesh = nullptr;
  for (const auto& [path, spec] : utah.specs)
    if (spec.type == SpecType::Prim && spec.field("typeName") && spec.field("typeName")->asString() == "Mesh") mesh = &spec;
  REQUIRE(mesh);

  Layer bolt = readTextLayerFile(samplesDir() + "/test_assets/RelationshipEncapsulationTests/ExternalReferenceBadTargetTest/bolt.usda");
  CHECK(bolt.pseudoRoot().field("metersPerUnit")->asDouble() == 0.01);
}
