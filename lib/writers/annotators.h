#pragma once
// Labels computed from one camera's frame passes: semantic and instance id
// maps, 2D tight and loose boxes with occlusion, 3D boxes, camera params.
// Inputs are plain frame results, so every annotator is testable without GL.
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "render/frame_passes.h"
#include "render/render_list.h"
#include "writers/semantics.h"

namespace sdg {

// One entity drawn alone (from the renderer): pixels covered and bounds.
struct EntityCoverage {
  uint64_t pixels = 0;
  int xMin = 0, yMin = 0, xMax = -1, yMax = -1;
};

struct Box2D {
  uint32_t semanticId = 0;
  int32_t xMin = 0, yMin = 0, xMax = 0, yMax = 0;  // inclusive pixel indices, origin top-left
  float occlusionRatio = 0.0f;
  size_t entity = 0;
};

struct Box3D {
  uint32_t semanticId = 0;
  float extentMin[3] = {0, 0, 0}, extentMax[3] = {0, 0, 0};  // the entity's local space
  float transform[16] = {};  // local-to-world, row-vector layout (translation in the last row)
  float occlusionRatio = 0.0f;
  size_t entity = 0;
};

struct FrameAnnotations {
  std::vector<uint32_t> semanticIds;  // per pixel
  std::vector<uint32_t> instanceIds;  // per pixel (entity instance ids; 0 background, 1 unlabelled)
  std::vector<uint64_t> visiblePixels;  // per entity
  std::vector<float> occlusion;         // per entity: hidden fraction of its unoccluded pixels
  std::vector<Box2D> tight, loose;
  std::vector<Box3D> boxes3d;
};

struct AnnotatorInputs {
  const FramePasses& frame;
  const RenderList& list;
  size_t camera;
  const FrameSemantics& semantics;
  const std::vector<EntityCoverage>& coverage;           // per entity; empty when not rendered
  const std::vector<Eigen::AlignedBox3f>& itemBounds;    // per render item, local space
};

void annotate(const AnnotatorInputs& in, FrameAnnotations& out);

// camera_params_X.json's content (spec §5.7), keys in Replicator's order.
nlohmann::ordered_json cameraParams(const RenderCamera& camera, int width, int height, double metersPerUnit);

}  // namespace sdg
