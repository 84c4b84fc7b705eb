// importUsdPrimLabels: material bindings, both semantics forms and Isaac's
// behavior scripts with their exposedVar values, on small composed layers.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "scene_io/usd_import.h"
#include "scene_io/usd_prim_labels.h"
#include "scene_io/usd_fixtures.h"
#include "scratch_name.h"

using namespace sdg;
using sdg::test::builtinCatalog;
using sdg::test::composeText;

namespace {

struct Labelled {
  Stage stage;
  Diagnostics diag;
  UsdImportReport report;
};

// Imports the labels of `path` onto a stage prim of the same path under /Mnt.
Prim& label(const usd::ComposedStage& composed, const std::string& path, Labelled& out,
            const UsdImportOptions& options = {}, PrimType type = PrimType::Xform) {
  if (!out.stage.find("/Mnt")) out.stage.definePrim("/Mnt", PrimType::Xform);
  Prim& prim = out.stage.definePrim("/Mnt" + path, type);
  const usd::ComposedPrim* source = composed.prim(path);
  REQUIRE(source);
  importUsdPrimLabels(composed, *source, prim, [](const std::string& p) { return "/Mnt" + p; }, builtinCatalog(),
                      options, out.report, out.diag);
  return prim;
}

const char* kMaterials = R"(
def Material "Red"
{
    token outputs:surface.connect = </Red/S.outputs:surface>
    def Shader "S"
    {
        uniform token info:id = "UsdPreviewSurface"
    }
}
def Material "Mtlx"
{
    token outputs:mtlx:surface.connect = </Mtlx/S.outputs:out>
    def Shader "S"
    {
        uniform token info:id = "ND_standard_surface_surfaceshader"
    }
}
)";

std::string stageText(const std::string& prims) { return std::string("#usda 1.0\n") + kMaterials + prims; }

}  // namespace

TEST_CASE("usd labels: material bindings and their strength", "[scene_io][usd]") {
  usd::ComposedStage composed = composeText(stageText(R"(
def Cube "Weak"
{
    rel material:binding = </Red>
}
def Cube "Strong"
{
    rel material:binding = </Red> (
        bindMaterialAs = "strongerThanDescendants"
    )
}
def Cube "Fallback"
{
    rel material:binding = </Mtlx>
}
def Cube "Dangling"
{
    rel material:binding = </Nowhere>
}
)"));
  Labelled l;
  CHECK(label(composed, "/Weak", l).material() == MaterialBinding{"/Mnt/Red", "weakerThanDescendants"});
  CHECK(label(composed, "/Strong", l).material() == MaterialBinding{"/Mnt/Red", "strongerThanDescendants"});
  // A material the mapping cannot read is not bound: the cube keeps its displayColor.
  CHECK_FALSE(label(composed, "/Fallback", l).material());
  CHECK_FALSE(label(composed, "/Dangling", l).material());
  CHECK_FALSE(l.diag.hasErrors());
  REQUIRE(l.report.warnings.size() == 1);
  CHECK_THAT(l.report.warnings[0], Catch::StartsWith("/v/scene.usda:"));
  CHECK_THAT(l.report.warnings[0], Catch::Contains("/Nowhere is not on the composed stage"));
}

TEST_CASE("usd labels: GeomSubset bindings onto a one-material stage prim", "[scene_io][usd]") {
  usd::ComposedStage composed = composeText(stageText(R"(
def Mesh "One"
{
    def GeomSubset "Top"
    {
        uniform token familyName = "materialBind"
        rel material:binding = </Red>
    }
}
def Mesh "Two"
{
    def GeomSubset "A"
    {
        rel material:binding = </Red>
    }
    def GeomSubset "B"
    {
        rel material:binding = </Red>
    }
}
)"));
  Labelled l;
  CHECK(label(composed, "/One", l, {}, PrimType::Mesh).material() == MaterialBinding{"/Mnt/Red", "weakerThanDescendants"});
  CHECK(l.report.warnings.empty());
  CHECK_FALSE(label(composed, "/Two", l, {}, PrimType::Mesh).material());
  REQUIRE(l.report.warnings.size() == 1);
  CHECK_THAT(l.report.warnings[0], Catch::Contains("/Two: 2 GeomSubsets"));
}

TEST_CASE("usd labels: both of Isaac's semantics forms", "[scene_io][usd]") {
  usd::ComposedStage composed = composeText(R"(#usda 1.0
def Cube "Box" (
    prepend apiSchemas = ["SemanticsAPI:Semantics_a1", "SemanticsAPI:Semantics_b2", "SemanticsLabelsAPI:class"]
)
{
    string semantic:Semantics_a1:params:semanticData = "box"
    string semantic:Semantics_a1:params:semanticType = "class"
    string semantic:Semantics_b2:params:semanticData = "cardboard"
    string semantic:Semantics_b2:params:semanticType = "material"
    token[] semantics:labels:class = ["box", "container"]
    token[] semantics:labels:bad:name = ["x"]
}
)");
  Labelled l;
  Prim& box = label(composed, "/Box", l);
  CHECK(box.semantics().at("class") == std::vector<std::string>{"box", "container"});
  CHECK(box.semantics().at("material") == std::vector<std::string>{"cardboard"});
  REQUIRE(l.diag.errorCount() == 1);
  CHECK_THAT(l.diag.all()[0].message, Catch::Contains("bad:name"));
  CHECK(l.diag.all()[0].loc.str() == "/v/scene.usda:11:5");
}

TEST_CASE("usd labels: Isaac's behavior scripts become the built-ins with typed exposedVar values",
          "[scene_io][usd]") {
  usd::ComposedStage composed = composeText(R"(#usda 1.0
def Xform "Target"
{
}
def Cube "Box"
{
    asset[] omni:scripting:scripts = [
        @/isaac-sim/exts/isaacsim.replicator.behavior/isaacsim/replicator/behavior/behaviors/location_randomizer.py@,
        @/isaac-sim/exts/isaacsim.replicator.behavior/isaacsim/replicator/behavior/behaviors/look_at_behavior.py@
    ]
    custom vector3d exposedVar:locationRandomizer:range:minPosition = (-2, -3, 0)
    custom vector3d exposedVar:locationRandomizer:range:maxPosition = (2, 3, 1)
    custom uint exposedVar:locationRandomizer:interval = 5
    custom string exposedVar:lookAtBehavior:targetPrimPath = "/Target"
}
)");
  Labelled l;
  Prim& box = label(composed, "/Box", l);
  CHECK_FALSE(l.diag.hasErrors());
  CHECK(box.behaviors() == std::vector<std::string>{"locationRandomizer", "lookAtBehavior"});
  const Attribute* minPos = box.findAttribute("exposedVar:locationRandomizer:range:minPosition");
  REQUIRE(minPos);
  CHECK(minPos->value == Value::makeVector3d({-2, -3, 0}));
  CHECK(minPos->loc.str() == "/v/scene.usda:11:5");
  CHECK(box.findAttribute("exposedVar:locationRandomizer:interval")->value == Value::makeUInt(5));
  // Variables the stage does not author take the spec's defaults.
  CHECK(box.findAttribute("exposedVar:locationRandomizer:seed")->value == Value::makeInt(-1));
  // Prim paths point into the stage.
  CHECK(box.findAttribute("exposedVar:lookAtBehavior:targetPrimPath")->value == Value::makeString("/Mnt/Target"));
}

TEST_CASE("usd labels: a bad exposedVar value is located at the usda file:line:col", "[scene_io][usd]") {
  usd::ComposedStage composed = composeText(R"(#usda 1.0
def Cube "Box"
{
    asset[] omni:scripting:scripts = [@/isaac/behaviors/rotation_randomizer.py@]
    custom float exposedVar:rotationRandomizer:range:minRotation = 3
    custom int exposedVar:rotationRandomizer:intervall = 3
}
)");
  Labelled l;
  label(composed, "/Box", l);
  REQUIRE(l.diag.errorCount() == 2);
  CHECK(l.diag.all()[0].format().starts_with("/v/scene.usda:5:5: error: /Box.exposedVar:rotationRandomizer:range:minRotation: expected"));
  CHECK(l.diag.all()[1].loc.str() == "/v/scene.usda:6:5");
  CHECK_THAT(l.diag.all()[1].message, Catch::Contains("did you mean"));
}

TEST_CASE("usd labels: listed scripts stand for what the program's loader attached, else are located errors",
          "[scene_io][usd]") {
  const std::filesystem::path dir = test::uniqueTempPath("sdg_usd_labels_test");
  std::filesystem::create_directories(dir);
  const std::string mine = (dir / "wobble.py").string();
  std::ofstream(mine) << "import sdgbehave\n\nBEHAVIOR_NS = \"wobble\"\n";
  const std::string isaacOnly = (dir / "isaac_thing.py").string();
  std::ofstream(isaacOnly) << "import omni.kit\n";
  usd::ComposedStage composed = composeText("#usda 1.0\ndef Cube \"Box\"\n{\n    asset[] omni:scripting:scripts = [@" + mine +
                                            "@, @" + isaacOnly + "@, @/nowhere/missing.py@]\n}\n");
  // Every listed file, whatever it holds: the loader decides what each is.
  const std::vector<ListedScript> listed = usdListedScripts(composed);
  REQUIRE(listed.size() == 3);
  CHECK(listed[0].path == mine);
  CHECK(listed[1].path == isaacOnly);
  CHECK(listed[2].loc.str() == "/v/scene.usda:4:5");

  // No loader attached them: each is a located error saying why.
  Labelled l;
  label(composed, "/Box", l);
  REQUIRE(l.diag.errorCount() == 3);
  for (const Diagnostic& d : l.diag.all()) CHECK(d.loc.str() == "/v/scene.usda:4:5");
  CHECK_THAT(l.diag.all()[0].message, Catch::Contains("was not loaded"));
  CHECK_THAT(l.diag.all()[1].message, Catch::Contains("was not loaded"));
  CHECK_THAT(l.diag.all()[2].message, Catch::Contains("not found (hint"));

  // What the loader recorded (BehaviorCatalog::attachedScripts) is attached, every behavior of the file.
  BehaviorCatalog catalog = builtinCatalog();
  catalog.attachedScripts[mine] = {"locationRandomizer", "lookAtBehavior"};
  usd::ComposedStage one = composeText("#usda 1.0\ndef Cube \"Box\"\n{\n    asset[] omni:scripting:scripts = [@" + mine + "@]\n}\n");
  Stage stage;
  stage.definePrim("/Mnt", PrimType::Xform);
  Prim& box = stage.definePrim("/Mnt/Box", PrimType::Cube);
  Diagnostics diag;
  UsdImportReport report;
  importUsdPrimLabels(one, *one.prim("/Box"), box, [](const std::string& p) { return "/Mnt" + p; }, catalog, {},
                      report, diag);
  CHECK_FALSE(diag.hasErrors());
  CHECK(box.behaviors() == std::vector<std::string>{"locationRandomizer", "lookAtBehavior"});

  // Without builtinsForIsaacScripts, Isaac's own scripts are not stand-ins.
  usd::ComposedStage isaac = composeText(R"(#usda 1.0
def Cube "Box"
{
    asset[] omni:scripting:scripts = [@/isaac/behaviors/light_randomizer.py@]
}
)");
  Labelled off;
  UsdImportOptions options;
  options.builtinsForIsaacScripts = false;
  CHECK(label(isaac, "/Box", off, options).behaviors().empty());
  CHECK(off.diag.errorCount() == 1);
  std::filesystem::remove_all(dir);
}
