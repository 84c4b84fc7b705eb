#pragma once
// `--record FILE.jsonl`: one JSON object per line, per captured frame (and a
// final one for the stop), listing every attribute behaviors changed since
// the previous line: {"frame": 0, "time": 0.0167, "changes": [{"prim": ...,
// "attribute": ..., "value": ...}]}. A removed attribute has "value": null.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stage/stage.h"

namespace sdg {

class ChangeRecorder {
 public:
  // Opens FILE (truncating); the recorder compares against `initial`.
  ChangeRecorder(const std::string& path, const Stage& initial);
  ~ChangeRecorder();
  ChangeRecorder(const ChangeRecorder&) = delete;
  ChangeRecorder& operator=(const ChangeRecorder&) = delete;

  // After each pre-roll: {"event": "preroll", "settle": [...], "changes":
  // what the pre-roll changed (e.g. the stacked assets)}.
  void recordPreroll(const std::vector<nlohmann::ordered_json>& settle, const Stage& now);
  void recordFrame(uint64_t frame, double time, const Stage& now);
  void recordStop(const Stage& now);
  // Flushes and closes; a write error throws RunError naming the file.
  void close();

 private:
  void writeLine(const std::string& head, const Stage& now);
  void writeText(const std::string& text);
  std::string path_;
  std::FILE* file_ = nullptr;
  Stage previous_;
};

}  // namespace sdg
