#include "run/record.h"

#include <cerrno>
#include <cstring>

#include <nlohmann/json.hpp>

#include "core/diagnostics.h"
#include "stage/value_json.h"
#include "stage/stage_diff.h"

namespace sdg {

ChangeRecorder::ChangeRecorder(const std::string& path, const Stage& initial) : path_(path), previous_(initial) {
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw RunError("cannot write the record file " + path + ": " + std::strerror(errno));
}

ChangeRecorder::~ChangeRecorder() {
  if (file_) std::fclose(file_);
}

void ChangeRecorder::writeLine(const std::string& head, const Stage& now) {
  nlohmann::ordered_json line = nlohmann::ordered_json::parse(head);
  nlohmann::ordered_json changes = nlohmann::ordered_json::array();
  for (const StageChange& c : diffStages(previous_, now)) {
    nlohmann::ordered_json change;
    change["prim"] = c.prim;
    change["attribute"] = c.attribute;
    change["value"] = c.value ? valueToJson(*c.value) : nlohmann::ordered_json(nullptr);
    changes.push_back(std::move(change));
  }
  line["changes"] = std::move(changes);
  writeText(line.dump() + "\n");
  previous_ = now;
}

void ChangeRecorder::writeText(const std::string& text) {
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size())
    throw RunError("cannot write the record file " + path_ + ": " + std::strerror(errno));
}

void ChangeRecorder::recordFrame(uint64_t frame, double time, const Stage& now) {
  nlohmann::ordered_json head;
  head["frame"] = frame;
  head["time"] = time;
  writeLine(head.dump(), now);
}

void ChangeRecorder::recordPreroll(const std::vector<nlohmann::ordered_json>& settle, const Stage& now) {
  nlohmann::ordered_json head;
  head["event"] = "preroll";
  head["settle"] = settle;
  writeLine(head.dump(), now);
}

void ChangeRecorder::recordStop(const Stage& now) { writeLine(R"({"event": "stop"})", now); }

void ChangeRecorder::close() {
  if (!file_) return;
  bool ok = std::fflush(file_) == 0;
  ok = std::fclose(file_) == 0 && ok;
  file_ = nullptr;
  if (!ok) throw RunError("cannot write the record file " + path_ + ": " + std::strerror(errno));
}

}  // namespace sdg
