#pragma once
// One render product's frame on its way from the renderer to the writers: a
// plain copy of everything its files need, so annotating and encoding run on
// a pool thread while the next frame renders.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/coverage_masks.h"
#include "render/frame_passes.h"
#include "render/lidar_sweep.h"
#include "render/render_list.h"
#include "writers/annotators.h"
#include "writers/semantics.h"

namespace sdg {

// What every render product of one frame shares, read by the pool.
struct FrameScene {
  RenderList list;
  FrameSemantics semantics;
  std::vector<Eigen::AlignedBox3f> itemBounds;  // per render item, local space
  // Motion annotators: the render lists of the frames before and after
  // (null at an iteration's first and last frame, or when none asks). The
  // run holds a frame's products back until `next` is known.
  std::shared_ptr<const RenderList> previous, next;
  bool nextKnown = false;
  // capture.lidars' sweeps, in that order (when a writer asks for them).
  std::vector<LidarSweep> lidars;
};

struct ProductFrame {
  uint64_t frame = 0;
  uint64_t iteration = 0;
  uint64_t frameInIteration = 0;
  size_t product = 0;
  size_t cameraIndex = 0;  // into scene->list.cameras
  std::shared_ptr<const FrameScene> scene;
  FramePasses passes;
  bool hasMasks = false;  // masks were drawn (a writer needs coverage)
  CoverageMasks masks;
  std::vector<MaskCoverage> coverage;  // per entity, from the masks (the pool fills it)
  bool toSheet = false;   // a contact sheet frame: its tile is made too
  FrameAnnotations annotations;
  // Motion annotators: (row, column) pixels to the next and the previous
  // frame, 2 floats a pixel (writers/motion.h; the pool fills them).
  std::vector<float> forwardFlow, backwardFlow;
  RenderCamera camera;
  double metersPerUnit = 1.0;
  // Per entity: root prim path, labels; per render id: prim path.
  std::vector<std::string> entityPaths;
  std::vector<LabelSet> entityLabels;
  std::vector<LabelSet> semanticLabels;  // by semantic id
  std::vector<std::string> renderIdPaths;  // index = render instance id; [0] unused
};

}  // namespace sdg
