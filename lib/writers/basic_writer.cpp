#include "writers/basic_writer.h"

#include "writers/py_json.h"

namespace sdg {

BasicWriter::BasicWriter(const OptionSet& options, std::vector<std::string> productNames, int64_t seed)
    : options_(options),
      layout_(std::move(productNames), options.getUInt("frame_padding"), options.getBool("use_common_output_dir")),
      seed_(seed) {
  for (const AnnotatorInfo& a : annotatorTable())
    if (options_.getBool(a.name)) annotators_.push_back(&a);
}

AnnotatorNeeds BasicWriter::needs() const {
  AnnotatorNeeds needs;
  for (const AnnotatorInfo* a : annotators_) needs |= a->needs;
  return needs;
}

std::string BasicWriter::rgbPath(uint64_t frame, size_t product) const {
  return layout_.path(product, frame, "rgb", "rgb", "png");
}

std::vector<OutputFile> BasicWriter::runFiles() const {
  nlohmann::ordered_json j;
  j["name"] = "BasicWriter";
  j["version"] = "0.0.2";
  j["replicator_global_seed:"] = seed_;  // the key really ends in a colon
  const std::string text = pythonJsonDumps(j);
  return {{"metadata.txt", std::vector<uint8_t>(text.begin(), text.end())}};
}

void BasicWriter::encode(const ProductFrame& frame, FrameFiles& out) const {
  const AnnotatorOutput output{frame, options_, layout_, out.dataset};
  for (const AnnotatorInfo* a : annotators_) a->encode(output);
}

}  // namespace sdg
