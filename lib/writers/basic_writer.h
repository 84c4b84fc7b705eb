#pragma once
// Replicator BasicWriter's folder layout and file formats (spec §5): file
// names <kind>_<frame>.<ext>, one render product at the root, several under
// <rp>/<annotator>/ (or <annotator>/<rp>_ with use_common_output_dir);
// PNG, numpy .npy (format 1.0, the structured dtypes of §5.4.1) and JSON as
// Python's json.dumps writes it; metadata.txt with the run seed. Each
// option that names an annotator of annotatorTable() turns it on.
#include <cstdint>
#include <string>
#include <vector>

#include "scene_io/scene.h"
#include "writers/writer.h"

namespace sdg {

class BasicWriter : public Writer {
 public:
  BasicWriter(const OptionSet& options, std::vector<std::string> productNames, int64_t seed);

  AnnotatorNeeds needs() const override;
  std::vector<OutputFile> runFiles() const override;
  void encode(const ProductFrame& frame, FrameFiles& out) const override;
  // Where this writer puts a frame's rgb image (COCO's file_name).
  std::string rgbPath(uint64_t frame, size_t product) const;

 private:
  OptionSet options_;
  BasicLayout layout_;
  std::vector<const AnnotatorInfo*> annotators_;  // turned on, in table order
  int64_t seed_;
};

}  // namespace sdg
