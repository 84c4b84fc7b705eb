#include "writers/motion.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

#include "render/camera_math.h"

namespace sdg {
namespace {

// Where a view-space point (GL axes) lands in pixels, (column, row); false
// behind the camera.
bool toPixel(const Matrix4d& projection, const Eigen::Vector4d& view, int width, int height, double& col, double& row) {
  const Eigen::Vector4d clip = projection * view;
  if (clip.w() <= 1e-12) return false;
  col = (clip.x() / clip.w() + 1.0) * 0.5 * width;
  row = (1.0 - clip.y() / clip.w()) * 0.5 * height;
  return true;
}

}  // namespace

void flowTo(const FramePasses& passes, const RenderList& list, const RenderCamera& camera, double metersPerUnit,
            const RenderList* other, std::vector<float>& out) {
  const int w = passes.width, h = passes.height;
  out.assign(size_t(w) * size_t(h) * 2, 0.0f);
  if (!other) return;
  const RenderCamera* otherCamera = nullptr;
  for (const RenderCamera& c : other->cameras)
    if (c.path == camera.path) otherCamera = &c;
  if (!otherCamera) return;

  const Matrix4d p = projectionMatrix(camera, w, h);
  const Matrix4d worldFromView = camera.worldFromCamera;
  const Matrix4d otherProjection = projectionMatrix(*otherCamera, w, h);
  const Matrix4d otherView = viewMatrix(*otherCamera);
  // Per render id: the other frame's view from this frame's world, through
  // the item's motion (empty where the item is gone).
  std::unordered_map<std::string, size_t> otherByPath;
  for (size_t i = 0; i < other->items.size(); ++i) otherByPath.emplace(other->items[i].primPath, i);
  uint32_t maxId = 0;
  for (const RenderItem& item : list.items) maxId = std::max(maxId, item.instanceId);
  std::vector<Matrix4d> motion(size_t(maxId) + 1, Matrix4d::Zero());
  std::vector<uint8_t> known(size_t(maxId) + 1, 0);
  for (const RenderItem& item : list.items) {
    auto it = otherByPath.find(item.primPath);
    if (it == otherByPath.end()) continue;
    motion[item.instanceId] = otherView * other->items[it->second].worldFromLocal * item.worldFromLocal.inverse();
    known[item.instanceId] = 1;
  }
  // The sky: directions, turned by the cameras' rotations only.
  Matrix4d skyMotion = Matrix4d::Zero();
  skyMotion.block<3, 3>(0, 0) = otherView.block<3, 3>(0, 0) * worldFromView.block<3, 3>(0, 0);
  const bool skyMoves = !camera.orthographic && !otherCamera->orthographic;

  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      const double col = x + 0.5, row = y + 0.5;
      const double ndcX = col / w * 2.0 - 1.0, ndcY = 1.0 - row / h * 2.0;
      const uint32_t id = passes.instanceIds[i];
      const double depth = double(passes.distanceToImagePlane[i]);
      double toCol = 0, toRow = 0;
      bool placed = false;
      if (id != 0 && id < known.size() && known[id] && std::isfinite(depth)) {
        // Back to view space from the pixel and its depth along the axis.
        const double z = -depth / metersPerUnit;
        const double clipW = p(3, 2) * z + p(3, 3);
        Eigen::Vector4d view((ndcX * clipW - p(0, 2) * z - p(0, 3)) / p(0, 0),
                             (ndcY * clipW - p(1, 2) * z - p(1, 3)) / p(1, 1), z, 1.0);
        placed = toPixel(otherProjection, motion[id] * worldFromView * view, w, h, toCol, toRow);
      } else if (id == 0 && skyMoves) {
        // The ray's direction (view z = -1), as a point at infinity (w = 0).
        const double clipW = -p(3, 2) + p(3, 3);
        Eigen::Vector4d direction((ndcX * clipW + p(0, 2) - p(0, 3)) / p(0, 0),
                                  (ndcY * clipW + p(1, 2) - p(1, 3)) / p(1, 1), -1.0, 0.0);
        placed = toPixel(otherProjection, skyMotion * direction, w, h, toCol, toRow);
      }
      if (!placed) continue;
      out[i * 2] = float(toRow - row);
      out[i * 2 + 1] = float(toCol - col);
    }
}

}  // namespace sdg
