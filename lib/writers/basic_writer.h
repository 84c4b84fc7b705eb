#pragma once
// Replicator BasicWriter's folder layout and file formats (spec §5): file
// names <kind>_<frame>.<ext>, one render product at the root, several under
// <rp>/<annotator>/ (or <annotator>/<rp>_ with use_common_output_dir);
// PNG, numpy .npy (format 1.0, the structured dtypes of §5.4.1) and JSON as
// Python's json.dumps writes it; metadata.txt with the run seed.
#include <cstdint>
#include <string>
#include <vector>

#include "render/frame_passes.h"
#include "scene_io/scene.h"
#include "writers/annotators.h"

namespace sdg {

struct OutputFile {
  std::string path;  // relative to the output folder
  std::vector<uint8_t> bytes;
};

// Everything one render product's frame needs; a plain copy, so encoding can
// run on a worker thread while the next frame renders.
struct ProductFrame {
  uint64_t frame = 0;
  size_t product = 0;
  FramePasses passes;
  FrameAnnotations annotations;
  RenderCamera camera;
  double metersPerUnit = 1.0;
  // Per entity: root prim path, labels; per render id: prim path.
  std::vector<std::string> entityPaths;
  std::vector<LabelSet> entityLabels;
  std::vector<LabelSet> semanticLabels;  // by semantic id
  std::vector<std::string> renderIdPaths;  // index = render instance id; [0] unused
};

class BasicWriter {
 public:
  BasicWriter(const OptionSet& options, std::vector<std::string> productNames, int64_t seed);

  // Which annotators need which inputs.
  bool needsCoverage() const;  // entities drawn alone: loose boxes and occlusion
  bool needsAnnotations() const;
  // The buffers its annotators read (colour is always read).
  PassSelection passesNeeded() const;
  std::vector<OutputFile> metadataFiles() const;
  std::vector<OutputFile> encode(const ProductFrame& frame) const;
  // Where this writer puts a frame's rgb image (COCO's file_name).
  std::string rgbPath(uint64_t frame, size_t product) const;

 private:
  std::string prefix(size_t product, const std::string& annotator) const;
  std::string frameName(uint64_t frame) const;

  OptionSet options_;
  std::vector<std::string> products_;
  int64_t seed_;
};

}  // namespace sdg
