#include "render/render_list.h"

#include <algorithm>
#include <cmath>

#include "core/text.h"
#include "stage/xform_edit.h"

namespace sdg {


const Prim* boundMaterial(const Stage& stage, const Prim& prim) {
  const Prim* closest = nullptr;
  const Prim* strongest = nullptr;
  for (const Prim* p = &prim; p && !p->isPseudoRoot(); p = p->parent()) {
    const auto& binding = p->material();
    if (!binding) continue;
    const Prim* m = stage.find(binding->path);
    if (!m || m->type() != PrimType::Material) continue;
    if (!closest) closest = m;
    if (p != &prim && binding->strength == "strongerThanDescendants") strongest = m;
  }
  return strongest ? strongest : closest;
}

namespace {

bool invisible(const Prim& prim) {
  for (const Prim* p = &prim; p && !p->isPseudoRoot(); p = p->parent()) {
    const Value* v = p->value("visibility");
    if (v && v->get<std::string>() == "invisible") return true;
  }
  return false;
}


// displayOpacity and per-vertex colours, which apply without a bound
// material only. An opacity is a cut-out at one half, as OmniPBR's
// fractional opacity is (neither renderer blends); a per-vertex one is
// interpolated across the face first. Meshes with neither keep
// OpacitySource::None and no vertex colours, exactly as before.
void displayPrimvarsOf(const Prim& prim, RenderMaterial& m) {
  const float opacity = prim.getFloat("primvars:displayOpacity");
  const bool inlineMesh = prim.type() == PrimType::Mesh && prim.findAttribute("points") && prim.getString("asset").empty();
  const bool perVertexColor = inlineMesh && prim.findAttribute("primvars:displayColor:faceVarying");
  const bool perVertexOpacity = inlineMesh && prim.findAttribute("primvars:displayOpacity:faceVarying");
  if (perVertexColor) m.baseColor = Vec3f(1.0f, 1.0f, 1.0f);
  m.vertexColors = perVertexColor || perVertexOpacity;
  if (perVertexOpacity || opacity < 1.0f) {
    m.opacity = OpacitySource::Constant;
    m.opacityConstant = perVertexOpacity ? 1.0f : opacity;  // the per-vertex one replaces the constant
    m.opacityCutoff = 0.5f;
  }
}

RenderMaterial materialOf(const Stage& stage, const Prim& prim) {
  RenderMaterial m;
  const Prim* material = boundMaterial(stage, prim);
  if (!material) {
    m.baseColor = prim.value("primvars:displayColor")->get<Vec3f>();
    displayPrimvarsOf(prim, m);
    return m;
  }
  m.fromPrim = true;
  m.baseColor = material->value("inputs:diffuse_color_constant")->get<Vec3f>();
  m.maps.baseColor = material->getString("inputs:diffuse_texture");
  m.maps.roughness = material->getString("inputs:reflectionroughness_texture");
  m.maps.metallic = material->getString("inputs:metallic_texture");
  if (material->getBool("inputs:enable_ORM_texture")) m.maps.orm = material->getString("inputs:ORM_texture");
  m.maps.normal = material->getString("inputs:normalmap_texture");
  m.textureScale = material->value("inputs:texture_scale")->get<Vec2f>();
  m.textureRotate = material->getFloat("inputs:texture_rotate");
  m.projectUvw = material->getBool("inputs:project_uvw");
  m.roughness = material->getFloat("inputs:reflection_roughness_constant");
  m.metallic = material->getFloat("inputs:metallic_constant");
  m.roughnessInfluence = std::min(material->getFloat("inputs:reflection_roughness_texture_influence"), 1.0f);
  m.metallicInfluence = std::min(material->getFloat("inputs:metallic_texture_influence"), 1.0f);
  m.normalScale = material->getFloat("inputs:bump_factor");
  m.specularLevel = std::min(material->getFloat("inputs:specular_level"), 1.0f);
  if (material->getBool("inputs:enable_opacity")) {
    m.opacityConstant = material->getFloat("inputs:opacity_constant");
    const bool mapped = material->getBool("inputs:enable_opacity_texture");
    if (mapped) m.maps.opacity = material->getString("inputs:opacity_texture");
    m.opacity = m.maps.opacity.empty() ? OpacitySource::Constant : OpacitySource::OpacityMap;
    // OmniPBR's threshold 0 means fractional opacity, which neither renderer
    // blends: it is cut at one half.
    const float threshold = material->getFloat("inputs:opacity_threshold");
    m.opacityCutoff = threshold > 0.0f ? threshold : 0.5f;
  }
  return m;
}

RenderLight lightOf(const Stage& stage, const Prim& prim) {
  RenderLight l;
  l.path = prim.path();
  const Matrix4d world = stage.worldMatrix(prim);
  l.position = world.block<3, 1>(0, 3);
  l.worldRotation = decompose(world).rotation;
  l.direction = (l.worldRotation * -Vec3d::UnitZ()).normalized();
  const float scale = prim.getFloat("inputs:intensity") * std::exp2(prim.getFloat("inputs:exposure"));
  l.radiance = prim.value("inputs:color")->get<Vec3f>() * scale;
  l.diffuse = prim.getFloat("inputs:diffuse");
  l.specular = prim.getFloat("inputs:specular");
  switch (prim.type()) {
    case PrimType::DistantLight:
      l.kind = LightKind::Distant;
      l.angle = prim.getFloat("inputs:angle");
      break;
    case PrimType::SphereLight:
      l.kind = LightKind::Sphere;
      l.radius = prim.getFloat("inputs:radius");  // treatAsPoint keeps the power of this radius
      l.treatAsPoint = prim.getBool("treatAsPoint");
      break;
    case PrimType::RectLight:
      l.kind = LightKind::Rect;
      l.width = prim.getFloat("inputs:width");
      l.height = prim.getFloat("inputs:height");
      break;
    case PrimType::DiskLight:
      l.kind = LightKind::Disk;
      l.radius = prim.getFloat("inputs:radius");
      break;
    case PrimType::CylinderLight:
      l.kind = LightKind::Cylinder;
      l.radius = prim.getFloat("inputs:radius");
      l.length = prim.getFloat("inputs:length");
      break;
    default:
      l.kind = LightKind::Dome;
      l.texture = prim.getString("inputs:texture:file");
      // USD's DomeLight_1 with poleAxis "scene": the map's pole follows the
      // stage's up axis, so on a Z-up stage the dome is first turned +90
      // degrees about X (its +Y to +Z), as Isaac Sim shows it.
      if (stage.metadata().upAxis == "Z")
        l.worldRotation = l.worldRotation * Eigen::AngleAxisd(M_PI / 2, Vec3d::UnitX()).toRotationMatrix();
      break;
  }
  // USD's inputs:normalize: the radiance over the emitting area, so the
  // power no longer follows the size. A distant light's intensity already
  // is its irradiance whatever its angle, and a dome has no area: neither
  // changes.
  if (prim.getBool("inputs:normalize")) {
    float area = 0.0f;
    switch (l.kind) {
      case LightKind::Rect: area = l.width * l.height; break;
      case LightKind::Disk: area = float(M_PI) * l.radius * l.radius; break;
      case LightKind::Sphere: area = 4.0f * float(M_PI) * l.radius * l.radius; break;
      case LightKind::Cylinder: area = 2.0f * float(M_PI) * l.radius * l.length; break;
      default: break;
    }
    if (area > 0.0f) l.radiance /= area;
  }
  return l;
}

// The camera's calibrated lens from its omni:lensdistortion:* attributes
// (validated by the scene loader: positive focal lengths and sizes).
LensModel lensOf(const Prim& prim) {
  LensModel lens;
  const std::string& token = prim.getString("omni:lensdistortion:model");
  lens.kind = lensModelFromToken(token).value_or(LensModelKind::Pinhole);
  if (!lens.calibrated()) return lens;
  const std::string p = "omni:lensdistortion:" + token + ":";
  auto number = [&](const std::string& name) { return double(prim.getFloat(p + name)); };
  if (lens.kind == LensModelKind::OpenCvPinhole || lens.kind == LensModelKind::OpenCvFisheye) {
    const Vec2i size = prim.value(p + "imageSize")->get<Vec2i>();
    lens.calibratedSize = Eigen::Vector2d(double(size.x()), double(size.y()));
    lens.fx = number("fx"), lens.fy = number("fy"), lens.cx = number("cx"), lens.cy = number("cy");
    const int radial = lens.kind == LensModelKind::OpenCvPinhole ? 6 : 4;
    for (int i = 0; i < radial; ++i) lens.k[i] = number("k" + std::to_string(i + 1));
    if (lens.kind == LensModelKind::OpenCvPinhole) {
      lens.p1 = number("p1"), lens.p2 = number("p2");
      for (int i = 0; i < 4; ++i) lens.s[i] = number("s" + std::to_string(i + 1));
    }
    lens.prepare();
    return lens;
  }
  lens.calibratedSize = Eigen::Vector2d(number("nominalWidth"), number("nominalHeight"));
  const Vec2f centre = prim.value(p + "opticalCenter")->get<Vec2f>();
  lens.cx = centre.x(), lens.cy = centre.y();
  lens.maxFovDegrees = number("maxFov");
  const int terms = lens.kind == LensModelKind::FTheta ? 5 : 4;
  for (int i = 0; i < terms; ++i) lens.k[i] = number("k" + std::to_string(i));
  lens.prepare();
  return lens;
}

RenderCamera cameraOf(const Stage& stage, const Prim& prim) {
  RenderCamera c;
  c.path = prim.path();
  Decomposed d = decompose(stage.worldMatrix(prim));
  c.worldFromCamera = compose(d.translation, d.rotation, Vec3d::Ones());
  c.focalLength = prim.getFloat("focalLength");
  c.horizontalAperture = prim.getFloat("horizontalAperture");
  c.verticalAperture = prim.getFloat("verticalAperture");
  c.horizontalApertureOffset = prim.getFloat("horizontalApertureOffset");
  c.verticalApertureOffset = prim.getFloat("verticalApertureOffset");
  Vec2f clip = prim.value("clippingRange")->get<Vec2f>();
  c.nearClip = clip.x();
  c.farClip = clip.y();
  c.orthographic = prim.getString("projection") == "orthographic";
  c.focusDistance = prim.getFloat("focusDistance");
  c.fStop = prim.getFloat("fStop");
  c.lens = lensOf(prim);
  return c;
}

}  // namespace

bool anyCalibratedLens(const RenderList& list) {
  for (const RenderCamera& c : list.cameras)
    if (c.lens.calibrated()) return true;
  return false;
}

RenderList buildRenderList(const Stage& stage) {
  RenderList list;
  list.metersPerUnit = stage.metadata().metersPerUnit;
  uint32_t nextId = 1;
  stage.traverse([&](const Prim& prim) {
    const PrimTypeInfo& info = prim.typeInfo();
    if (info.gprim) {
      uint32_t id = nextId++;  // ids follow stage order, hidden prims included, so they stay stable
      if (invisible(prim)) return;
      RenderItem item;
      item.primPath = prim.path();
      item.mesh = meshKeyOf(prim, stage.metadata().subdivisionLevel);
      item.meshId = item.mesh.id();
      item.worldFromLocal = stage.worldMatrix(prim);
      item.material = materialOf(stage, prim);
      item.instanceId = id;
      item.doubleSided = prim.getBool("doubleSided");
      list.items.push_back(std::move(item));
    } else if (info.light && !invisible(prim)) {
      list.lights.push_back(lightOf(stage, prim));
    } else if (prim.type() == PrimType::Camera) {
      list.cameras.push_back(cameraOf(stage, prim));
    }
  });
  return list;
}

}  // namespace sdg
