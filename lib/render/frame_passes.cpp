#include "render/frame_passes.h"

namespace sdg {

void FramePasses::resize(int w, int h, const PassSelection& passes) {
  width = w;
  height = h;
  const size_t n = size_t(w) * size_t(h);
  rgba.resize(n * 4);
  if (passes.normals) {
    normals.resize(n * 4);
    distanceToCamera.resize(n);
  }
  if (passes.imagePlane) distanceToImagePlane.resize(n);
  if (passes.ids) instanceIds.resize(n);
}

}  // namespace sdg
