#include "writers/frame_encoder.h"

#include <chrono>

#include "writers/contact_sheet.h"
#include "writers/motion.h"

namespace sdg {
namespace {

using Clock = std::chrono::steady_clock;

uint64_t microsBetween(Clock::time_point a, Clock::time_point b) {
  return uint64_t(std::chrono::duration_cast<std::chrono::microseconds>(b - a).count());
}

// A frame's thumbnail with the tight box (visible pixels) and class of
// every visible entity.
std::vector<uint8_t> sheetTile(const ProductFrame& frame) {
  const FrameSemantics& semantics = frame.scene->semantics;
  std::vector<SheetBox> boxes;
  for (const Box2D& b : frame.annotations.tight) {
    const LabelSet& labels = semantics.entities[b.entity].labels;
    auto cls = labels.find("class");
    std::string label = cls != labels.end() ? cls->second : labels.empty() ? "" : labels.begin()->second;
    boxes.push_back({b.xMin, b.yMin, b.xMax, b.yMax, b.semanticId, label});
  }
  return contactSheetTile(frame.frame, frame.passes.rgba, frame.passes.width, frame.passes.height, boxes);
}

// Per entity and render id, the names the writers print.
void nameEntities(ProductFrame& frame) {
  const FrameScene& scene = *frame.scene;
  for (const SemanticEntity& e : scene.semantics.entities) {
    frame.entityPaths.push_back(e.primPath);
    frame.entityLabels.push_back(e.labels);
  }
  frame.semanticLabels = scene.semantics.semanticLabels;
  frame.renderIdPaths.assign(scene.semantics.entityOfRenderId.size(), "");
  for (const RenderItem& item : scene.list.items)
    if (item.instanceId < frame.renderIdPaths.size()) frame.renderIdPaths[item.instanceId] = item.primPath;
}

}  // namespace

FrameEncoder::FrameEncoder(const std::vector<std::unique_ptr<Writer>>& writers, const AnnotatorNeeds& needs,
                           ManifestWriter& manifest, std::string outDir)
    : writers_(writers), needs_(needs), manifest_(manifest), outDir_(std::move(outDir)) {}

void FrameEncoder::encode(ProductFrame& frame, uint64_t sequence) {
  const auto jobStart = Clock::now();
  const FrameScene& scene = *frame.scene;
  std::vector<EntityCoverage> entityCoverage;
  if (frame.hasMasks) {
    coverageOfMasks(frame.masks, frame.coverage);
    for (const auto& c : frame.coverage) entityCoverage.push_back({c.pixels, c.xMin, c.yMin, c.xMax, c.yMax});
  }
  // Sheet frames need the tight boxes even when no writer does.
  if (needs_.labels || frame.toSheet)
    annotate(AnnotatorInputs{frame.passes, scene.list, frame.cameraIndex, scene.semantics, entityCoverage,
                             scene.itemBounds},
             frame.annotations);
  nameEntities(frame);
  if (needs_.motion) {
    frame.forwardFlow = spareFlows.take();
    frame.backwardFlow = spareFlows.take();
    flowTo(frame.passes, scene.list, frame.camera, frame.metersPerUnit, scene.next.get(), frame.forwardFlow);
    flowTo(frame.passes, scene.list, frame.camera, frame.metersPerUnit, scene.previous.get(), frame.backwardFlow);
  }
  const auto encodeStart = Clock::now();
  annotateMicros += microsBetween(jobStart, encodeStart);

  FrameFiles files;
  for (const auto& writer : writers_) writer->encode(frame, files);
  if (frame.toSheet) files.parts.push_back({contactSheetTilePath(frame.frame), sheetTile(frame)});
  const size_t datasetCount = files.dataset.size();  // the hidden parts are not counted
  std::vector<OutputFile>& encoded = files.dataset;
  for (OutputFile& part : files.parts) encoded.push_back(std::move(part));
  writeFiles(outDir_, encoded);  // made durable with the manifest's next batch (group commit)
  ManifestEntry entry{frame.frame, uint32_t(frame.product), {}};
  for (const OutputFile& f : encoded) entry.files.push_back({f.path, f.bytes.size(), sha256Hex(f.bytes)});
  manifest_.commit(sequence, std::move(entry));
  datasetFiles += datasetCount;
  spareFrames.give(std::move(frame.passes));
  if (frame.hasMasks) spareMasks.give(std::move(frame.masks));
  if (needs_.motion) {
    spareFlows.give(std::move(frame.forwardFlow));
    spareFlows.give(std::move(frame.backwardFlow));
  }
  encodeMicros += microsBetween(encodeStart, Clock::now());
}

}  // namespace sdg
