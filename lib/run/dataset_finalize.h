#pragma once
// What a dataset gets once all its frames exist: the canonical manifest
// (sorted, one line per frame and product), the COCO file assembled from
// its fragments, and the contact sheet composed from its tiles. The end of
// a whole run and `sdgbehave merge` after shards both call it, which is why
// both give the same bytes.
#include <string>

#include "run/output_folder.h"

namespace sdg {

struct FinalizeResult {
  uint64_t frames = 0;   // frames listed for every product
  uint64_t files = 0;    // files it wrote (COCO, contact sheet, manifest)
};

// RunError naming the first missing frame when the folder is incomplete.
FinalizeResult finalizeDataset(const std::string& dir, const RunInfo& info);

// After a failed run: contact_sheet.png of the sheet frames that were
// finished (their tiles exist), so a look shows how far it got. Nothing
// when none was.
void writeContactSheetOfFinishedFrames(const std::string& dir, const RunInfo& info);

}  // namespace sdg
