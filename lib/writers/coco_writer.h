#pragma once
// One COCO "instances" JSON for the run: images, categories from the
// semantic labels, and per visible entity an annotation with its tight box,
// an uncompressed RLE mask (column-major, as pycocotools reads), its area and
// iscrowd 0. Each (frame, render product) first becomes a small fragment
// file with category names instead of ids; assembling the fragments in
// frame order numbers images, annotations and categories. A whole run, a
// resumed one and merged shards therefore write the same bytes.
#include <cstdint>
#include <string>
#include <vector>

#include "writers/annotators.h"
#include "writers/basic_writer.h"

namespace sdg {

// Writes each frame's fragment (a hidden part); the dataset's finish joins
// them. Its images are a BasicWriter's rgb files.
class CocoWriter : public Writer {
 public:
  CocoWriter(const BasicWriter& images, std::string taxonomy) : images_(images), taxonomy_(std::move(taxonomy)) {}
  AnnotatorNeeds needs() const override { return AnnotatorNeeds{.labels = true}; }
  void encode(const ProductFrame& frame, FrameFiles& out) const override;

 private:
  const BasicWriter& images_;
  std::string taxonomy_;
};

// The fragment of one image (JSON text).
std::string cocoFragment(const std::string& imageFile, int width, int height, const FrameAnnotations& annotations,
                         const FrameSemantics& semantics, const std::string& taxonomy);

// Joins fragments (in order) into the final file at `path` (atomic);
// RunError names a missing or corrupt fragment.
void assembleCoco(const std::string& path, const std::string& taxonomy, const std::vector<std::string>& fragmentFiles);

// Uncompressed COCO RLE of a mask (column-major runs, starting with zeros).
std::vector<uint32_t> encodeRle(const std::vector<uint32_t>& ids, int width, int height, uint32_t id);

}  // namespace sdg
