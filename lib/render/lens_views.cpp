#include "render/lens_views.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "render/camera_math.h"

namespace sdg {
namespace {

using Eigen::Vector2d;

// Rays within this angle of the axis fit one frustum; wider lenses use
// the cube (a frustum of 120 degrees already spends most pixels at its rim).
constexpr double kOneFrustumDegrees = 60.0;
constexpr int kMaxTiles = 4;
// The frustum's margin past the outermost ray, so that the nearest pixel
// of a ray at the rim is inside the view.
constexpr double kMargin = 1.02;

// The cube's faces as rotations camera <- face: the face looks down its -z.
std::array<Matrix3d, 6> cubeFaces() {
  auto face = [](const Vec3d& forward, const Vec3d& up) {
    Matrix3d r;
    r.col(2) = -forward;
    r.col(1) = up;
    r.col(0) = up.cross(-forward);
    return r;
  };
  return {face(-Vec3d::UnitZ(), Vec3d::UnitY()), face(Vec3d::UnitX(), Vec3d::UnitY()),
          face(-Vec3d::UnitX(), Vec3d::UnitY()), face(Vec3d::UnitY(), Vec3d::UnitZ()),
          face(-Vec3d::UnitY(), -Vec3d::UnitZ()), face(Vec3d::UnitZ(), Vec3d::UnitY())};
}

bool sameLens(const LensModel& a, const LensModel& b) {
  return a.kind == b.kind && a.calibratedSize == b.calibratedSize && a.fx == b.fx && a.fy == b.fy && a.cx == b.cx &&
         a.cy == b.cy && a.k == b.k && a.p1 == b.p1 && a.p2 == b.p2 && a.s == b.s && a.maxFovDegrees == b.maxFovDegrees;
}

}  // namespace

LensViewPlan planLensViews(const RenderCamera& camera, int width, int height) {
  LensViewPlan plan;
  plan.width = width, plan.height = height;
  plan.lens = camera.lens;
  const LensModel& lens = camera.lens;
  const size_t pixels = size_t(width) * size_t(height);

  // Every pixel's ray, and the widest angle among them.
  std::vector<std::optional<Vec3d>> rays(pixels);
  double widest = 0.0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::optional<Vec3d>& ray = rays[size_t(y) * size_t(width) + size_t(x)];
      ray = lensUnproject(lens, Vector2d(x, y), width, height);
      if (ray) widest = std::max(widest, std::acos(std::clamp(-ray->z(), -1.0, 1.0)));
    }

  // The faces and each one's extent in tangent units (x, y at unit depth),
  // widened to the frame's aspect so that its pixels are square.
  std::vector<Matrix3d> faces;
  Vector2d extent(1.0, 1.0);
  if (widest * 180.0 / std::numbers::pi < kOneFrustumDegrees) {
    faces.push_back(Matrix3d::Identity());
    extent.setZero();
    for (const auto& ray : rays)
      if (ray) extent = extent.cwiseMax(Vector2d(std::fabs(ray->x() / ray->z()), std::fabs(ray->y() / ray->z())));
    extent = (extent * kMargin).cwiseMax(Vector2d(1e-3, 1e-3));
  } else {
    for (const Matrix3d& f : cubeFaces()) faces.push_back(f);
    extent *= kMargin;
  }
  const double aspect = double(width) / double(height);
  extent = Vector2d(std::max(extent.x(), extent.y() * aspect), std::max(extent.y(), extent.x() / aspect));

  // Tiles: as dense as the lens's image one pixel off its centre.
  int tiles = 1;
  if (const std::optional<Vector2d> centre = lensProject(lens, Vec3d(0, 0, -1), width, height)) {
    const std::optional<Vec3d> a = lensUnproject(lens, *centre, width, height);
    const std::optional<Vec3d> b = lensUnproject(lens, *centre + Vector2d(1, 0), width, height);
    if (a && b) {
      const double pitch = std::fabs(b->x() / -b->z() - a->x() / -a->z());  // tangent units per pixel
      if (pitch > 0) tiles = std::clamp(int(std::ceil(2.0 * extent.x() / (width * pitch) - 1e-9)), 1, kMaxTiles);
    }
  }
  const Vector2d tileSize = 2.0 * extent / tiles;

  // Each pixel's view: its face (the one it is most head-on to), its tile,
  // the nearest pixel there.
  plan.view.assign(pixels, -1);
  plan.sourcePixel.assign(pixels, 0);
  plan.planeScale.assign(pixels, 0.0f);
  std::vector<int32_t> compact(faces.size() * size_t(tiles * tiles), -1);
  std::vector<Matrix4d> clipFromView;  // by view
  for (size_t i = 0; i < pixels; ++i) {
    if (!rays[i]) continue;
    const Vec3d& d = *rays[i];
    size_t f = 0;
    for (size_t k = 1; k < faces.size(); ++k)
      if (-faces[k].col(2).dot(d) > -faces[f].col(2).dot(d)) f = k;
    const Vec3d local = faces[f].transpose() * d;
    if (!(local.z() < 0)) continue;
    const Vector2d t(local.x() / -local.z(), local.y() / -local.z());
    const int tx = std::clamp(int(std::floor((t.x() + extent.x()) / tileSize.x())), 0, tiles - 1);
    const int ty = std::clamp(int(std::floor((extent.y() - t.y()) / tileSize.y())), 0, tiles - 1);
    const Vector2d tileCentre(-extent.x() + (tx + 0.5) * tileSize.x(), extent.y() - (ty + 0.5) * tileSize.y());
    int32_t& slot = compact[f * size_t(tiles * tiles) + size_t(ty * tiles + tx)];
    if (slot < 0) {
      slot = int32_t(plan.viewTemplates.size());
      Matrix4d cameraFromView = Matrix4d::Identity();
      cameraFromView.block<3, 3>(0, 0) = faces[f];
      plan.cameraFromView.push_back(cameraFromView);
      RenderCamera v = camera;
      v.lens = LensModel{};
      v.orthographic = false;
      v.focalLength = 1.0f;
      v.horizontalAperture = float(tileSize.x());
      v.verticalAperture = float(tileSize.y());
      // camera_math.h's offsets move the image, so the tile's centre takes
      // the opposite sign to land in the middle of the view.
      v.horizontalApertureOffset = float(-tileCentre.x());
      v.verticalApertureOffset = float(-tileCentre.y());
      plan.viewTemplates.push_back(v);
      clipFromView.push_back(projectionMatrix(v, width, height));
    }
    // Within the tile: through the projection the rasterizer draws the view
    // with (its float apertures), so the pixel is the one drawn.
    const Eigen::Vector4d clip = clipFromView[size_t(slot)] * local.homogeneous();
    const Vector2d ndc = clip.head<2>() / clip.w();
    const int px = std::clamp(int(std::floor((ndc.x() + 1.0) * 0.5 * width)), 0, width - 1);
    const int py = std::clamp(int(std::floor((1.0 - ndc.y()) * 0.5 * height)), 0, height - 1);
    plan.view[i] = slot;
    plan.sourcePixel[i] = uint32_t(py) * uint32_t(width) + uint32_t(px);
    plan.planeScale[i] = float(-d.z() / -local.z());
  }
  return plan;
}

bool lensPlanFits(const LensViewPlan& plan, const RenderCamera& camera, int width, int height) {
  if (plan.width != width || plan.height != height || !sameLens(plan.lens, camera.lens)) return false;
  return plan.viewTemplates.empty() || (plan.viewTemplates[0].nearClip == camera.nearClip &&
                                        plan.viewTemplates[0].farClip == camera.farClip);
}

RenderCamera lensView(const LensViewPlan& plan, const RenderCamera& camera, size_t i) {
  RenderCamera v = plan.viewTemplates[i];
  v.path = camera.path;
  v.worldFromCamera = camera.worldFromCamera * plan.cameraFromView[i];
  return v;
}

void resampleLensViews(const LensViewPlan& plan, const std::vector<FramePasses>& views, const PassSelection& passes,
                       FramePasses& out) {
  out.resize(plan.width, plan.height, passes);
  constexpr float inf = std::numeric_limits<float>::infinity();
  const size_t pixels = size_t(plan.width) * size_t(plan.height);
  for (size_t i = 0; i < pixels; ++i) {
    const int32_t v = plan.view[i];
    if (v < 0) {  // no ray: black, nothing hit
      std::fill_n(&out.rgba[4 * i], 3, uint8_t(0));
      out.rgba[4 * i + 3] = 255;
      if (passes.normals) {
        std::fill_n(&out.normals[4 * i], 4, 0.0f);
        out.distanceToCamera[i] = inf;
      }
      if (passes.imagePlane) out.distanceToImagePlane[i] = inf;
      if (passes.ids) out.instanceIds[i] = 0;
      continue;
    }
    const FramePasses& from = views[size_t(v)];
    const size_t s = plan.sourcePixel[i];
    std::copy_n(&from.rgba[4 * s], 4, &out.rgba[4 * i]);
    if (passes.normals) {
      std::copy_n(&from.normals[4 * s], 4, &out.normals[4 * i]);
      out.distanceToCamera[i] = from.distanceToCamera[s];
    }
    if (passes.imagePlane) {
      const float z = from.distanceToImagePlane[s];
      out.distanceToImagePlane[i] = std::isfinite(z) ? z * plan.planeScale[i] : z;
    }
    if (passes.ids) out.instanceIds[i] = from.instanceIds[s];
  }
}

}  // namespace sdg
