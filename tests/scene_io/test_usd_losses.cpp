// What a USD stage has that the stage does not carry over: one warning per
// kind of loss, with the count and the first place (scene_io/usd_losses.h).
#include <catch2/catch.hpp>

#include "scene_io/usd_import.h"
#include "scene_io/usd_fixtures.h"

namespace sdg {
namespace {

UsdImportReport importText(const std::string& text) {
  test::ImportedStage in;
  test::importText(text, in);
  REQUIRE_FALSE(in.diag.hasErrors());
  return std::move(in.report);
}

const DroppedWarning* findDropped(const std::vector<DroppedWarning>& all, const std::string& kind,
                                  const std::string& what) {
  for (const DroppedWarning& d : all)
    if (d.info.kind == kind && d.info.what == what) return &d;
  return nullptr;
}

}  // namespace

TEST_CASE("UsdLosses counts each kind once and keeps the first place", "[usd_losses]") {
  UsdLosses losses;
  losses.note(UsdLossKind::PrimType, "BasisCurves", SourceLoc{"a.usda", 3, 1}, "/A");
  losses.note(UsdLossKind::PrimType, "BasisCurves", SourceLoc{"a.usda", 9, 1}, "/B");
  losses.note(UsdLossKind::PrimType, "Points", SourceLoc{"a.usda", 12, 1}, "/C");
  losses.note(UsdLossKind::AppliedSchema, "ShapingAPI", SourceLoc{"a.usda", 20, 5}, "/L");
  const std::vector<DroppedWarning> w = losses.warnings();
  REQUIRE(w.size() == 3);
  CHECK(w[0].diagnostic.severity == Severity::Warning);
  CHECK(w[0].diagnostic.loc.line == 3);
  CHECK(w[0].info.count == 2);
  CHECK_THAT(w[0].diagnostic.message, Catch::StartsWith("dropped: 2 prims of type BasisCurves (first /A)"));
  CHECK_THAT(w[1].diagnostic.message, Catch::StartsWith("dropped: 1 prim of type Points (/C)"));
  CHECK(w[2].info.kind == "applied_schema");

  UsdLosses more;
  more.note(UsdLossKind::PrimType, "Points", SourceLoc{"b.usda", 1, 1}, "/D");
  losses.append(more);
  CHECK(losses.warnings()[1].info.count == 2);
  CHECK(losses.warnings()[1].diagnostic.loc.file.str() == "a.usda");
}

TEST_CASE("applied schemas that change the look are losses, others are not", "[usd_losses]") {
  CHECK(appliedSchemaChangesAppearance("ShapingAPI", true));
  CHECK(appliedSchemaChangesAppearance("ShadowAPI", true));
  CHECK_FALSE(appliedSchemaChangesAppearance("OmniLensDistortionOpenCvPinholeAPI", false));  // read (lens models)
  CHECK(appliedSchemaChangesAppearance("OmniLensDistortionRadTanThinPrismAPI", false));
  CHECK(appliedSchemaChangesAppearance("MeshLightAPI", false));
  CHECK_FALSE(appliedSchemaChangesAppearance("LightAPI", true));  // a light's own
  CHECK(appliedSchemaChangesAppearance("LightAPI", false));       // a mesh light
  CHECK_FALSE(appliedSchemaChangesAppearance("MaterialBindingAPI", false));
  CHECK_FALSE(appliedSchemaChangesAppearance("SemanticsAPI:Semantics_a1", false));
  CHECK_FALSE(appliedSchemaChangesAppearance("PhysicsRigidBodyAPI", false));
  CHECK_FALSE(appliedSchemaChangesAppearance("CollectionAPI:lightLink", false));
}

TEST_CASE("the import notes unread prim types, schemas, material networks and composition", "[usd_losses]") {
  const UsdImportReport report = importText(R"(#usda 1.0
def Xform "W"
{
    def BasisCurves "C1" { }
    def BasisCurves "C2" { }
    def FooBar "F" { }
    def SphereLight "L" (prepend apiSchemas = ["ShapingAPI"]) { float inputs:intensity = 10 }
    def Cube "Box" (prepend apiSchemas = ["MaterialBindingAPI"]) {
        rel material:binding = </W/M>
        double weirdness = 3
    }
    def Material "M"
    {
        token outputs:ri:surface.connect = </W/M/S.outputs:out>
        def Shader "S" { uniform token info:id = "PxrDiffuse"
                         token outputs:out }
    }
}
)");
  const std::vector<DroppedWarning> w = report.losses.warnings();
  const DroppedWarning* curves = findDropped(w, "prim_type", "BasisCurves");
  REQUIRE(curves);
  CHECK(curves->info.count == 2);
  CHECK(curves->diagnostic.loc.file.str() == "/v/scene.usda");
  CHECK(curves->diagnostic.loc.line == 4);
  CHECK(findDropped(w, "prim_type", "FooBar"));
  CHECK(findDropped(w, "applied_schema", "ShapingAPI"));
  CHECK_FALSE(findDropped(w, "applied_schema", "MaterialBindingAPI"));
  CHECK(findDropped(w, "attribute", "weirdness"));
  bool network = false;
  for (const DroppedWarning& d : w) network = network || d.info.kind == "material_network";
  CHECK(network);
}

TEST_CASE("a stage the mapping reads whole drops nothing", "[usd_losses]") {
  const UsdImportReport report = importText(R"(#usda 1.0
def Xform "W"
{
    def Cube "Box" { double size = 2 }
    def DistantLight "Sun" { float inputs:intensity = 3 }
}
)");
  CHECK(report.losses.empty());
}

}  // namespace sdg
