#pragma once
// A run's identity: every input that shapes its output files, hashed. The
// scene file and every file it mounts (smart assets), the behavior scripts
// and the Python files they import, plugins, and every file the stage names
// (meshes with the files they pull in, textures, domes, behaviors' file
// lists), plus sdgbehave's own version. It is recorded in the output
// folder's run.json; --resume, every shard and `merge` refuse a folder whose
// recorded identity differs, naming each changed file.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sdg {

struct LoadedScene;

struct RunInput {
  std::string path;  // relative to the scene's folder when below it, else absolute
  std::string role;  // "scene", "asset", "script", "python", "plugin", "file"
  uint64_t bytes = 0;
  std::string sha256;
  bool operator==(const RunInput&) const = default;
};

struct RunInputs {
  std::string version;          // sdgbehave's version
  std::vector<RunInput> files;  // sorted by path, each once

  // One SHA-256 over the version and every file's path and hash.
  std::string identity() const;
  nlohmann::ordered_json toJson() const;
  static RunInputs fromJson(const nlohmann::json& j);  // {} for a run.json without inputs
  bool operator==(const RunInputs&) const = default;
};

// sdgbehave's version as `--version` prints it ("0.1.0 (v0.1.0-12-gabc)").
std::string toolVersion();

// Hashes the inputs of a loaded scene (files are read once each).
RunInputs collectRunInputs(const LoadedScene& loaded, const std::string& version = toolVersion());

// What differs, one line per file ("scripts/light.py: changed",
// "textures/old.png: no longer used", "textures/new.png: new input",
// "sdgbehave version: 0.1.0, now 0.2.0"); empty when nothing does.
std::vector<std::string> inputChanges(const RunInputs& recorded, const RunInputs& now);

}  // namespace sdg
