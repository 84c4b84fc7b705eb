// Every material input and every light input that the schema accepts
// changes both a rasterized and a path-traced frame when set away from its
// default: the test that finds an input accepted, documented and then
// ignored by a renderer (specular_level in the path tracer, a light's
// normalize, diffuse and specular in both). The inputs come from the prim
// type table, so a new one fails here until a case below makes it matter
// or the exception table says, with the reason, why a renderer may ignore it.
#include <catch2/catch.hpp>

#include <map>
#include <sstream>

#include "render/pathtrace/path_tracer.h"
#include "render_fixtures.h"
#include "run/scene_setup.h"
#include "stage/prim_types.h"

using namespace sdg;

namespace {

constexpr int kSize = 20;

const AssetResolver& assets() {
  static const AssetResolver a({SDG_SOURCE_DIR "/scenes", SDG_SOURCE_DIR "/tests/data"});
  return a;
}

struct Frames {
  std::vector<uint8_t> raster, traced;
};

Frames render(const std::string& yaml) {
  static RenderSettings settings = [] {
    RenderSettings s = defaultRenderSettings();
    s.width = s.height = kSize;
    return s;
  }();
  static Renderer rasterizer(test::sharedContext(), assets(), settings);
  static PathTracer tracer(assets(), PathTraceSettings{2, 2, 1});
  const Scene scene = buildScene(sceneDocumentFromText(yaml, "t.yaml"), builtinRegistry().catalog());
  const RenderList list = buildRenderList(scene.stage);
  Frames out;
  FramePasses passes;
  rasterizer.render(list, 0, passes, PassSelection::colourOnly());
  out.raster = passes.rgba;
  PathTracedFrame frame;
  tracer.render(list, 0, kSize, kSize, 7, frame);
  out.traced.resize(size_t(kSize) * kSize * 4);
  toneMap(frame, settings.exposureScale, out.traced.data());
  return out;
}

std::string sceneWith(const std::string& material, const std::string& lightType, const std::string& light,
                      const std::string& ballMaterial = "") {
  return "version: 1\nprims:\n  /Looks: {type: Scope}\n  /Looks/M: {type: Material" + material +
         "}\n  /Looks/Plain: {type: Material, inputs:diffuse_color_constant: [0.6, 0.6, 0.6], "
         "inputs:metallic_constant: 0.6, inputs:reflection_roughness_constant: 0.35}\n"
         "  /Floor: {type: Plane, width: 10, length: 10, material: /Looks/Plain}\n"
         "  /Ball: {type: Sphere, radius: 1, translate: [0, 0, 1], material: " +
         (ballMaterial.empty() ? std::string("/Looks/M") : ballMaterial) + "}\n  /Light: {type: " + lightType + light +
         "}\n  /Cam: {type: Camera, translate: [0, -6, 3], rotateXYZ: [70, 0, 0], clippingRange: [0.1, 100]}\n";
}

// Each material input: what else it needs to matter, and its own setting.
const std::map<std::string, std::pair<std::string, std::string>>& materialCases() {
  static const std::string base = "inputs:diffuse_texture: images/split.png";
  static const std::string roughness = "inputs:reflection_roughness_texture_influence: 1";
  static const std::string metallic = "inputs:metallic_texture_influence: 1";
  static const std::string orm = roughness + ", " + metallic;
  static const std::string split = "images/split.png";
  static const std::map<std::string, std::pair<std::string, std::string>> cases = {
      {"inputs:diffuse_color_constant", {"", "inputs:diffuse_color_constant: [0.8, 0.1, 0.1]"}},
      {"inputs:diffuse_texture", {"", base}},
      {"inputs:texture_scale", {base, "inputs:texture_scale: [3, 2]"}},
      {"inputs:texture_rotate", {base, "inputs:texture_rotate: 40"}},
      {"inputs:project_uvw", {base, "inputs:project_uvw: true"}},
      {"inputs:reflection_roughness_constant", {"", "inputs:reflection_roughness_constant: 0.1"}},
      {"inputs:metallic_constant", {"", "inputs:metallic_constant: 0.9"}},
      {"inputs:specular_level", {"", "inputs:specular_level: 0"}},
      {"inputs:reflectionroughness_texture", {roughness, "inputs:reflectionroughness_texture: " + split}},
      {"inputs:reflection_roughness_texture_influence", {"inputs:reflectionroughness_texture: " + split, roughness}},
      {"inputs:metallic_texture", {metallic, "inputs:metallic_texture: " + split}},
      {"inputs:metallic_texture_influence", {"inputs:metallic_texture: " + split, metallic}},
      {"inputs:enable_ORM_texture", {orm + ", inputs:ORM_texture: " + split, "inputs:enable_ORM_texture: true"}},
      {"inputs:ORM_texture", {orm + ", inputs:enable_ORM_texture: true", "inputs:ORM_texture: " + split}},
      {"inputs:normalmap_texture", {"", "inputs:normalmap_texture: " + split}},
      {"inputs:bump_factor", {"inputs:normalmap_texture: " + split, "inputs:bump_factor: 0.3"}},
      {"inputs:enable_opacity", {"inputs:opacity_constant: 0.3", "inputs:enable_opacity: true"}},
      {"inputs:enable_opacity_texture",
       {"inputs:enable_opacity: true, inputs:opacity_texture: " + split, "inputs:enable_opacity_texture: true"}},
      {"inputs:opacity_constant", {"inputs:enable_opacity: true", "inputs:opacity_constant: 0.3"}},
      {"inputs:opacity_texture",
       {"inputs:enable_opacity: true, inputs:enable_opacity_texture: true", "inputs:opacity_texture: " + split}},
      {"inputs:opacity_threshold",
       {"inputs:enable_opacity: true, inputs:opacity_constant: 0.7", "inputs:opacity_threshold: 0.9"}},
  };
  return cases;
}

// Where each light type stands, bright enough to see in both renderers
// (the rect is 2 wide, so that inputs:normalize has an area other than 1).
using Settings = std::map<std::string, std::string>;
const std::map<std::string, Settings>& lightPlacements() {
  static const std::map<std::string, Settings> placements = {
      {"SphereLight", {{"inputs:intensity", "40000"}, {"translate", "[2, -2, 4]"}}},
      {"RectLight", {{"inputs:intensity", "20000"}, {"inputs:width", "2"}, {"translate", "[0, 0, 4]"}}},
      {"DiskLight", {{"inputs:intensity", "25000"}, {"translate", "[0, 0, 4]"}}},
      {"CylinderLight", {{"inputs:intensity", "20000"}, {"translate", "[0, 0, 4]"}}},
      {"DistantLight", {{"inputs:intensity", "3000"}, {"rotateXYZ", "[30, 20, 0]"}}},
      {"DomeLight", {{"inputs:intensity", "400"}}},
  };
  return placements;
}

std::string yamlOf(const Settings& settings) {
  std::string out;
  for (const auto& [key, value] : settings) out += ", " + key + ": " + value;
  return out;
}

// A value away from the default, by type; empty: no rule for this type.
std::string awayFromDefault(const AttributeSpec& spec) {
  std::ostringstream v;
  switch (spec.type) {
    case ValueType::Bool: return spec.defaultValue.get<bool>() ? "false" : "true";
    case ValueType::Float: {
      const float d = spec.defaultValue.get<float>();
      v << (d == 0.0f ? 2.0f : d * 0.5f);
      return v.str();
    }
    case ValueType::Color3f: return "[1, 0.5, 0.2]";
    case ValueType::Asset: return "images/sky.png";
    default: return "";
  }
}

struct Exception {
  bool raster, traced;  // which renderer may leave the frame unchanged
  const char* why;
};

// Inputs a renderer may ignore, each with its reason (docs/rendering.md).
const std::map<std::string, Exception>& exceptions() {
  static const std::map<std::string, Exception> e = {
      {"DistantLight inputs:angle", {true, false, "the rasterizer's shadow maps are hard: it ignores the sun's size"}},
      {"SphereLight treatAsPoint", {true, false, "the rasterizer lights every sphere light as a point already"}},
      {"DistantLight inputs:normalize", {true, true, "a distant light's intensity is its irradiance at any angle"}},
      {"DomeLight inputs:normalize", {true, true, "a dome has no area to divide by"}},
      {"DomeLight inputs:texture:format", {true, true, "only lat-long maps are read"}},
      {"RectLight inputs:texture:file", {true, true, "a rect light's texture is read by neither renderer"}},
  };
  return e;
}

}  // namespace

TEST_CASE("every material input changes a rasterized and a path-traced frame", "[render][pathtrace][inputs]") {
  const std::string light = ", inputs:intensity: 40000, translate: [2, -2, 4]";
  auto material = [](const std::string& settings) { return settings.empty() ? settings : ", " + settings; };
  for (const AttributeSpec& spec : primTypeInfo(PrimType::Material).attributes) {
    INFO(spec.name);
    const auto found = materialCases().find(spec.name);
    REQUIRE(found != materialCases().end());  // a new input: give it a case
    const auto& [context, setting] = found->second;
    const Frames before = render(sceneWith(material(context), "SphereLight", light));
    const Frames after = render(sceneWith(material(context) + ", " + setting, "SphereLight", light));
    const bool rasterChanged = before.raster != after.raster, tracedChanged = before.traced != after.traced;
    CHECK(rasterChanged);
    CHECK(tracedChanged);
  }
}

TEST_CASE("every light input changes a rasterized and a path-traced frame", "[render][pathtrace][inputs]") {
  for (const auto& [type, placement] : lightPlacements()) {
    const PrimTypeInfo& info = primTypeInfo(*primTypeFromName(type));
    const Frames before = render(sceneWith("", type, yamlOf(placement), "/Looks/Plain"));
    for (const AttributeSpec& spec : info.attributes) {
      if (spec.name.rfind("inputs:", 0) != 0 && spec.name != "treatAsPoint") continue;
      const std::string key = type + " " + spec.name;
      INFO(key);
      const auto exception = exceptions().find(key);
      std::string value = awayFromDefault(spec);
      if (value.empty()) {
        REQUIRE(exception != exceptions().end());  // a new kind of input: give it a value or a reason
        continue;
      }
      Settings changed = placement;
      if (changed.count(spec.name)) value = changed[spec.name] == "2" ? "0.5" : "10000";  // away from the placement's
      changed[spec.name] = value;
      const Frames after = render(sceneWith("", type, yamlOf(changed), "/Looks/Plain"));
      const bool rasterMayIgnore = exception != exceptions().end() && exception->second.raster;
      const bool tracedMayIgnore = exception != exceptions().end() && exception->second.traced;
      const bool rasterChanged = before.raster != after.raster, tracedChanged = before.traced != after.traced;
      // An exception that no longer holds is taken out of the table.
      CHECK(rasterChanged != rasterMayIgnore);
      CHECK(tracedChanged != tracedMayIgnore);
    }
  }
}
