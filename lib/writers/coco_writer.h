#pragma once
// One COCO "instances" JSON for the whole run: images, categories from the
// semantic labels, and per visible entity an annotation with its tight box,
// an uncompressed RLE mask (column-major, as pycocotools reads), its area and
// iscrowd 0. Streamed: each frame's entries are appended to two temporary
// files in frame order; finish() joins them into the final file once, with
// an atomic rename. Nothing is re-read or rewritten per frame.
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "writers/annotators.h"

namespace sdg {

class CocoWriter {
 public:
  // `outDir`/`fileName` is the final file; `imagePrefix` names the rgb files.
  CocoWriter(std::string outDir, std::string fileName, std::string taxonomy);
  ~CocoWriter();
  CocoWriter(const CocoWriter&) = delete;
  CocoWriter& operator=(const CocoWriter&) = delete;

  // Appends one image and its annotations; call in frame order.
  void addFrame(const std::string& imageFile, int width, int height, const FrameAnnotations& annotations,
                const FrameSemantics& semantics);
  // Writes the final JSON (RunError on I/O failure) and removes the streams.
  void finish();

  // Uncompressed COCO RLE of a mask (column-major runs, starting with zeros).
  static std::vector<uint32_t> encodeRle(const std::vector<uint32_t>& ids, int width, int height, uint32_t id);

 private:
  void append(std::FILE* file, const std::string& text, bool& first);
  std::string outDir_, fileName_, taxonomy_;
  std::FILE* images_ = nullptr;
  std::FILE* annotations_ = nullptr;
  bool firstImage_ = true, firstAnnotation_ = true;
  uint64_t nextImage_ = 1, nextAnnotation_ = 1;
  std::map<std::string, uint32_t> categories_;  // label -> category id, first-seen order
  std::vector<std::string> categoryOrder_;
};

}  // namespace sdg
