#pragma once
// The one table of annotators: each with the name that turns it on (a
// BasicWriter option), what it reads from the renderer, and the function
// that encodes its files. Writers and the run's pass list are derived from
// it: a writer's needs are the union of its annotators', and the renderer
// reads back only those passes.
//
// Adding an annotator: a row in annotatorTable() (annotator_table.cpp), its
// encode function, its option in scene_io/settings_specs.cpp (BasicWriter),
// a line in docs/writers.md and a check in tests/python/check_dataset.py.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "render/frame_passes.h"
#include "scene_io/scene.h"
#include "writers/output_files.h"
#include "writers/product_frame.h"

namespace sdg {

// What an annotator (or a writer) reads from a frame besides colour.
struct AnnotatorNeeds {
  bool normals = false;     // world normals and distance to camera
  bool imagePlane = false;  // distance to the image plane
  bool ids = false;         // render instance ids
  bool labels = false;      // semantic entities: id maps, boxes (annotate())
  bool coverage = false;    // each entity drawn alone: loose boxes, occlusion, full silhouettes
  bool radiance = false;    // linear radiance (render.mode pathtraced)
  bool motion = false;      // poses of the frames before and after
  bool lidar = false;       // the frame's LiDAR sweeps (capture.lidars)

  AnnotatorNeeds& operator|=(const AnnotatorNeeds& o);
  PassSelection passes() const;
};

// BasicWriter's file names: <kind>_<frame>.<ext>, under <camera>/<annotator>/
// (or <annotator>/<camera>_) when there are several render products.
class BasicLayout {
 public:
  BasicLayout(std::vector<std::string> products, uint32_t framePadding, bool commonOutputDir);
  std::string path(size_t product, uint64_t frame, const std::string& annotator, const std::string& kind,
                   const char* ext) const;
  // <kind>_<frame>.<ext> at the folder's root, whatever the products.
  std::string rootPath(uint64_t frame, const std::string& kind, const char* ext) const;

 private:
  std::string prefix(size_t product, const std::string& annotator) const;
  std::vector<std::string> products_;
  uint32_t framePadding_;
  bool commonOutputDir_;
};

// Where an annotator writes one product's frame, and with which options.
struct AnnotatorOutput {
  const ProductFrame& frame;
  const OptionSet& options;  // the BasicWriter's (colorize_*, ...)
  const BasicLayout& layout;
  std::vector<OutputFile>& files;

  void add(const std::string& annotator, const std::string& kind, const char* ext, std::vector<uint8_t> bytes) const;
};

struct AnnotatorInfo {
  std::string_view name;  // the BasicWriter option that turns it on
  AnnotatorNeeds needs;
  void (*encode)(const AnnotatorOutput& out);
};

// In the order a frame's files are written (and listed in the manifest).
std::span<const AnnotatorInfo> annotatorTable();
const AnnotatorInfo* findAnnotator(std::string_view name);

}  // namespace sdg
