// `export-usd`: scenes exported as a usda layer, read back with lib/usd's
// reader and composed, give the stage's prims, types, world transforms,
// mesh geometry, materials, semantics and behaviors; the text is
// deterministic.
#include <catch2/catch.hpp>

#include <map>

#include "run/scene_setup.h"
#include "assets/mesh_source.h"
#include "scene_io/usd_export.h"
#include "stage/behavior_spec.h"
#include "usd/compose.h"
#include "usd/layer_io.h"
#include "usd/usda_writer.h"

using namespace sdg;

namespace {

struct Exported {
  LoadedScene loaded;
  std::string text;
  usd::ComposedStage composed;
};

Exported exportScene(const std::string& scene) {
  Exported e{loadSceneForRun(SceneRequest{.scenePath = std::string(SDG_SOURCE_DIR) + "/" + scene}), {}, {}};
  UsdExportOptions options;
  options.isaacScriptsRoot = "/opt/isaac/behaviors";
  options.catalog = &e.loaded.registry.catalog();
  usd::Layer layer = exportUsdLayer(e.loaded.scene, e.loaded.assets, options);
  layer.identifier = "stage.usda";
  e.text = usd::writeUsdaLayer(layer);
  const std::string text = e.text;
  e.composed = usd::composeStage("stage.usda", [text](const std::string& id) { return usd::readUsdaLayer(text, id); });
  return e;
}

Vec3d vec3(const usd::Value& v) { return Vec3d(v.numbers.at(0), v.numbers.at(1), v.numbers.at(2)); }

// The local matrix USD computes from xformOpOrder, independently of the
// exporter: each op's matrix, USD's row-vector matrices transposed.
Matrix4d localFromUsd(const usd::ComposedPrim& prim) {
  Matrix4d m = Matrix4d::Identity();
  const usd::ComposedProperty* order = prim.property("xformOpOrder");
  if (!order) return m;
  for (const std::string& name : order->value.strings) {
    const usd::ComposedProperty* p = prim.property(name);
    REQUIRE(p);
    std::optional<XformOp> op = parseXformOpName(name);
    REQUIRE(op);
    const usd::Value& v = p->value;
    switch (op->kind) {
      case XformOpKind::RotateX:
      case XformOpKind::RotateY:
      case XformOpKind::RotateZ: op->value = Value::makeDouble(v.asDouble()); break;
      case XformOpKind::Orient:
        op->value = Value::makeQuatd(Quatd(v.numbers[0], v.numbers[1], v.numbers[2], v.numbers[3]));
        break;
      case XformOpKind::Transform: {
        Matrix4d t;
        for (int r = 0; r < 4; ++r)
          for (int c = 0; c < 4; ++c) t(c, r) = v.numbers[size_t(r * 4 + c)];
        op->value = Value::makeMatrix4d(t);
        break;
      }
      default: op->value = Value::makeDouble3(vec3(v)); break;
    }
    m = m * op->matrix();
  }
  return m;
}

std::string parentPath(const std::string& path) {
  size_t slash = path.rfind('/');
  return slash == 0 ? "/" : path.substr(0, slash);
}

}  // namespace

TEST_CASE("export-usd: every_type.yaml composes to the stage's prims, transforms and values", "[scene_io][usd_export]") {
  Exported e = exportScene("scenes/every_type.yaml");
  const Stage& stage = e.loaded.scene.stage;
  CHECK(e.composed.units.upAxis == "Z");
  CHECK(e.composed.units.metersPerUnit == 1.0);
  CHECK(e.composed.defaultPrim == "World");

  // Every stage prim, with its type; world matrices equal the stage's.
  std::map<std::string, Matrix4d> world{{"/", Matrix4d::Identity()}};
  size_t checked = 0;
  for (const usd::ComposedPrim& prim : e.composed.prims) {
    if (prim.path.starts_with("/Prototypes")) {
      CHECK(prim.abstract);
      continue;
    }
    world[prim.path] = world.at(parentPath(prim.path)) * localFromUsd(prim);
    const Prim* original = stage.find(prim.path);
    if (!original) {  // the shaders below a Material
      CHECK(prim.typeName == "Shader");
      continue;
    }
    INFO(prim.path);
    CHECK(prim.typeName == original->typeInfo().name);
    CHECK(prim.defined);
    Matrix4d expected = stage.worldMatrix(*original);
    CHECK((world[prim.path] - expected).cwiseAbs().maxCoeff() < 1e-9);
    ++checked;
  }
  CHECK(checked == stage.primCount());

  // The mesh file: one prototype, referenced, with the file's triangles.
  const usd::ComposedPrim* prop = e.composed.prim("/World/Shapes/Prop");
  REQUIRE(prop);
  const usd::ComposedProperty* points = prop->property("points");
  REQUIRE(points);
  MeshData mesh = meshDataFor(meshKeyOf(*stage.find("/World/Shapes/Prop"), stage.metadata().subdivisionLevel), e.loaded.assets, "/World/Shapes/Prop");
  CHECK(points->value.elementCount() == mesh.positions.size());
  CHECK(prop->property("faceVertexIndices")->value.elementCount() == mesh.indices.size());
  CHECK(prop->property("normals")->value.elementCount() == mesh.positions.size());
  CHECK(prop->metadata.at("documentation").asString() == "A mesh prop with one custom attribute of each type.");
  CHECK(prop->kind == "component");

  // Custom attributes keep their USD types and values.
  CHECK(prop->property("user:grid")->typeName == "int2");
  CHECK(prop->property("user:tint")->typeName == "color3f");
  CHECK(prop->property("user:spinD")->typeName == "quatd");
  CHECK(prop->property("user:spinD")->value.numbers == std::vector<double>{0, 1, 0, 0});
  CHECK(prop->property("user:tags")->value.strings == std::vector<std::string>{"warehouse", "cardboard"});
  CHECK(prop->property("user:id")->value.kind == usd::Kind::UInt);

  // Materials: OmniPBR (MDL) and a UsdPreviewSurface, both wired.
  const usd::ComposedPrim* painted = e.composed.prim("/World/Looks/Painted");
  REQUIRE(painted);
  CHECK(painted->property("outputs:mdl:surface")->connections ==
        std::vector<std::string>{"/World/Looks/Painted/OmniPBR.outputs:out"});
  CHECK(painted->property("outputs:surface")->connections ==
        std::vector<std::string>{"/World/Looks/Painted/PreviewSurface.outputs:surface"});
  const usd::ComposedPrim* omni = e.composed.prim("/World/Looks/Painted/OmniPBR");
  REQUIRE(omni);
  CHECK(omni->property("info:mdl:sourceAsset")->value.asString() == "OmniPBR.mdl");
  CHECK(omni->property("info:mdl:sourceAsset:subIdentifier")->value.asString() == "OmniPBR");
  CHECK(omni->property("inputs:reflection_roughness_constant")->value.asDouble() == Approx(0.4));
  const usd::ComposedPrim* preview = e.composed.prim("/World/Looks/Painted/PreviewSurface");
  REQUIRE(preview);
  CHECK(preview->property("info:id")->value.asString() == "UsdPreviewSurface");
  CHECK(preview->property("inputs:diffuseColor")->value.numbers[0] == Approx(0.8));
  const usd::ComposedPrim* texture = e.composed.prim("/World/Looks/Textured/DiffuseTexture");
  REQUIRE(texture);
  CHECK(texture->property("info:id")->value.asString() == "UsdUVTexture");
  CHECK(texture->property("inputs:file")->value.asString().ends_with("/scenes/textures/checker.png"));

  // Binding with its strength; semantics in both of Isaac's forms.
  const usd::ComposedPrim* box = e.composed.prim("/World/Shapes/Box");
  REQUIRE(box);
  const usd::ComposedProperty* binding = box->property("material:binding");
  REQUIRE(binding);
  CHECK(binding->targets == std::vector<std::string>{"/World/Looks/Painted"});
  CHECK(binding->metadata.at("bindMaterialAs").asString() == "strongerThanDescendants");
  CHECK(box->property("semantics:labels:class")->value.strings == std::vector<std::string>{"box", "container"});
  std::map<std::string, std::vector<std::string>> isaacLabels;
  for (const usd::ComposedProperty& p : box->properties)
    if (p.name.starts_with("semantic:") && p.name.ends_with(":params:semanticType"))
      isaacLabels[p.value.asString()].push_back(
          box->property(p.name.substr(0, p.name.size() - 13) + ":semanticData")->value.asString());
  CHECK(isaacLabels == std::map<std::string, std::vector<std::string>>{{"class", {"box", "container"}}, {"color", {"red"}}});
}

TEST_CASE("export-usd: behaviors as Isaac attaches them, settings in customLayerData", "[scene_io][usd_export]") {
  Exported e = exportScene("scenes/warehouse.yaml");
  const Stage& stage = e.loaded.scene.stage;
  size_t withBehaviors = 0;
  stage.traverse([&](const Prim& prim) {
    if (prim.behaviors().empty()) return;
    ++withBehaviors;
    INFO(prim.path());
    const usd::ComposedPrim* composed = e.composed.prim(prim.path());
    REQUIRE(composed);
    const usd::ComposedProperty* scripts = composed->property("omni:scripting:scripts");
    REQUIRE(scripts);
    CHECK(scripts->typeName == "asset[]");
    REQUIRE(scripts->value.strings.size() == prim.behaviors().size());
    for (size_t i = 0; i < prim.behaviors().size(); ++i) {
      const std::string& script = scripts->value.strings[i];
      CHECK(script.starts_with("/opt/isaac/behaviors/"));
      CHECK(script.ends_with(".py"));
    }
    // Every exposed variable, typed as the behavior declares it.
    for (const auto& [name, attribute] : prim.attributes()) {
      if (!name.starts_with("exposedVar:")) continue;
      const usd::ComposedProperty* p = composed->property(name);
      REQUIRE(p);
      CHECK(p->custom);
      CHECK(p->typeName == valueTypeName(attribute.value.type()));
      if (attribute.value.type() == ValueType::UInt) CHECK(p->value.asDouble() == attribute.value.get<uint32_t>());
      if (attribute.value.type() == ValueType::Float) CHECK(p->value.asDouble() == attribute.value.get<float>());
      if (attribute.value.type() == ValueType::Bool) CHECK(p->value.asBool() == attribute.value.get<bool>());
    }
  });
  CHECK(withBehaviors > 0);
  const usd::Value& data = e.composed.layerMetadata.at("customLayerData");
  REQUIRE(data.dictionary);
  const usd::Dictionary& sdg = *data.dictionary->at("sdgbehave").dictionary;
  CHECK(sdg.at("capture").dictionary->at("frames").asDouble() == e.loaded.scene.capture.getUInt("frames"));
  CHECK(sdg.at("events").dictionary->size() == e.loaded.scene.events.size());
  CHECK(sdg.at("writers").dictionary->size() == e.loaded.scene.writers.size());
}

TEST_CASE("export-usd: the same scene gives the same bytes", "[scene_io][usd_export]") {
  for (const char* scene : {"scenes/every_type.yaml", "scenes/warehouse.yaml"}) {
    INFO(scene);
    CHECK(exportScene(scene).text == exportScene(scene).text);
  }
}
