#include "writers/writer_registry.h"

#include <iterator>

#include "core/diagnostics.h"
#include "core/text.h"
#include "writers/basic_writer.h"
#include "writers/bop_writer.h"
#include "writers/coco_writer.h"

namespace sdg {
namespace {

// What a factory sees: its config, the setup, and the writers made so far.
struct Making {
  const WriterConfig& config;
  const WriterSetup& setup;
  WriterSet& set;
  const BasicWriter* images;  // the BasicWriter, made first (null when there is none)
};

std::vector<std::string> typesOf(const WriterConfig& config) {
  return config.options.get("semantic_types").get<std::vector<std::string>>();
}

std::unique_ptr<Writer> makeBasic(Making& m) {
  return std::make_unique<BasicWriter>(m.config.options, m.setup.productNames, m.setup.seed);
}

std::unique_ptr<Writer> makeCoco(Making& m) {
  const std::vector<std::string> types = typesOf(m.config);
  m.set.parts.cocoFile = m.config.options.getString("file_name");
  m.set.parts.cocoTaxonomy = types.empty() ? std::string("class") : types.front();
  return std::make_unique<CocoWriter>(*m.images, m.set.parts.cocoTaxonomy);
}

std::unique_ptr<Writer> makeBop(Making& m) {
  const std::string taxonomy = m.set.semanticTypes.empty() ? std::string("class") : m.set.semanticTypes.front();
  auto writer = std::make_unique<BopWriter>(m.config, m.setup, taxonomy, m.set.semanticTypes);
  m.set.parts.bopSplit = writer->split();
  return writer;
}

struct WriterEntry {
  std::string_view type;
  std::unique_ptr<Writer> (*make)(Making&);
};

// In the order a frame's files are made (BasicWriter first: COCO names its images).
constexpr size_t kBasic = 0, kCoco = 1;
constexpr WriterEntry kWriters[] = {
    {"BasicWriter", makeBasic},
    {"CocoWriter", makeCoco},
    {"BopWriter", makeBop},
};

}  // namespace

std::vector<std::string_view> registeredWriterTypes() {
  std::vector<std::string_view> names;
  for (const WriterEntry& e : kWriters) names.push_back(e.type);
  return names;
}

WriterSet makeWriters(const std::vector<WriterConfig>& configs, const WriterSetup& setup, const SourceLoc& sceneLoc) {
  if (configs.empty())
    throw SceneError(sceneLoc, "the scene has no writer; add e.g. `writer: {type: BasicWriter, rgb: true}`");
  std::vector<std::string> known;
  for (const WriterEntry& e : kWriters) known.emplace_back(e.type);
  const WriterConfig* byEntry[std::size(kWriters)] = {};  // kBasic, kCoco, ...
  for (const WriterConfig& config : configs) {
    size_t at = 0;
    while (at < std::size(kWriters) && kWriters[at].type != config.type) ++at;
    if (at == std::size(kWriters))
      throw SceneError(config.loc, "writer.type: unknown writer " + text::quote(config.type) + "; known writers: " +
                                       text::join(known, ", ") + text::didYouMean(config.type, known));
    byEntry[at] = &config;
  }
  // COCO alone still needs its images: they are written as BasicWriter's rgb.
  const WriterTypeInfo* basicType = findWriterType("BasicWriter");
  WriterConfig imagesOnly{"BasicWriter", OptionSet(basicType->options), sceneLoc};
  imagesOnly.options.set("rgb", Value::makeBool(true));
  const bool coco = byEntry[kCoco] != nullptr;
  if (coco && !byEntry[kBasic]) byEntry[kBasic] = &imagesOnly;

  WriterSet set;
  // Entities come from the taxonomies of the writer that shows them.
  if (byEntry[kBasic] && byEntry[kBasic] != &imagesOnly) set.semanticTypes = typesOf(*byEntry[kBasic]);
  else if (coco) set.semanticTypes = typesOf(*byEntry[kCoco]);
  else set.semanticTypes = {"class"};
  const BasicWriter* images = nullptr;
  for (size_t i = 0; i < std::size(kWriters); ++i) {
    if (!byEntry[i]) continue;
    Making making{*byEntry[i], setup, set, images};
    set.writers.push_back(kWriters[i].make(making));
    if (i == kBasic) images = static_cast<const BasicWriter*>(set.writers.back().get());
    set.needs |= set.writers.back()->needs();
  }
  return set;
}

}  // namespace sdg
