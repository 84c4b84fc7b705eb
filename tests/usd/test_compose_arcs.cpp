// Composition arcs and their strength order (LIVRPS), on hand-written layers.
#include <catch2/catch.hpp>

#include "usd/compose_test_util.h"

using namespace sdg::usd;
using sdg::usd::test::composeError;
using sdg::usd::test::MemoryLayers;
using sdg::usd::test::numberAt;
using sdg::usd::test::valueAt;

namespace {

const char* kAsset = R"(#usda 1.0
(
    defaultPrim = "Asset"
)
def Xform "Asset" (
    kind = "component"
    customData = { string from = "asset"; string assetOnly = "yes" }
)
{
    double size = 1
    color3f color = (1, 0, 0)
    def Mesh "Geom" {
        rel material:binding = </Asset/Looks/Mat>
        float inputs:x.connect = </Asset/Looks/Mat.outputs:out>
    }
    def Scope "Looks" { def Material "Mat" {} }
}
)";

std::vector<std::string> names(std::initializer_list<const char*> items) { return {items.begin(), items.end()}; }

}  // namespace

TEST_CASE("compose: local opinions over a reference, defaultPrim, provenance", "[compose]") {
  MemoryLayers layers;
  layers.texts["asset.usda"] = kAsset;
  layers.texts["root.usda"] = R"(#usda 1.0
def "A" (
    references = @asset.usda@
    customData = { string from = "root" }
)
{
    double size = 2
}
def "B" (references = @./asset.usda@</Asset/Geom>) {}
)";
  ComposedStage stage = layers.compose("root.usda");
  const ComposedPrim* a = stage.prim("/A");
  REQUIRE(a);
  CHECK(a->typeName == "Xform");
  CHECK(a->kind == "component");
  CHECK(a->specifier == Specifier::Def);
  CHECK(a->defined);
  CHECK(numberAt(stage, "/A", "size") == 2);
  CHECK(valueAt(stage, "/A", "color").numbers == std::vector<double>{1, 0, 0});
  CHECK(a->loc.str() == "root.usda:2:1");
  CHECK(a->layers == names({"root.usda", "asset.usda"}));
  CHECK(a->property("size")->loc.str() == "root.usda:7:5");
  CHECK(a->property("color")->loc.str() == "asset.usda:11:5");
  CHECK(a->property("color")->typeName == "color3f");
  // Dictionaries merge key by key, the stronger opinion winning.
  const Dictionary& data = *a->metadata.at("customData").dictionary;
  CHECK(data.at("from").asString() == "root");
  CHECK(data.at("assetOnly").asString() == "yes");
  // Children come through the reference, with paths mapped into /A.
  CHECK(a->children == names({"Geom", "Looks"}));
  const ComposedPrim* geom = stage.prim("/A/Geom");
  REQUIRE(geom);
  CHECK(geom->property("material:binding")->targets == names({"/A/Looks/Mat"}));
  CHECK(geom->property("inputs:x")->connections == names({"/A/Looks/Mat.outputs:out"}));
  REQUIRE(stage.prim("/B"));
  CHECK(stage.prim("/B")->typeName == "Mesh");
  // The binding of /B points outside the referenced prim: dropped, with a warning.
  CHECK(stage.prim("/B")->property("material:binding")->targets.empty());
  REQUIRE(stage.warnings.size() == 2);
  CHECK_THAT(stage.warnings[0].message, Catch::Contains("/B.material:binding: the path </Asset/Looks/Mat> written at asset.usda:13:9 lies outside the scope of the reference"));
  CHECK(stage.rootPrims() == names({"/A", "/B"}));
  CHECK(layers.reads == names({"root.usda", "asset.usda"}));  // each layer read once
}

TEST_CASE("compose: the strength order of the arcs (LIVRPS)", "[compose]") {
  MemoryLayers layers;
  layers.texts["ref.usda"] = R"(#usda 1.0
def "R" { double a = 1
  double b = 1
  double c = 1
  double d = 1
  double e = 1 }
)";
  layers.texts["payload.usda"] = R"(#usda 1.0
def "P" { double a = 2
  double b = 2
  double c = 2
  double d = 2
  double e = 2
  double p = 2 }
)";
  layers.texts["root.usda"] = R"(#usda 1.0
class "_Class" { double c = 4
  double b = 4 }
class "_Base" { double e = 6
  double s = 6 }
def "A" (
    inherits = </_Class>
    references = @ref.usda@</R>
    payload = @payload.usda@</P>
    specializes = </_Base>
    variants = { string v = "x" }
    variantSets = "v"
)
{
    double a = 5
    variantSet "v" = {
        "x" { double a = 3
            double b = 3
            double d = 3 }
    }
}
)";
  ComposedStage stage = layers.compose("root.usda");
  CHECK(numberAt(stage, "/A", "a") == 5);  // local over everything
  CHECK(numberAt(stage, "/A", "c") == 4);  // inherits over references
  CHECK(numberAt(stage, "/A", "b") == 4);  // inherits over variants
  CHECK(numberAt(stage, "/A", "d") == 3);  // variants over references
  CHECK(numberAt(stage, "/A", "e") == 1);  // references over specializes
  CHECK(numberAt(stage, "/A", "p") == 2);  // payloads are loaded
  CHECK(numberAt(stage, "/A", "s") == 6);  // specializes, the weakest, still count
  const ComposedPrim* a = stage.prim("/A");
  REQUIRE(a->variantSets.size() == 1);
  CHECK(a->variantSets[0].name == "v");
  CHECK(a->variantSets[0].variants == names({"x"}));
  CHECK(a->variantSets[0].selection == "x");
  CHECK(stage.prim("/_Class")->abstract);
  CHECK_FALSE(a->abstract);
}

TEST_CASE("compose: references are stronger than payloads and listed order decides", "[compose]") {
  MemoryLayers layers;
  layers.texts["one.usda"] = "#usda 1.0\ndef \"X\" { double v = 1 }\n";
  layers.texts["two.usda"] = "#usda 1.0\ndef \"X\" { double v = 2\n double w = 2 }\n";
  layers.texts["root.usda"] = R"(#usda 1.0
def "A" ( references = [@one.usda@</X>, @two.usda@</X>] ) {}
def "B" ( references = [@two.usda@</X>, @one.usda@</X>] ) {}
def "C" ( payload = @two.usda@</X>
          references = @one.usda@</X> ) {}
)";
  ComposedStage stage = layers.compose("root.usda");
  CHECK(numberAt(stage, "/A", "v") == 1);
  CHECK(numberAt(stage, "/A", "w") == 2);
  CHECK(numberAt(stage, "/B", "v") == 2);
  CHECK(numberAt(stage, "/C", "v") == 1);
}

TEST_CASE("compose: sublayers in order, with list-op edits across layers", "[compose]") {
  MemoryLayers layers;
  layers.texts["strong.usda"] = R"(#usda 1.0
over "A" (
    prepend apiSchemas = ["StrongAPI"]
    delete apiSchemas = ["GoneAPI"]
    delete references = @x.usda@</X>
)
{
    double size = 2
    prepend rel targets = </Z>
    delete rel targets = </X>
}
)";
  layers.texts["weak.usda"] = R"(#usda 1.0
def Xform "A" (
    apiSchemas = ["WeakAPI", "GoneAPI"]
    references = [@x.usda@</X>, @y.usda@</Y>]
)
{
    double size = 1
    double weakOnly = 1
    rel targets = [</X>, </Y>]
}
def "Explicit" ( prepend apiSchemas = ["WeakAPI"] ) {}
)";
  layers.texts["x.usda"] = "#usda 1.0\ndef \"X\" { double fromX = 1 }\n";
  layers.texts["y.usda"] = "#usda 1.0\ndef \"Y\" { double fromY = 1 }\n";
  layers.texts["root.usda"] = R"(#usda 1.0
(
    subLayers = [@strong.usda@, @weak.usda@]
)
over "A" { double rootOnly = 3 }
over "Explicit" ( apiSchemas = ["RootAPI"] ) {}
)";
  ComposedStage stage = layers.compose("root.usda");
  const ComposedPrim* a = stage.prim("/A");
  REQUIRE(a);
  CHECK(a->specifier == Specifier::Def);  // over in stronger layers, def in a weaker one
  CHECK(a->typeName == "Xform");
  CHECK(numberAt(stage, "/A", "size") == 2);
  CHECK(numberAt(stage, "/A", "weakOnly") == 1);
  CHECK(numberAt(stage, "/A", "rootOnly") == 3);
  CHECK(a->apiSchemas == names({"StrongAPI", "WeakAPI"}));
  CHECK(a->property("targets")->targets == names({"/Z", "/Y"}));
  CHECK(a->property("fromX") == nullptr);  // the reference deleted in a stronger layer
  CHECK(numberAt(stage, "/A", "fromY") == 1);
  CHECK(stage.prim("/Explicit")->apiSchemas == names({"RootAPI"}));  // an explicit list replaces
  CHECK(a->layers == names({"root.usda", "strong.usda", "weak.usda", "y.usda"}));
  CHECK(stage.layers == names({"root.usda", "strong.usda", "weak.usda", "y.usda"}));
}

TEST_CASE("compose: internal references, children order, inactive and over prims", "[compose]") {
  MemoryLayers layers;
  layers.texts["root.usda"] = R"(#usda 1.0
(
    defaultPrim = "World"
)
class Scope "Prototypes"
{
    def Xform "bolt" (kind = "component")
    {
        def Mesh "mesh" {
            rel material:binding = </World/Looks/metal>
            rel local = </Prototypes/bolt/mesh>
        }
        def "second" {}
    }
}
def Xform "World"
{
    def Scope "Looks" { def Material "metal" {} }
    def "bolt_01" (prepend references = </Prototypes/bolt>)
    {
        def "first" {}
        double3 xformOp:translate = (1, 2, 3)
    }
    def "off" (active = false) { def "hidden" {} }
    over "ghost" { }
}
)";
  ComposedStage stage = layers.compose("root.usda");
  const ComposedPrim* bolt = stage.prim("/World/bolt_01");
  REQUIRE(bolt);
  CHECK(bolt->typeName == "Xform");
  CHECK(bolt->kind == "component");
  CHECK(bolt->children == names({"mesh", "second", "first"}));  // weaker opinions' names first
  const ComposedPrim* mesh = stage.prim("/World/bolt_01/mesh");
  REQUIRE(mesh);
  // Inside the referenced prim paths follow it; outside they keep their meaning.
  CHECK(mesh->property("local")->targets == names({"/World/bolt_01/mesh"}));
  CHECK(mesh->property("material:binding")->targets == names({"/World/Looks/metal"}));
  CHECK(stage.warnings.empty());
  CHECK(stage.prim("/Prototypes/bolt/mesh")->abstract);
  CHECK(stage.prim("/Prototypes/bolt/mesh")->defined);  // defined, but abstract: under a class
  CHECK(stage.prim("/World/bolt_01/mesh")->defined);
  const ComposedPrim* off = stage.prim("/World/off");
  REQUIRE(off);
  CHECK_FALSE(off->active);
  CHECK(off->children.empty());
  CHECK(stage.prim("/World/off/hidden") == nullptr);
  const ComposedPrim* ghost = stage.prim("/World/ghost");
  REQUIRE(ghost);
  CHECK(ghost->specifier == Specifier::Over);
  CHECK_FALSE(ghost->defined);
  CHECK(stage.defaultPrim == "World");
}

TEST_CASE("compose: variant selections — none authored, authored in a reference, overridden, nested", "[compose]") {
  MemoryLayers layers;
  layers.texts["asset.usda"] = R"(#usda 1.0
def "Asset" (
    variants = { string color = "red" }
    prepend variantSets = ["color", "size"]
)
{
    variantSet "color" = {
        "red" ( variants = { string shade = "dark" }
                prepend variantSets = "shade" ) {
            double r = 1
            variantSet "shade" = {
                "dark" { double darkness = 0.9 }
                "light" { double darkness = 0.1 }
            }
        }
        "blue" { double r = 0 }
    }
    variantSet "size" = {
        "big" { double scale = 10 }
        "small" { double scale = 1 }
    }
}
)";
  layers.texts["root.usda"] = R"(#usda 1.0
def "A" (references = @asset.usda@</Asset>) {}
def "B" (references = @asset.usda@</Asset>
         variants = { string color = "blue" }) {}
)";
  ComposedStage stage = layers.compose("root.usda");
  CHECK(numberAt(stage, "/A", "r") == 1);              // the asset's own selection
  CHECK(numberAt(stage, "/A", "darkness") == 0.9);     // a selection written inside a variant
  CHECK(stage.prim("/A")->property("scale") == nullptr);  // no selection: no variant applied
  CHECK(numberAt(stage, "/B", "r") == 0);              // the referencing layer's selection is stronger
  const ComposedPrim* a = stage.prim("/A");
  REQUIRE(a->variantSets.size() == 3);
  CHECK(a->variantSets[0].name == "color");
  CHECK(a->variantSets[0].variants == names({"red", "blue"}));
  CHECK(a->variantSets[1].name == "size");
  CHECK(a->variantSets[1].selection.empty());
  CHECK(a->variantSets[2].name == "shade");

  ComposeOptions options;
  options.variantOverrides["/A"]["size"] = "big";
  options.variantOverrides["/B"]["color"] = "red";
  options.variantOverrides["/B"]["shade"] = "light";
  ComposedStage chosen = layers.compose("root.usda", options);
  CHECK(numberAt(chosen, "/A", "scale") == 10);
  CHECK(numberAt(chosen, "/B", "r") == 1);
  CHECK(numberAt(chosen, "/B", "darkness") == 0.1);

  ComposeOptions bad;
  bad.variantOverrides["/A"]["size"] = "huge";
  CHECK(composeError(layers, "root.usda", bad) ==
        "variant override /A: variant set 'size' has no variant 'huge' (it offers big, small)");
  ComposeOptions noSet;
  noSet.variantOverrides["/A"]["lod"] = "high";
  CHECK(composeError(layers, "root.usda", noSet) == "variant override /A lod=high: the prim has no variant set 'lod'");
  ComposeOptions noPrim;
  noPrim.variantOverrides["/Nope"]["lod"] = "high";
  CHECK(composeError(layers, "root.usda", noPrim) == "variant override /Nope lod=high: there is no prim /Nope in the stage");
}

TEST_CASE("compose: inherits in a referenced asset see the stage's class opinions", "[compose]") {
  MemoryLayers layers;
  layers.texts["asset.usda"] = R"(#usda 1.0
class "_Look" { double shine = 1 }
def "Asset" (inherits = </_Look>) {}
)";
  layers.texts["root.usda"] = R"(#usda 1.0
class "_Look" { double shine = 7 }
def "A" (references = @asset.usda@</Asset>) {}
)";
  ComposedStage stage = layers.compose("root.usda");
  CHECK(numberAt(stage, "/A", "shine") == 7);
}

TEST_CASE("compose: specializes are the weakest arc, even from inside a reference", "[compose]") {
  MemoryLayers layers;
  layers.texts["asset.usda"] = R"(#usda 1.0
def "Base" { double roughness = 0.5
  double metal = 0 }
def "Asset" (specializes = </Base>) { double metal = 1 }
)";
  layers.texts["root.usda"] = R"(#usda 1.0
def "A" (references = @asset.usda@</Asset>) {}
)";
  ComposedStage stage = layers.compose("root.usda");
  CHECK(numberAt(stage, "/A", "metal") == 1);
  CHECK(numberAt(stage, "/A", "roughness") == 0.5);
}

TEST_CASE("compose: units of referenced layers that differ are recorded", "[compose]") {
  MemoryLayers layers;
  layers.texts["cm_yup.usda"] = "#usda 1.0\n(\n metersPerUnit = 0.01\n upAxis = \"Y\"\n)\ndef \"M\" {}\n";
  layers.texts["m_zup.usda"] = "#usda 1.0\n(\n metersPerUnit = 1\n upAxis = \"Z\"\n)\ndef \"M\" {}\n";
  layers.texts["root.usda"] = R"(#usda 1.0
(
    metersPerUnit = 1
    upAxis = "Z"
)
def "Other" (references = @cm_yup.usda@</M>) {}
def "Same" (references = @m_zup.usda@</M>) {}
)";
  ComposedStage stage = layers.compose("root.usda");
  CHECK(stage.units.metersPerUnit == 1);
  CHECK(stage.units.upAxis == "Z");
  const ComposedPrim* other = stage.prim("/Other");
  REQUIRE(other->unitsChange);
  CHECK(other->unitsChange->asset.metersPerUnit == 0.01);
  CHECK(other->unitsChange->asset.upAxis == "Y");
  CHECK(other->unitsChange->asset.layer == "cm_yup.usda");
  CHECK(other->unitsChange->into.upAxis == "Z");
  CHECK_FALSE(stage.prim("/Same")->unitsChange);
}

TEST_CASE("compose: asset paths resolve against the layer that wrote them, inside packages too", "[compose]") {
  CHECK(resolveAssetPath("./b.usda", "/x/y/a.usda") == "/x/y/b.usda");
  CHECK(resolveAssetPath("../b.usda", "/x/y/a.usda") == "/x/b.usda");
  CHECK(resolveAssetPath("b.usda", "rel/a.usda") == "rel/b.usda");
  CHECK(resolveAssetPath("/abs/./b.usda", "/x/a.usda") == "/abs/b.usda");
  CHECK(resolveAssetPath("./tex/wood.png", "/p/pkg.usdz") == "/p/pkg.usdz[tex/wood.png]");
  CHECK(resolveAssetPath("../b.usdc", "/p/pkg.usdz[geo/a.usdc]") == "/p/pkg.usdz[b.usdc]");
  CHECK(resolveAssetPath("../../beside.usda", "/p/pkg.usdz[geo/a.usdc]") == "/p/beside.usda");
  CHECK(resolveAssetPath("./other.usdz[x/../y.usda]", "/p/a.usda") == "/p/other.usdz[y.usda]");

  // A package's root layer referencing another entry of the package.
  MemoryLayers layers;
  layers.texts["/p/pkg.usdz"] = "#usda 1.0\n(\n defaultPrim = \"Root\"\n)\ndef \"Root\" (references = @./geo/part.usda@) {}\n";
  layers.texts["/p/pkg.usdz[geo/part.usda]"] =
      "#usda 1.0\n(\n defaultPrim = \"Part\"\n)\ndef \"Part\" { asset tex = @../tex/wood.png@ }\n";
  layers.texts["/stage.usda"] = "#usda 1.0\ndef \"A\" (references = @./p/pkg.usdz@) {}\n";
  ComposedStage stage = layers.compose("/stage.usda");
  const ComposedProperty* tex = stage.prim("/A")->property("tex");
  REQUIRE(tex);
  CHECK(tex->valueLayer == "/p/pkg.usdz[geo/part.usda]");
  CHECK(tex->resolvedAssets == names({"/p/pkg.usdz[tex/wood.png]"}));
}
