#pragma once
// How the rasterizer draws a camera with a calibrated lens (lens_model.h):
// ordinary pinhole views from the camera's eye that together hold every
// ray of the lens's image, each drawn at the frame's resolution, then each
// pixel of the lens's image takes the nearest pixel of the view its ray
// falls in. Nearest for every pass (colour too): ids, labels and depths are
// never blended.
//
// The views: one frustum around the optical axis when every ray is within
// 60 degrees of it, else the faces of a cube around the eye (only those some
// ray falls in), so fields of view past 180 degrees work. Each is split into
// T x T tiles (pinholes with aperture offsets), T chosen so that the tiles
// are at least as dense as the lens's image at its centre (at most 4).
#include <cstdint>
#include <vector>

#include "render/frame_passes.h"
#include "render/render_list.h"

namespace sdg {

struct LensViewPlan {
  int width = 0, height = 0;
  LensModel lens;  // the plan's lens, to know when a camera needs a new plan
  // The views in the camera's frame: each is the camera with this pose
  // (camera <- view) and its own pinhole projection.
  std::vector<Matrix4d> cameraFromView;
  std::vector<RenderCamera> viewTemplates;  // worldFromCamera unset
  // Per pixel of the lens's image, rows top to bottom: the view (-1: the
  // lens images nothing there), the pixel in it, and the factor turning the
  // view's distance to its image plane into the lens camera's (the ray's
  // cosine to the camera's axis over its cosine to the view's).
  std::vector<int32_t> view;
  std::vector<uint32_t> sourcePixel;
  std::vector<float> planeScale;
};

// The plan for `camera`'s lens at width x height (the camera's pose is
// not used; RenderCamera::lens must be calibrated).
LensViewPlan planLensViews(const RenderCamera& camera, int width, int height);
// Whether `plan` was made for this camera's lens and clipping at this size.
bool lensPlanFits(const LensViewPlan& plan, const RenderCamera& camera, int width, int height);
// View i of the plan for the camera at its current pose.
RenderCamera lensView(const LensViewPlan& plan, const RenderCamera& camera, size_t i);
// The lens's image from the views' passes (views[i] drawn with lensView(i),
// each width x height); `out` is resized for `passes`.
void resampleLensViews(const LensViewPlan& plan, const std::vector<FramePasses>& views, const PassSelection& passes,
                       FramePasses& out);

}  // namespace sdg
