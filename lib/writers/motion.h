#pragma once
// Optical flow from the scene, not from the pixels: each pixel's surface
// point (its render item and its depth) is carried to another frame by that
// item's pose there, and projected with that frame's camera. The sky (no
// item) is a direction at infinity, moved by the camera's rotation only.
#include <vector>

#include "render/frame_passes.h"
#include "render/render_list.h"

namespace sdg {

// Per pixel of a frame drawn with `camera` from `list`: (row, column)
// displacement in pixels to where the point lands in the frame described by
// `other` (Kubric's layout, 2 floats a pixel, rows top to bottom). 0 where the
// point has no place there: its prim or the camera is gone from `other`, it
// is behind the other camera, or (orthographic cameras) it is the sky.
// `other` null: all 0 (no frame before the first or after the last).
void flowTo(const FramePasses& passes, const RenderList& list, const RenderCamera& camera, double metersPerUnit,
            const RenderList* other, std::vector<float>& out);

}  // namespace sdg
