#include "writers/motion.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

#include "render/camera_math.h"

namespace sdg {

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
  const Matrix4d otherClipFromWorld = projectionMatrix(*otherCamera, w, h) * viewMatrix(*otherCamera);
  // Per render id, one matrix: this frame's view space to the other frame's
  // clip space, through the item's motion (unknown where the item is gone).
  std::unordered_map<std::string, size_t> otherByPath;
  for (size_t i = 0; i < other->items.size(); ++i) otherByPath.emplace(other->items[i].primPath, i);
  uint32_t maxId = 0;
  for (const RenderItem& item : list.items) maxId = std::max(maxId, item.instanceId);
  std::vector<Matrix4d> clipFromView(size_t(maxId) + 1, Matrix4d::Zero());
  std::vector<uint8_t> known(size_t(maxId) + 1, 0);
  for (const RenderItem& item : list.items) {
    auto it = otherByPath.find(item.primPath);
    if (it == otherByPath.end()) continue;
    clipFromView[item.instanceId] =
        otherClipFromWorld * other->items[it->second].worldFromLocal * item.worldFromLocal.inverse() * worldFromView;
    known[item.instanceId] = 1;
  }
  // The sky: directions (w = 0), turned by the cameras' rotations only.
  Matrix4d skyFromView = Matrix4d::Zero();
  skyFromView.block<3, 3>(0, 0) = worldFromView.block<3, 3>(0, 0);
  skyFromView = otherClipFromWorld * skyFromView;
  const bool skyMoves = !camera.orthographic && !otherCamera->orthographic;
  // Back to view space: x = (ndcX * clipW - p02 z - p03) / p00 at view depth z.
  const double p00 = p(0, 0), p02 = p(0, 2), p03 = p(0, 3), p11 = p(1, 1), p12 = p(1, 2), p13 = p(1, 3);
  const double p32 = p(3, 2), p33 = p(3, 3);

  for (int y = 0; y < h; ++y) {
    const double row = y + 0.5, ndcY = 1.0 - row / h * 2.0;
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      const double col = x + 0.5, ndcX = col / w * 2.0 - 1.0;
      const uint32_t id = passes.instanceIds[i];
      Eigen::Vector4d clip;
      if (id != 0 && id < known.size() && known[id]) {
        const double depth = double(passes.distanceToImagePlane[i]);
        if (!std::isfinite(depth)) continue;
        const double z = -depth / metersPerUnit, clipW = p32 * z + p33;
        clip = clipFromView[id] * Eigen::Vector4d((ndcX * clipW - p02 * z - p03) / p00,
                                                  (ndcY * clipW - p12 * z - p13) / p11, z, 1.0);
      } else if (id == 0 && skyMoves) {
        // The ray's direction (view z = -1), as a point at infinity.
        const double clipW = p33 - p32;
        clip = skyFromView * Eigen::Vector4d((ndcX * clipW + p02 - p03) / p00, (ndcY * clipW + p12 - p13) / p11, -1.0, 0.0);
      } else {
        continue;
      }
      if (clip.w() <= 1e-12) continue;  // behind the other camera
      out[i * 2] = float((1.0 - clip.y() / clip.w()) * 0.5 * h - row);
      out[i * 2 + 1] = float((clip.x() / clip.w() + 1.0) * 0.5 * w - col);
    }
  }
}

}  // namespace sdg
