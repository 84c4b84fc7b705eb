// Composition of the real files in ../shared/usd-samples: the Teapot (a
// payload, sublayers, nested variant sets, references in variants), its
// DrawModes stage (internal references to a referenced asset), the
// relationship encapsulation tests (targets across internal and external
// references) and MaterialX references (not USD layers: ignored with a
// warning). Counts and values were checked against the files by hand.
#include <catch2/catch.hpp>

#include "usd/compose.h"
#include "usd/layer_io.h"
#include "usd/samples_dir.h"

using namespace sdg::usd;
using sdg::usd::test::samplesDir;

namespace {

ComposedStage composeSample(const std::string& relative, const ComposeOptions& options = {}) {
  return composeStage(samplesDir() + "/" + relative, textLayerFileReader(), options);
}

size_t countDefined(const ComposedStage& stage) {
  size_t n = 0;
  for (const ComposedPrim& p : stage.prims) n += p.defined && !p.abstract && p.active;
  return n;
}

const ComposedProperty& prop(const ComposedStage& stage, const std::string& prim, const std::string& name) {
  const ComposedPrim* p = stage.prim(prim);
  INFO(prim);
  REQUIRE(p);
  const ComposedProperty* property = p->property(name);
  INFO(name);
  REQUIRE(property);
  return *property;
}

std::string fileName(const std::string& path) { return path.substr(path.rfind('/') + 1); }

}  // namespace

TEST_CASE("compose samples: the Teapot with its payload, sublayer and variants", "[samples]") {
  ComposedStage stage = composeSample("full_assets/Teapot/Teapot.usd");
  CHECK(stage.prims.size() == 17);
  CHECK(stage.units.metersPerUnit == 1);
  CHECK(stage.units.upAxis == "Y");
  CHECK(stage.timeCode == 1);
  CHECK(stage.defaultPrim == "Teapot");
  CHECK(stage.warnings.empty());
  const ComposedPrim* teapot = stage.prim("/Teapot");
  REQUIRE(teapot);
  CHECK(teapot->kind == "component");
  CHECK(teapot->apiSchemas == std::vector<std::string>{"GeomModelAPI"});
  REQUIRE(teapot->variantSets.size() == 2);
  CHECK(teapot->variantSets[0].name == "modelVariant");
  CHECK(teapot->variantSets[0].selection == "Utah");
  CHECK(teapot->variantSets[0].variants == std::vector<std::string>{"Fancy", "Utah"});
  CHECK(teapot->variantSets[1].name == "shadingVariant");
  CHECK(teapot->variantSets[1].selection == "CeramicLimeGreen");
  CHECK(teapot->metadata.at("assetInfo").dictionary->at("name").asString() == "Teapot");
  // The Utah geometry, through payload -> sublayer -> variant -> reference.
  const ComposedProperty& points = prop(stage, "/Teapot/Geometry", "points");
  CHECK(points.typeName == "point3f[]");
  CHECK(points.value.elementCount() == 1286);
  CHECK(fileName(points.loc.file) == "UtahTeapot.usd");
  CHECK(points.loc.line == 18);
  CHECK(prop(stage, "/Teapot/Geometry", "material:binding").targets ==
        std::vector<std::string>{"/Teapot/Materials/Ceramic"});
  CHECK(prop(stage, "/Teapot/Geometry", "primvars:displayColor").value.numbers ==
        std::vector<double>{double(0.325f), double(0.825f), 0});
  const ComposedPrim* geometry = stage.prim("/Teapot/Geometry");
  REQUIRE(geometry->layers.size() == 2);
  CHECK(fileName(geometry->layers[0]) == "Teapot_Materials.usd");
  CHECK(fileName(geometry->layers[1]) == "UtahTeapot.usd");
  // Asset values resolve against the layer that wrote them.
  const ComposedProperty& card = prop(stage, "/Teapot", "model:cardTextureXNeg");
  CHECK(card.value.asString() == "./cards/Utah/XNeg.png");
  REQUIRE(card.resolvedAssets.size() == 1);
  CHECK(card.resolvedAssets[0] == samplesDir() + "/full_assets/Teapot/cards/Utah/XNeg.png");

  ComposeOptions fancy;
  fancy.variantOverrides["/Teapot"]["modelVariant"] = "Fancy";
  ComposedStage other = composeSample("full_assets/Teapot/Teapot.usd", fancy);
  CHECK(other.prim("/Teapot")->variantSets[1].selection == "PorcelainFlowers");
  CHECK(other.prim("/Teapot/Geometry/body"));
  CHECK_FALSE(other.prim("/Teapot/Geometry/Body"));
  CHECK(prop(other, "/Teapot/Geometry/body", "indices").value.elementCount() == 2872);
  const ComposedProperty& file = prop(other, "/Teapot/Materials/PorcelainFlowers/UsdPreview/img_diffuseColor", "inputs:file");
  CHECK(file.resolvedAssets[0] == samplesDir() + "/full_assets/Teapot/textures/tea_set_01_diff_2k.jpg");
  CHECK(prop(other, "/Teapot/Materials/PorcelainFlowers/UsdPreview/usdpreviewsurface", "inputs:roughness").connections ==
        std::vector<std::string>{"/Teapot/Materials/PorcelainFlowers/UsdPreview/img_ARM.outputs:g"});
}

TEST_CASE("compose samples: DrawModes references the Teapot and its own prims", "[samples]") {
  ComposedStage stage = composeSample("full_assets/Teapot/DrawModes.usd");
  CHECK(stage.prims.size() == 597);
  CHECK(stage.warnings.empty());
  // FancyTeapot_1 references FancyTeapot_0 internally, which references the Teapot asset.
  const ComposedPrim* copy = stage.prim("/World/FancyTeapot_1");
  REQUIRE(copy);
  CHECK(copy->variantSets[0].selection == "Fancy");
  CHECK(prop(stage, "/World/FancyTeapot_1", "xformOpOrder").value.strings ==
        std::vector<std::string>{"xformOp:transform", "xformOp:transform:duplicate1"});
  CHECK(prop(stage, "/World/FancyTeapot_1", "xformOp:transform").value.numbers[12] == -1.5);  // from FancyTeapot_0
  CHECK(prop(stage, "/World/FancyTeapot_1/Geometry", "material:binding").targets ==
        std::vector<std::string>{"/World/FancyTeapot_1/Materials/PorcelainFlowers"});
  CHECK_FALSE(copy->unitsChange);  // the Teapot's units are the stage's
}

TEST_CASE("compose samples: relationship targets across internal and external references", "[samples]") {
  const std::string dir = "test_assets/RelationshipEncapsulationTests/";
  ComposedStage bad = composeSample(dir + "ExternalReferenceBadTargetTest.usda");
  CHECK(bad.prims.size() == 11);
  CHECK(bad.units.metersPerUnit == 0.01);
  CHECK(bad.units.upAxis == "Z");
  CHECK(prop(bad, "/World/washer", "material:binding").targets.empty());
  REQUIRE(bad.warnings.size() == 1);
  CHECK_THAT(bad.warnings[0].message, Catch::Contains("/World/washer.material:binding: the path </World/Looks/metal> written at"));
  CHECK_THAT(bad.warnings[0].message, Catch::Contains("washer.usda:183:13 lies outside the scope of the reference"));

  for (const char* file : {"InternalReferenceTest.usda", "SublayeredInternalReferenceTest.usda"}) {
    INFO(file);
    ComposedStage stage = composeSample(dir + file);
    CHECK(stage.prims.size() == 30);
    CHECK(countDefined(stage) == 25);  // the five prototypes are abstract
    CHECK(stage.warnings.empty());
    for (const char* bolt : {"/World/bolt_01/bolt", "/World/bolt_02/bolt", "/World/bolt_03/bolt"})
      CHECK(prop(stage, bolt, "material:binding").targets == std::vector<std::string>{"/World/Looks/metal"});
  }
  ComposedStage assemblies = composeSample(dir + "ReferencedAssembliesWithInternalReferencesTest.usda");
  CHECK(assemblies.prims.size() == 47);
  CHECK(assemblies.warnings.empty());
  CHECK(prop(assemblies, "/World/Encapsulated/bolt_01/bolt", "material:binding").targets ==
        std::vector<std::string>{"/World/Encapsulated/Looks/metal"});
}

TEST_CASE("compose samples: MaterialX references are not USD layers and are skipped", "[samples]") {
  ComposedStage stage = composeSample("test_assets/MaterialXTest/basic.usda");
  CHECK(stage.prims.size() == 2);
  REQUIRE(stage.warnings.size() == 1);
  CHECK_THAT(stage.warnings[0].message, Catch::Contains("basic.usda:9:18: reference @./usd_preview_surface_plastic.mtlx@</MaterialX>: not a USD layer"));
  ComposedStage coords = composeSample("test_assets/TextureCoordinateTest/TextureCoordinateTest.usda");
  CHECK(coords.prims.size() == 39);
  CHECK(coords.warnings.empty());
}

TEST_CASE("compose samples: a Y-up metre asset referenced into a Z-up centimetre stage records its units", "[samples]") {
  std::string teapot = samplesDir() + "/full_assets/Teapot/Teapot.usd";
  LayerReader files = textLayerFileReader();
  LayerReader reader = [&](const std::string& identifier) {
    if (identifier != "stage.usda") return files(identifier);
    return readUsdaLayer("#usda 1.0\n(\n metersPerUnit = 0.01\n upAxis = \"Z\"\n)\ndef Xform \"Pot\" (references = @" +
                             teapot + "@) {}\n",
                         identifier);
  };
  ComposedStage stage = composeStage("stage.usda", reader);
  const ComposedPrim* pot = stage.prim("/Pot");
  REQUIRE(pot);
  REQUIRE(pot->unitsChange);
  CHECK(pot->unitsChange->asset.metersPerUnit == 1);
  CHECK(pot->unitsChange->asset.upAxis == "Y");
  CHECK(pot->unitsChange->asset.layer == teapot);
  CHECK(pot->unitsChange->into.metersPerUnit == 0.01);
  CHECK(pot->unitsChange->into.upAxis == "Z");
  // Prims inside the asset are in the asset's own units: nothing more to correct.
  CHECK_FALSE(stage.prim("/Pot/Geometry")->unitsChange);
  CHECK(stage.prim("/Pot/Geometry")->typeName == "Mesh");
}
