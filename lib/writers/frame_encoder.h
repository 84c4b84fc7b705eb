#pragma once
// The per-frame job of the write pool: a collected render product's
// annotators, every writer's files, its contact sheet tile, the durable
// writes, then its manifest line (in submission order). One FrameEncoder
// serves a run; jobs hold only their frame and their sequence number.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/recycler.h"
#include "writers/manifest.h"
#include "writers/writer.h"

namespace sdg {

class FrameEncoder {
 public:
  FrameEncoder(const std::vector<std::unique_ptr<Writer>>& writers, const AnnotatorNeeds& needs,
               ManifestWriter& manifest, std::string outDir);

  // On a pool thread: everything product `frame` needs, written durably,
  // its manifest line committed as job `sequence`.
  void encode(ProductFrame& frame, uint64_t sequence);

  // Big buffers circulate between the render thread and the pool.
  Recycler<FramePasses> spareFrames;
  Recycler<CoverageMasks> spareMasks;
  // Motion: the forward and backward flow of a product (2 floats a pixel
  // each), scratch that lives only while the pool encodes it.
  Recycler<std::vector<float>> spareFlows;
  // Totals over the pool's threads.
  std::atomic<uint64_t> datasetFiles{0};
  std::atomic<uint64_t> annotateMicros{0};
  std::atomic<uint64_t> encodeMicros{0};

 private:
  const std::vector<std::unique_ptr<Writer>>& writers_;
  AnnotatorNeeds needs_;  // the writers' together
  ManifestWriter& manifest_;
  std::string outDir_;
};

}  // namespace sdg
