#include "scripting/new_behavior.h"

#include <cctype>
#include <filesystem>
#include <regex>

#include "core/diagnostics.h"
#include "core/file_io.h"
#include "core/text.h"

extern const char kTimelineBehaviorTemplate[];
extern const char kEventBehaviorTemplate[];
extern const char kExampleSceneTemplate[];

namespace sdg::scripting {
namespace {

std::string fill(std::string text, const std::vector<std::pair<std::string, std::string>>& values) {
  for (const auto& [key, value] : values) {
    const std::string placeholder = "{{" + key + "}}";
    for (size_t at = text.find(placeholder); at != std::string::npos; at = text.find(placeholder, at + value.size()))
      text.replace(at, placeholder.size(), value);
  }
  return text;
}

}  // namespace

std::string snakeCase(const std::string& camelCase) {
  std::string out;
  for (char c : camelCase) {
    if (std::isupper(static_cast<unsigned char>(c))) {
      if (!out.empty() && out.back() != '_') out += '_';
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else {
      out += c;
    }
  }
  return out;
}

NewBehaviorFiles writeNewBehavior(const std::string& name, bool events, const std::string& folder, bool overwrite) {
  static const std::regex camelCase("[a-z][A-Za-z0-9]*");
  if (!std::regex_match(name, camelCase))
    throw SceneError(SourceLoc{"NAME", 0, 0}, "a behavior's name is a camelCase identifier such as 'randomScale' "
                                              "(a lower-case letter, then letters and digits), found " +
                                                  text::quote(name));
  namespace fs = std::filesystem;
  const std::string stem = snakeCase(name);
  NewBehaviorFiles files{(fs::path(folder) / (stem + ".py")).string(), (fs::path(folder) / (stem + ".yaml")).string()};
  for (const std::string& path : {files.script, files.scene})
    if (!overwrite && fs::exists(path))
      throw SceneError(SourceLoc{path, 0, 0}, "exists already; pass --overwrite to replace it");
  std::string className = name;
  className[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(className[0])));
  const std::vector<std::pair<std::string, std::string>> values = {
      {"NAME", name},
      {"CLASS", className},
      {"FILE", stem + ".py"},
      {"SCENE", files.scene},
      {"ATTACH", events ? "{minHeight: 0.5, maxHeight: 2.0}" : "{interval: 1, minScale: 0.5, maxScale: 1.5}"},
      {"EVENTS", events ? "events:\n  - {publish: " + name + ".in, payload: {action: place}, wait_for: {state_name: "
                              "PLACED}, max_updates: 10}\n"
                        : std::string()},
  };
  std::error_code ec;
  fs::create_directories(folder.empty() ? "." : folder, ec);
  writeFileAtomic(files.script, fill(events ? kEventBehaviorTemplate : kTimelineBehaviorTemplate, values));
  writeFileAtomic(files.scene, fill(kExampleSceneTemplate, values));
  return files;
}

}  // namespace sdg::scripting
