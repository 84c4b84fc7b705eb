#include "core/log.h"

#include <atomic>
#include <cstdio>
#include <mutex>

#include <nlohmann/json.hpp>

namespace sdg::log {
namespace {
std::atomic<Level> gMinimum{Level::Info};
std::atomic<Format> gFormat{Format::Text};
std::mutex gWriteMutex;  // keeps lines from worker threads whole

const char* levelName(Level level) {
  switch (level) {
    case Level::Debug: return "debug";
    case Level::Info: return "info";
    case Level::Warn: return "warning";
    case Level::Error: return "error";
    case Level::Quiet: break;
  }
  return "quiet";
}
}  // namespace

void configure(Level minimum, Format format) {
  gMinimum = minimum;
  gFormat = format;
}

Level minimumLevel() { return gMinimum; }

bool enabled(Level level) { return level >= gMinimum.load() && level != Level::Quiet; }

void write(Level level, std::string_view message) {
  if (!enabled(level)) return;
  std::string line;
  if (gFormat == Format::Json) {
    nlohmann::ordered_json j;
    j["level"] = levelName(level);
    j["message"] = std::string(message);
    line = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  } else {
    line = std::string("sdgbehave: ") + levelName(level) + ": " + std::string(message);
  }
  line += '\n';
  std::lock_guard lock(gWriteMutex);
  std::fwrite(line.data(), 1, line.size(), stderr);
}

namespace {

// A located problem, with a loss's count in the JSON form when `dropped` is set.
void writeDiagnostic(const Diagnostic& d, const DroppedInfo* dropped) {
  Level level = d.severity == Severity::Error ? Level::Error : Level::Warn;
  if (!enabled(level)) return;
  std::string line;
  if (gFormat == Format::Json) {
    nlohmann::ordered_json j;
    j["level"] = levelName(level);
    j["file"] = d.loc.file.str();
    j["line"] = d.loc.line;
    j["column"] = d.loc.column;
    j["message"] = d.message;
    if (dropped) j["dropped"] = {{"kind", dropped->kind}, {"what", dropped->what}, {"count", dropped->count}};
    // A value mounted from a smart asset: where each file referenced the next.
    if (d.loc.via) {
      nlohmann::ordered_json chain = nlohmann::ordered_json::array();
      for (const SourceLoc* from = d.loc.via.get(); from; from = from->via.get())
        chain.push_back({{"file", from->file.str()}, {"line", from->line}, {"column", from->column}});
      j["referenced_from"] = std::move(chain);
    }
    line = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  } else {
    line = d.format();
  }
  line += '\n';
  std::lock_guard lock(gWriteMutex);
  std::fwrite(line.data(), 1, line.size(), stderr);
}

}  // namespace

void diagnostic(const Diagnostic& d) { writeDiagnostic(d, nullptr); }

void dropped(const DroppedWarning& w) { writeDiagnostic(w.diagnostic, &w.info); }

}  // namespace sdg::log
