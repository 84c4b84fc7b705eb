#pragma once
// The project log: one line per message on stderr, as text or as JSON lines
// for log collectors. Libraries and ODE's message handlers all end up here.
#include <string>
#include <string_view>

#include "core/diagnostics.h"
#include "core/dropped.h"

namespace sdg::log {

enum class Level { Debug = 0, Info = 1, Warn = 2, Error = 3, Quiet = 4 };
enum class Format { Text, Json };

void configure(Level minimum, Format format);
Level minimumLevel();
bool enabled(Level level);
void write(Level level, std::string_view message);

// A located problem: "file:line:col: error: message" as text (the compiler
// convention editors parse), or a JSON object with separate fields.
void diagnostic(const Diagnostic& d);
// A loss (core/dropped.h): the diagnostic, with `"dropped": {kind, what,
// count}` in the JSON form.
void dropped(const DroppedWarning& w);

inline void debug(std::string_view m) { write(Level::Debug, m); }
inline void info(std::string_view m) { write(Level::Info, m); }
inline void warn(std::string_view m) { write(Level::Warn, m); }
inline void error(std::string_view m) { write(Level::Error, m); }

}  // namespace sdg::log
