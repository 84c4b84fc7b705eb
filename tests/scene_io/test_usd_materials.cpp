// importUsdMaterial: UsdPreviewSurface networks, Isaac's OmniPBR and the
// fallback for anything else, on small composed layers.
#include <catch2/catch.hpp>

#include <filesystem>

#include "scene_io/usd_import.h"
#include "scene_io/usd_materials.h"
#include "scene_io/usd_fixtures.h"

using namespace sdg;
using sdg::test::composeText;

namespace {

struct Imported {
  Stage stage;
  Diagnostics diag;
  UsdImportReport report;
  Prim* material = nullptr;
};

void importMaterial(const usd::ComposedStage& composed, const std::string& path, Imported& out) {
  const usd::ComposedPrim* prim = composed.prim(path);
  REQUIRE(prim);
  out.material = &out.stage.definePrim("/M", PrimType::Material);
  importUsdMaterial(composed, *prim, *out.material, out.diag, out.report);
}

Vec3f color(const Prim& p, const char* name) { return p.value(name)->get<Vec3f>(); }
std::string asset(const Prim& p, const char* name) { return p.value(name)->get<std::string>(); }

const char* kConstants = R"(#usda 1.0
def Material "Mat"
{
    token outputs:surface.connect = </Mat/Surface.outputs:surface>
    def Shader "Surface"
    {
        uniform token info:id = "UsdPreviewSurface"
        color3f inputs:diffuseColor = (0.1, 0.2, 0.3)
        float inputs:roughness = 0.25
        float inputs:metallic = 0.75
        float inputs:opacity = 0.4
        float inputs:opacityThreshold = 0.5
        token outputs:surface
    }
}
)";

const char* kTextured = R"(#usda 1.0
def Material "Tex"
{
    token outputs:surface.connect = </Tex/Surface.outputs:surface>
    string inputs:stName = "st"
    def Shader "Surface"
    {
        uniform token info:id = "UsdPreviewSurface"
        color3f inputs:diffuseColor.connect = </Tex/Diffuse.outputs:rgb>
        float inputs:roughness.connect = </Tex/Orm.outputs:g>
        float inputs:metallic.connect = </Tex/Orm.outputs:b>
        normal3f inputs:normal.connect = </Tex/Normal.outputs:rgb>
        float inputs:opacity.connect = </Tex/Alpha.outputs:r>
        token outputs:surface
    }
    def Shader "Reader"
    {
        uniform token info:id = "UsdPrimvarReader_float2"
        string inputs:varname.connect = </Tex.inputs:stName>
        float2 outputs:result
    }
    def Shader "Transform"
    {
        uniform token info:id = "UsdTransform2d"
        float2 inputs:in.connect = </Tex/Reader.outputs:result>
        float2 inputs:scale = (2, 3)
        float inputs:rotation = 45
        float2 outputs:result
    }
    def Shader "Diffuse"
    {
        uniform token info:id = "UsdUVTexture"
        asset inputs:file = @textures/albedo.png@
        float2 inputs:st.connect = </Tex/Transform.outputs:result>
        token inputs:sourceColorSpace = "sRGB"
        float3 outputs:rgb
    }
    def Shader "Orm"
    {
        uniform token info:id = "UsdUVTexture"
        asset inputs:file = @orm.png@
        float2 inputs:st.connect = </Tex/Transform.outputs:result>
        float outputs:g
        float outputs:b
    }
    def Shader "Normal"
    {
        uniform token info:id = "UsdUVTexture"
        asset inputs:file = @normal.png@
        float4 inputs:scale = (2, 2, 2, 1)
        float4 inputs:bias = (-1, -1, -1, 0)
        float3 outputs:rgb
    }
    def Shader "Alpha"
    {
        uniform token info:id = "UsdUVTexture"
        asset inputs:file = @alpha.png@
        float outputs:r
    }
}
)";

}  // namespace

TEST_CASE("usd materials: UsdPreviewSurface constants", "[scene_io][usd]") {
  Imported m;
  importMaterial(composeText(kConstants), "/Mat", m);
  CHECK_FALSE(m.diag.hasErrors());
  CHECK(color(*m.material, "inputs:diffuse_color_constant") == Vec3f(0.1f, 0.2f, 0.3f));
  CHECK(m.material->getFloat("inputs:reflection_roughness_constant") == 0.25f);
  CHECK(m.material->getFloat("inputs:metallic_constant") == 0.75f);
  CHECK(m.material->getFloat("inputs:opacity_constant") == 0.4f);
  CHECK(m.material->getFloat("inputs:opacity_threshold") == 0.5f);
  CHECK(m.material->getBool("inputs:enable_opacity"));
  CHECK(m.report.warnings.empty());
  // Each value is located at its opinion in the layer.
  CHECK(m.material->findAttribute("inputs:metallic_constant")->loc.str() == "/v/scene.usda:10:9");
}

TEST_CASE("usd materials: textured UsdPreviewSurface with UsdTransform2d and an ORM map", "[scene_io][usd]") {
  Imported m;
  importMaterial(composeText(kTextured), "/Tex", m);
  CHECK_FALSE(m.diag.hasErrors());
  const Prim& p = *m.material;
  CHECK(asset(p, "inputs:diffuse_texture") == "/v/textures/albedo.png");
  CHECK(asset(p, "inputs:ORM_texture") == "/v/orm.png");
  CHECK(p.getBool("inputs:enable_ORM_texture"));
  CHECK(asset(p, "inputs:normalmap_texture") == "/v/normal.png");
  CHECK(asset(p, "inputs:opacity_texture") == "/v/alpha.png");
  CHECK(p.getBool("inputs:enable_opacity_texture"));
  CHECK(p.getBool("inputs:enable_opacity"));
  CHECK(p.value("inputs:texture_scale")->get<Vec2f>() == Vec2f(2, 3));
  CHECK(p.getFloat("inputs:texture_rotate") == 45.0f);
  CHECK(m.report.warnings.empty());
}

TEST_CASE("usd materials: single-channel maps and what the stage cannot hold", "[scene_io][usd]") {
  const char* text = R"(#usda 1.0
def Material "Ch"
{
    token outputs:surface.connect = </Ch/S.outputs:surface>
    def Shader "S"
    {
        uniform token info:id = "UsdPreviewSurface"
        float inputs:roughness.connect = </Ch/Rough.outputs:r>
        float inputs:metallic.connect = </Ch/Metal.outputs:a>
        color3f inputs:emissiveColor = (1, 0, 0)
        int inputs:useSpecularWorkflow = 0
    }
    def Shader "Rough"
    {
        uniform token info:id = "UsdUVTexture"
        asset inputs:file = @rough.png@
        token inputs:wrapS = "clamp"
        float2 inputs:st.connect = </Ch/T.outputs:result>
    }
    def Shader "T"
    {
        uniform token info:id = "UsdTransform2d"
        float2 inputs:translation = (0.5, 0)
    }
    def Shader "Metal"
    {
        uniform token info:id = "UsdUVTexture"
        asset inputs:file = @metal.png@
    }
}
)";
  Imported m;
  importMaterial(composeText(text), "/Ch", m);
  CHECK_FALSE(m.diag.hasErrors());
  CHECK(asset(*m.material, "inputs:reflectionroughness_texture") == "/v/rough.png");
  CHECK(m.material->getFloat("inputs:reflection_roughness_texture_influence") == 1.0f);
  CHECK(m.material->findAttribute("inputs:metallic_texture") == nullptr);
  REQUIRE(m.report.warnings.size() == 1);
  const std::string& w = m.report.warnings[0];
  CHECK_THAT(w, Catch::Contains("material /Ch"));
  CHECK_THAT(w, Catch::Contains("inputs:metallic from channel a"));
  CHECK_THAT(w, Catch::Contains("inputs:emissiveColor"));
  CHECK_THAT(w, Catch::Contains("wrapS = clamp"));
  CHECK_THAT(w, Catch::Contains("translation"));
  CHECK_THAT(w, !Catch::Contains("useSpecularWorkflow"));  // authored at its default
}

TEST_CASE("usd materials: Isaac's OmniPBR by its inputs, preferred over UsdPreviewSurface", "[scene_io][usd]") {
  const char* text = R"(#usda 1.0
def Material "Omni"
{
    token outputs:mdl:surface.connect = </Omni/Shader.outputs:out>
    token outputs:surface.connect = </Omni/Preview.outputs:surface>
    color3f inputs:tint = (0.8, 0.1, 0.1)
    def Shader "Shader"
    {
        uniform token info:implementationSource = "sourceAsset"
        uniform asset info:mdl:sourceAsset = @OmniPBR.mdl@
        uniform token info:mdl:sourceAsset:subIdentifier = "OmniPBR"
        color3f inputs:diffuse_color_constant.connect = </Omni.inputs:tint>
        float inputs:reflection_roughness_constant = 0.3
        asset inputs:diffuse_texture = @wood.png@
        float2 inputs:texture_scale = (4, 4)
        bool inputs:enable_ORM_texture = 1
        color3f inputs:emissive_color = (1, 1, 1)
        token outputs:out
    }
    def Shader "Preview"
    {
        uniform token info:id = "UsdPreviewSurface"
        color3f inputs:diffuseColor = (0, 1, 0)
    }
}
)";
  Imported m;
  importMaterial(composeText(text), "/Omni", m);
  CHECK_FALSE(m.diag.hasErrors());
  CHECK(color(*m.material, "inputs:diffuse_color_constant") == Vec3f(0.8f, 0.1f, 0.1f));
  CHECK(m.material->getFloat("inputs:reflection_roughness_constant") == 0.3f);
  CHECK(asset(*m.material, "inputs:diffuse_texture") == "/v/wood.png");
  CHECK(m.material->value("inputs:texture_scale")->get<Vec2f>() == Vec2f(4, 4));
  CHECK(m.material->getBool("inputs:enable_ORM_texture"));
  REQUIRE(m.report.warnings.size() == 1);
  CHECK_THAT(m.report.warnings[0], Catch::Contains("inputs:emissive_color"));
}

TEST_CASE("usd materials: a bad OmniPBR value is located at its opinion", "[scene_io][usd]") {
  const char* text = R"(#usda 1.0
def Material "Omni"
{
    token outputs:mdl:surface.connect = </Omni/Shader.outputs:out>
    def Shader "Shader"
    {
        uniform asset info:mdl:sourceAsset = @OmniPBR.mdl@
        float inputs:reflection_roughness_constant = -1
        string inputs:texture_scale = "big"
    }
}
)";
  Imported m;
  importMaterial(composeText(text), "/Omni", m);
  REQUIRE(m.diag.errorCount() == 2);
  CHECK(m.diag.all()[0].loc.str() == "/v/scene.usda:8:9");
  CHECK_THAT(m.diag.all()[0].message, Catch::Contains("must be at least 0"));
  CHECK(m.diag.all()[1].loc.str() == "/v/scene.usda:9:9");
  CHECK_THAT(m.diag.all()[1].message, Catch::Contains("inputs:texture_scale"));
}

TEST_CASE("usd materials: MaterialX falls back to grey with exactly one warning", "[scene_io][usd]") {
  const char* text = R"(#usda 1.0
def Material "Plastic"
{
    token outputs:mtlx:surface.connect = </Plastic/SR.outputs:out>
    def Shader "SR"
    {
        uniform token info:id = "ND_UsdPreviewSurface_surfaceshader"
        token outputs:out
    }
}
)";
  usd::ComposedStage composed = composeText(text);
  Imported m;
  importMaterial(composed, "/Plastic", m);
  CHECK_FALSE(m.diag.hasErrors());
  CHECK_FALSE(usdMaterialIsSupported(composed, *composed.prim("/Plastic")));
  REQUIRE(m.report.warnings.size() == 1);
  CHECK_THAT(m.report.warnings[0], Catch::Contains("material /Plastic"));
  CHECK_THAT(m.report.warnings[0], Catch::Contains("MaterialX"));
  CHECK(color(*m.material, "inputs:diffuse_color_constant") == Vec3f(0.5f, 0.5f, 0.5f));
}

TEST_CASE("usd materials: the MaterialX sample's material lives in a .mtlx layer", "[scene_io][usd][samples]") {
  const std::string file = std::string(SDG_SOURCE_DIR) + "/../shared/usd-samples/test_assets/MaterialXTest/basic.usda";
  REQUIRE(std::filesystem::exists(file));  // run only through run_samples.sh, which skips when absent
  // lib/usd reads no .mtlx (USD reads them through a MaterialX file-format
  // plugin), so the material is not on the composed stage: the sphere keeps
  // its displayColor, with one warning naming the material.
  usd::ComposedStage composed = usd::composeStage(file, usd::textLayerFileReader());
  CHECK(composed.prim("/MaterialX/Materials/USD_Plastic") == nullptr);
  Stage stage;
  Prim& sphere = stage.definePrim("/sphere", PrimType::Sphere);
  Diagnostics diag;
  UsdImportReport report;
  importUsdPrimLabels(composed, *composed.prim("/sphere"), sphere, [](const std::string& p) { return p; },
                      sdg::test::builtinCatalog(), {}, report, diag);
  CHECK_FALSE(diag.hasErrors());
  CHECK_FALSE(sphere.material());
  REQUIRE(report.warnings.size() == 1);
  CHECK_THAT(report.warnings[0], Catch::Contains("/MaterialX/Materials/USD_Plastic"));
}
