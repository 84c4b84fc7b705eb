#include "run/run_inputs.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "assets/file_check.h"
#include "run/scene_setup.h"
#include "scripting/script_imports.h"
#include "writers/manifest.h"

namespace sdg {
namespace fs = std::filesystem;

namespace {

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Files a mesh pulls in that the scene does not name: an OBJ's material
// libraries and their maps, a glTF's buffers and images. They change the
// rendered pixels as much as the mesh itself.
std::vector<std::string> meshSidecars(const std::string& meshPath) {
  std::string ext = fs::path(meshPath).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  const fs::path dir = fs::path(meshPath).parent_path();
  std::vector<std::string> out;
  auto addRelative = [&](const std::string& name) {
    if (name.empty() || name.starts_with("data:") || name.find("://") != std::string::npos) return;
    fs::path p = dir / name;
    std::error_code ec;
    if (fs::is_regular_file(p, ec)) out.push_back(p.lexically_normal().string());
  };
  if (ext == ".obj" || ext == ".mtl") {
    static const std::regex line(R"(^\s*(mtllib|map_\w+|bump|disp|norm)\s+(?:-\S+\s+\S+\s+)*(.+?)\s*$)",
                                 std::regex::multiline);
    const std::string text = readText(meshPath);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), line); it != std::sregex_iterator(); ++it) {
      const std::string name = (*it)[2].str();
      const size_t before = out.size();
      addRelative(name);
      if (out.size() > before && (*it)[1].str() == "mtllib")
        for (const std::string& m : meshSidecars(out.back())) out.push_back(m);
    }
  } else if (ext == ".gltf") {
    auto j = nlohmann::json::parse(readText(meshPath), nullptr, false);
    if (j.is_object())
      for (const char* key : {"buffers", "images"})
        if (j.contains(key) && j[key].is_array())
          for (const auto& item : j[key])
            if (item.is_object() && item.contains("uri") && item["uri"].is_string()) addRelative(item["uri"]);
  }
  return out;
}

class InputSet {
 public:
  explicit InputSet(std::string sceneDir) : sceneDir_(fs::absolute(sceneDir).lexically_normal().string()) {
    if (!sceneDir_.ends_with('/')) sceneDir_ += '/';
  }

  void add(const std::string& file, const std::string& role) {
    const std::string absolute = fs::absolute(file).lexically_normal().string();
    if (!seen_.insert(absolute).second) return;
    // A file that cannot be read fails the run where it is used, with its own message.
    std::error_code ec;
    const uint64_t bytes = fs::file_size(absolute, ec);
    std::string hash = ec ? std::string() : sha256OfFile(absolute);
    if (hash.empty()) return;
    const std::string shown = absolute.starts_with(sceneDir_) ? absolute.substr(sceneDir_.size()) : absolute;
    inputs_.files.push_back({shown, role, bytes, std::move(hash)});
  }

  RunInputs take(std::string version) {
    std::sort(inputs_.files.begin(), inputs_.files.end(),
              [](const RunInput& a, const RunInput& b) { return a.path < b.path; });
    inputs_.version = std::move(version);
    return std::move(inputs_);
  }

 private:
  std::string sceneDir_;
  std::set<std::string> seen_;
  RunInputs inputs_;
};

}  // namespace

std::string toolVersion() {
  std::string v = SDG_VERSION;
  if (std::string(SDG_GIT_DESCRIBE).size()) v += " (" SDG_GIT_DESCRIBE ")";
  return v;
}

std::string RunInputs::identity() const {
  std::string text = "sdgbehave " + version + "\n";
  for (const RunInput& f : files) text += f.sha256 + " " + f.path + "\n";
  return sha256Hex(std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

nlohmann::ordered_json RunInputs::toJson() const {
  nlohmann::ordered_json j;
  j["sdgbehave"] = version;
  j["identity"] = identity();
  j["files"] = nlohmann::ordered_json::array();
  for (const RunInput& f : files)
    j["files"].push_back({{"path", f.path}, {"role", f.role}, {"bytes", f.bytes}, {"sha256", f.sha256}});
  return j;
}

RunInputs RunInputs::fromJson(const nlohmann::json& j) {
  RunInputs inputs;
  if (!j.is_object()) return inputs;
  inputs.version = j.value("sdgbehave", "");
  if (j.contains("files"))
    for (const auto& f : j.at("files"))
      inputs.files.push_back({f.at("path").get<std::string>(), f.at("role").get<std::string>(),
                              f.at("bytes").get<uint64_t>(), f.at("sha256").get<std::string>()});
  return inputs;
}

RunInputs collectRunInputs(const LoadedScene& loaded, const std::string& version) {
  const Scene& scene = loaded.scene;
  InputSet set(scene.sourceDir.empty() ? "." : scene.sourceDir);
  if (!scene.sourcePath.empty()) set.add(scene.sourcePath, "scene");
  for (const std::string& file : loaded.mountedFiles) set.add(file, "asset");
  for (const std::string& file : loaded.scriptFiles) set.add(file, "script");
  for (const std::string& file : scripting::importedSourceFiles(loaded.scriptFiles)) set.add(file, "python");
  for (const std::string& file : loaded.pluginFiles) set.add(file, "plugin");
  forEachStageFile(scene.stage, loaded.registry.catalog(), loaded.assets,
                   [&](const Prim&, const Attribute&, const std::string&, const std::string& entry, FileKind kind) {
                     std::string file = entry;
                     if (kind == FileKind::Mesh) file = file.substr(0, file.rfind('#'));
                     if (std::optional<std::string> path = loaded.assets.resolve(file)) {
                       set.add(*path, "file");
                       if (kind == FileKind::Mesh || kind == FileKind::Any)
                         for (const std::string& sidecar : meshSidecars(*path)) set.add(sidecar, "file");
                     } else if (std::optional<std::string> folder = loaded.assets.resolveFolder(file)) {
                       // A folder a behavior draws from: every file in it counts.
                       std::vector<std::string> names;
                       std::error_code ec;
                       for (const auto& e : fs::directory_iterator(*folder, ec))
                         if (e.is_regular_file(ec)) names.push_back(e.path().string());
                       std::sort(names.begin(), names.end());
                       for (const std::string& name : names) set.add(name, "file");
                     }
                   });
  return set.take(version);
}

std::vector<std::string> inputChanges(const RunInputs& recorded, const RunInputs& now) {
  std::vector<std::string> changes;
  if (recorded.files.empty() && recorded.version.empty()) {
    changes.push_back("the folder's run.json records no input hashes (written by an older sdgbehave)");
    return changes;
  }
  if (recorded.version != now.version)
    changes.push_back("sdgbehave version: " + recorded.version + ", now " + now.version);
  std::map<std::string, const RunInput*> before, after;
  for (const RunInput& f : recorded.files) before[f.path] = &f;
  for (const RunInput& f : now.files) after[f.path] = &f;
  for (const auto& [path, f] : before) {
    auto it = after.find(path);
    if (it == after.end())
      changes.push_back(path + ": no longer an input");
    else if (it->second->sha256 != f->sha256)
      changes.push_back(path + ": changed (" + std::to_string(f->bytes) + " bytes, now " +
                        std::to_string(it->second->bytes) + ")");
  }
  for (const auto& [path, f] : after)
    if (!before.count(path)) changes.push_back(path + ": new input");
  return changes;
}

}  // namespace sdg
