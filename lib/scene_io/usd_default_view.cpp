// Default framing camera and lights for a USD stage that has none
// (usd_default_view.h).
#include "scene_io/usd_default_view.h"

#include <algorithm>
#include <cmath>

#include "assets/mesh_source.h"
#include "stage/look_at.h"

namespace sdg {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Extends `box` by the prim's geometry in world space.
void extendByPrim(const Stage& stage, const Prim& prim, Eigen::AlignedBox3d& box) {
  if (!primTypeInfo(prim.type()).gprim) return;
  if (const Attribute* vis = prim.findAttribute("visibility"); vis && vis->value.get<std::string>() == "invisible") return;
  const MeshKey key = meshKeyOf(prim, stage.metadata().subdivisionLevel);
  const Matrix4d world = stage.worldMatrix(prim);
  if (key.inlineMesh) {
    // Every point, transformed: exact, and cheaper than triangulating.
    const FloatArray& points = key.inlineMesh->points.get<FloatArray>();
    for (size_t i = 0; i + 2 < points.size(); i += 3)
      box.extend((world * Vec3d(points[i], points[i + 1], points[i + 2]).homogeneous()).head<3>());
    return;
  }
  if (key.shape == PrimType::Mesh) return;  // a mesh file, or a Mesh with no geometry
  const MeshData shape = meshDataFor(key, AssetResolver(), prim.path());
  if (shape.bounds.isEmpty()) return;
  for (int c = 0; c < 8; ++c) {
    const Vec3d corner = shape.bounds.corner(static_cast<Eigen::AlignedBox3f::CornerType>(c)).cast<double>();
    box.extend((world * corner.homogeneous()).head<3>());
  }
}

// A root prim name not yet on the stage: `base`, else base_1, base_2, ...
std::string freeRootPath(const Stage& stage, const std::string& base) {
  std::string path = "/" + base;
  for (int n = 1; stage.find(path); ++n) path = "/" + base + "_" + std::to_string(n);
  return path;
}

// A transform op placing a prim at `eye` with its -Z toward `target`, Z up.
XformOp lookAtOp(const Vec3d& eye, const Vec3d& target) {
  Matrix4d m = Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = *lookAtRotation(eye, target, Vec3d::UnitZ());
  m.topRightCorner<3, 1>() = eye;
  XformOp op;
  op.kind = XformOpKind::Transform;
  op.value = Value::makeMatrix4d(m);
  return op;
}

}  // namespace

BoundingSphere stageBoundingSphere(const Stage& stage) {
  Eigen::AlignedBox3d box;
  stage.traverse([&](const Prim& p) { extendByPrim(stage, p, box); });
  BoundingSphere sphere;
  if (box.isEmpty()) return sphere;
  sphere.centre = box.center();
  sphere.radius = 0.5 * box.diagonal().norm();
  return sphere;
}

std::vector<std::string> addDefaultCameraAndLights(Scene& scene) {
  bool hasCamera = false, hasLight = false;
  scene.stage.traverse([&](const Prim& p) {
    hasCamera = hasCamera || p.type() == PrimType::Camera;
    hasLight = hasLight || primTypeInfo(p.type()).light;
  });
  std::vector<std::string> added;
  const BoundingSphere sphere = stageBoundingSphere(scene.stage);
  const Vec3d centre = sphere.centre;
  const double radius = sphere.radius > 0 ? sphere.radius : 1.0;  // nothing to frame: a unit sphere at the origin
  if (!hasCamera) {
    // The sphere fits the narrower of the two fields of view: USD's
    // horizontal aperture sets the horizontal one, the image's aspect the
    // vertical one.
    const Vec2i resolution = scene.render.get("resolution").get<Vec2i>();
    const double aspect = double(resolution.x()) / double(resolution.y());
    const double halfH = kDefaultCameraFovDegrees * kPi / 360.0;
    const double halfV = std::atan(std::tan(halfH) / aspect);
    const double distance = radius / std::sin(std::min(halfH, halfV));
    const Vec3d eye = centre + distance * Vec3d(1.0, -2.0, 1.0).normalized();
    const std::string path = freeRootPath(scene.stage, "DefaultCamera");
    Prim& camera = scene.stage.definePrim(path, PrimType::Camera);
    const float horizontalAperture = 20.955f;  // USD's default; the focal length gives the field of view
    camera.setAttribute("horizontalAperture", Value::makeFloat(horizontalAperture));
    camera.setAttribute("verticalAperture", Value::makeFloat(float(horizontalAperture / aspect)));
    camera.setAttribute("focalLength", Value::makeFloat(float(horizontalAperture / (2.0 * std::tan(halfH)))));
    camera.setAttribute("clippingRange",
                        Value::makeFloat2(float(std::max(1e-4, 0.5 * (distance - radius))), float(2.0 * (distance + radius))));
    camera.xformOps() = {lookAtOp(eye, centre)};
    added.push_back(path);
  }
  if (!hasLight) {
    // A sun from the upper front left (-Z of the light toward the centre)
    // and a dim sky, as tests/data/usd/cube_camera.usda lights its cube.
    const std::string sunPath = freeRootPath(scene.stage, "DefaultLight");
    Prim& sun = scene.stage.definePrim(sunPath, PrimType::DistantLight);
    sun.setAttribute("inputs:intensity", Value::makeFloat(3000.0f));
    sun.xformOps() = {lookAtOp(Vec3d(-1.0, -1.5, 2.5), Vec3d::Zero())};
    const std::string domePath = freeRootPath(scene.stage, "DefaultDome");
    Prim& dome = scene.stage.definePrim(domePath, PrimType::DomeLight);
    dome.setAttribute("inputs:intensity", Value::makeFloat(300.0f));
    added.push_back(sunPath);
    added.push_back(domePath);
  }
  return added;
}

}  // namespace sdg
