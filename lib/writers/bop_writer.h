#pragma once
// `writer.type: BopWriter`: the BOP-scenewise layout the BOP toolkit reads
// (docs/writers.md#bop). Each iteration is one BOP scene,
// <split>/<iteration:06d>/, with per image rgb/, depth/ (16-bit, in units of
// depth_scale mm), mask/ and mask_visib/ per annotated object instance;
// scene_camera.json, scene_gt.json and scene_gt_info.json are assembled from
// per-frame fragments when the dataset is finished (so shards, --resume and
// merge give the same bytes); camera.json and models/ are written once.
// Objects are the entities whose label (the run's first semantic taxonomy)
// is listed in `objects`; obj_id is its position there plus one.
#include <cstdint>
#include <string>
#include <vector>

#include "writers/bop_models.h"
#include "writers/writer.h"
#include "writers/writer_registry.h"

namespace sdg {

class BopWriter : public Writer {
 public:
  // SceneError (located at the option) for an empty `objects` list or a
  // symmetry it cannot read.
  BopWriter(const WriterConfig& config, const WriterSetup& setup, const std::string& taxonomy,
            const std::vector<std::string>& semanticTypes);

  AnnotatorNeeds needs() const override;
  std::vector<OutputFile> runFiles() const override;
  void encode(const ProductFrame& frame, FrameFiles& out) const override;
  const std::string& split() const { return split_; }

 private:
  std::string split_;
  double depthScale_ = 1.0;  // millimetres per depth unit
  std::string taxonomy_;
  std::vector<BopObject> objects_;
  size_t products_ = 1;
  int width_ = 0, height_ = 0;
  RenderCamera firstCamera_;  // camera.json: the first product's camera as loaded
};

// im_id of a product's frame within its scene: frames of the iteration in
// order, the render products of a frame one after another.
uint64_t bopImageId(uint64_t frameInIteration, size_t product, size_t products);

// Writes <split>/<scene>/scene_camera.json, scene_gt.json and
// scene_gt_info.json of every scene from the frames' fragments (RunError
// naming a missing or corrupt one). Returns the files written.
uint64_t assembleBopScenes(const std::string& dir, const std::string& split, uint64_t iterations,
                           uint64_t framesPerIteration, size_t products);

}  // namespace sdg
