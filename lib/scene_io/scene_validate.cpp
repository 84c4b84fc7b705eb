#include "scene_io/scene_validate.h"

#include <cmath>

#include "assets/inline_mesh.h"
#include "core/text.h"
#include "stage/lidar_pattern.h"

namespace sdg {
namespace {

SourceLoc attributeLoc(const Prim& prim, std::string_view name) {
  const Attribute* a = prim.findAttribute(name);
  return a && a->loc.known() ? a->loc : prim.loc();
}

void validateCamera(const Prim& prim, Diagnostics& diag) {
  for (const char* aperture : {"horizontalAperture", "verticalAperture", "focalLength"})
    if (prim.getFloat(aperture) <= 0.0f)
      diag.error(attributeLoc(prim, aperture),
                 prim.path() + "." + aperture + ": must be greater than 0, found " + text::formatFloat(prim.getFloat(aperture)));
  const Vec2f range = prim.value("clippingRange")->get<Vec2f>();
  if (!(range.x() > 0.0f && range.x() < range.y()))
    diag.error(attributeLoc(prim, "clippingRange"),
               prim.path() + ".clippingRange: expected 0 < near < far, found near " + text::formatFloat(range.x()) +
                   " and far " + text::formatFloat(range.y()));
}

void validateLidar(const Prim& prim, Diagnostics& diag) {
  for (const LidarProblem& p : lidarProblems(prim))
    diag.error(attributeLoc(prim, p.attribute), prim.path() + "." + p.attribute + ": " + p.message);
}

// capture.<key>: each path names an existing prim of `type`.
void validateCapturedPrims(const Scene& scene, const char* key, PrimType type, Diagnostics& diag) {
  const auto& paths = scene.capture.get(key).get<std::vector<std::string>>();
  const SourceLoc* at = scene.capture.locOf(key);
  const std::string typeName(primTypeInfo(type).name);
  for (const std::string& path : paths) {
    const Prim* prim = scene.stage.find(path);
    SourceLoc loc = at ? *at : SourceLoc{scene.sourcePath, 0, 0};
    if (!prim)
      diag.error(loc, std::string("capture.") + key + ": " + text::quote(path) + " does not exist");
    else if (prim->type() != type)
      diag.error(loc, std::string("capture.") + key + ": " + path + " is a " + std::string(prim->typeInfo().name) +
                          ", not a " + typeName);
  }
}

// A calibrated lens: only the selected model's parameters are used, and
// each must be a finite number; focal lengths, sizes and the field of view
// positive, and the f-theta / K-B polynomials increasing at the centre.
void validateLens(const Prim& prim, Diagnostics& diag) {
  const std::string& model = prim.getString("omni:lensdistortion:model");
  if (model.empty()) return;
  const std::string p = "omni:lensdistortion:" + model + ":";
  auto fail = [&](const std::string& name, const std::string& expected, const std::string& found) {
    diag.error(attributeLoc(prim, p + name), prim.path() + "." + p + name + ": expected " + expected + ", found " + found);
  };
  for (const AttributeSpec& spec : prim.typeInfo().attributes) {
    if (!spec.name.starts_with(p) || spec.type != ValueType::Float) continue;
    const float v = prim.getFloat(spec.name);
    if (!std::isfinite(v)) fail(spec.name.substr(p.size()), "a finite number", text::formatFloat(v));
  }
  auto positive = [&](const std::string& name, const std::string& what) {
    const float v = prim.getFloat(p + name);
    if (std::isfinite(v) && !(v > 0.0f)) fail(name, what + " greater than 0", text::formatFloat(v));
  };
  if (model == "opencvPinhole" || model == "opencvFisheye") {
    positive("fx", "a focal length");
    positive("fy", "a focal length");
    const Vec2i size = prim.value(p + "imageSize")->get<Vec2i>();
    if (size.minCoeff() <= 0)
      fail("imageSize", "a width and height greater than 0",
           std::to_string(size.x()) + " x " + std::to_string(size.y()));
  } else {
    positive("nominalWidth", "a width");
    positive("nominalHeight", "a height");
    positive("maxFov", "a field of view (degrees)");
    // The centre's slope: angle per pixel (ftheta k1), pixels per radian (K-B k0).
    positive(model == "ftheta" ? "k1" : "k0", model == "ftheta" ? "radians per pixel" : "pixels per radian");
  }
  if (prim.getString("projection") == "orthographic")
    diag.error(attributeLoc(prim, "omni:lensdistortion:model"),
               prim.path() + ".omni:lensdistortion:model: a calibrated lens needs projection = perspective, found orthographic");
}

void validatePrim(const Stage& stage, const Prim& prim, const BehaviorCatalog& catalog, Diagnostics& diag) {
  if (prim.type() == PrimType::Camera) {
    validateCamera(prim, diag);
    validateLens(prim, diag);
  }
  if (prim.type() == PrimType::Lidar) validateLidar(prim, diag);
  if (prim.type() == PrimType::Mesh && prim.getString("asset").empty()) {
    if (auto mesh = inlineMeshOf(prim, stage.metadata().subdivisionLevel)) {
      std::string attribute;
      if (std::string problem = inlineMeshProblem(*mesh, &attribute); !problem.empty())
        diag.error(attributeLoc(prim, attribute), prim.path() + ": " + problem);
    } else {
      diag.error(prim.loc(), prim.path() + ": a Mesh needs `asset:` (the path of its mesh file) or inline `points:`");
    }
  }
  if (const auto& binding = prim.material()) {
    const Prim* target = stage.find(binding->path);
    if (!target)
      diag.error(prim.loc(), prim.path() + ".material: " + binding->path + " does not exist");
    else if (target->type() != PrimType::Material)
      diag.error(prim.loc(), prim.path() + ".material: " + binding->path + " is a " +
                                 std::string(target->typeInfo().name) + ", not a Material");
  }
  // Exposed variables that name prims must name existing ones.
  for (const std::string& behavior : prim.behaviors()) {
    const BehaviorSpec* spec = catalog.find(behavior);
    if (!spec) continue;
    for (const AttributeSpec& var : spec->variables) {
      if (!var.primPath) continue;
      std::string name = exposedAttributeName(spec->name, var.name);
      const std::string& target = prim.value(name)->get<std::string>();
      if (!target.empty() && !stage.find(target))
        diag.error(attributeLoc(prim, name), prim.path() + "." + name + ": prim " + text::quote(target) +
                                                 " does not exist");
    }
    if (spec->validate) spec->validate(prim, diag);
  }
}

}  // namespace

void validateScene(const Scene& scene, const BehaviorCatalog& catalog, Diagnostics& diag) {
  scene.stage.traverse([&](const Prim& prim) { validatePrim(scene.stage, prim, catalog, diag); });

  const Vec2i resolution = scene.render.get("resolution").get<Vec2i>();
  if (resolution.maxCoeff() > kMaxResolution) {
    const SourceLoc* loc = scene.render.locOf("resolution");
    diag.error(loc ? *loc : SourceLoc{scene.sourcePath, 0, 0},
               "render.resolution: each side is limited to " + std::to_string(kMaxResolution) + " pixels, found " +
                   std::to_string(resolution.x()) + " x " + std::to_string(resolution.y()));
  }
  validateCapturedPrims(scene, "cameras", PrimType::Camera, diag);
  validateCapturedPrims(scene, "lidars", PrimType::Lidar, diag);
}

}  // namespace sdg
