#pragma once
// The buffers one camera's frame produces, rows top to bottom. Buffers are
// reused from frame to frame (no per-frame allocation once sized).
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace sdg {

// Which buffers to read back besides colour. Read-back is most of a GPU
// frame's cost, so a run asks only for what its writer uses; buffers not
// read keep their previous contents.
struct PassSelection {
  bool normals = true;    // normals and distanceToCamera
  bool imagePlane = true; // distanceToImagePlane
  bool ids = true;        // instanceIds

  static constexpr PassSelection colourOnly() { return {false, false, false}; }
};

struct FramePasses {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;                  // 4 per pixel, sRGB, alpha 255
  std::vector<float> normals;                 // 4 per pixel: world normal xyz, w 0; zero where nothing was hit
  std::vector<float> distanceToCamera;        // metres; +inf where nothing was hit
  std::vector<float> distanceToImagePlane;    // metres along the optical axis; +inf where nothing was hit
  std::vector<uint32_t> instanceIds;          // RenderItem::instanceId; 0 = background
  std::vector<float> hdrColor;                // 3 per pixel: linear radiance, path-traced frames when asked

  // Sizes colour and the buffers `passes` fills for w x h; the others keep
  // what they hold (nothing, in a fresh frame), so a run that reads back
  // colour alone never allocates or touches the 7 bytes a pixel it skips.
  void resize(int w, int h, const PassSelection& passes);
  size_t pixelCount() const { return size_t(width) * size_t(height); }
};

}  // namespace sdg
