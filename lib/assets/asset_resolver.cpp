#include "assets/asset_resolver.h"

#include <algorithm>
#include <filesystem>

#include "core/text.h"

namespace sdg {
namespace fs = std::filesystem;

namespace {

// "a/b/." and "a/b/" name the folder "a/b": one spelling, so it is listed once.
std::string normalFolder(const std::string& folder) {
  std::string s = fs::path(folder).lexically_normal().string();
  while (s.size() > 1 && s.back() == '/') s.pop_back();
  return s;
}

void addOnce(std::vector<std::string>& list, std::string item) {
  if (std::find(list.begin(), list.end(), item) == list.end()) list.push_back(std::move(item));
}

}  // namespace

bool isIsaacAssetPath(const std::string& path) { return path.starts_with("/Isaac/"); }

AssetResolver::AssetResolver(std::vector<std::string> roots, std::string isaacRoot)
    : isaacRoot_(std::move(isaacRoot)) {
  for (const std::string& root : roots) addOnce(roots_, normalFolder(root));
}

std::vector<std::string> AssetResolver::candidates(const std::string& path) const {
  std::vector<std::string> out = allCandidates(path);
  if (confined_) std::erase_if(out, [&](const std::string& c) { return !insideRoots(c); });
  return out;
}

bool AssetResolver::leavesRoots(const std::string& path) const {
  if (!confined_) return false;
  for (const std::string& c : allCandidates(path))
    if (!insideRoots(c)) return true;
  return false;
}

bool AssetResolver::insideRoots(const std::string& candidate) const {
  const fs::path file = fs::absolute(candidate).lexically_normal();
  auto inside = [&](const std::string& root) {
    const fs::path relative = file.lexically_relative(fs::absolute(root).lexically_normal());
    return !relative.empty() && *relative.begin() != "..";
  };
  if (!isaacRoot_.empty() && inside(isaacRoot_)) return true;
  return std::any_of(roots_.begin(), roots_.end(), inside);
}

std::vector<std::string> AssetResolver::allCandidates(const std::string& path) const {
  std::vector<std::string> out;
  if (path.empty()) return out;
  fs::path p(path);
  if (p.is_absolute()) {
    std::string relative = path.substr(path.find_first_not_of('/'));
    // An Isaac root may be the folder that holds Isaac/ or Isaac/ itself.
    if (!isaacRoot_.empty() && isIsaacAssetPath(path)) {
      addOnce(out, (fs::path(isaacRoot_) / relative).lexically_normal().string());
      addOnce(out, (fs::path(isaacRoot_) / relative.substr(std::string("Isaac/").size())).lexically_normal().string());
    }
    addOnce(out, path);
    for (const std::string& root : roots_) addOnce(out, (fs::path(root) / relative).lexically_normal().string());
    return out;
  }
  for (const std::string& root : roots_) addOnce(out, (fs::path(root) / p).lexically_normal().string());
  return out;
}

std::optional<std::string> AssetResolver::resolve(const std::string& path) const {
  for (const std::string& candidate : candidates(path)) {
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec)) return candidate;
  }
  return std::nullopt;
}

std::optional<std::string> AssetResolver::resolveFolder(const std::string& path) const {
  for (const std::string& candidate : candidates(path)) {
    std::error_code ec;
    if (fs::is_directory(candidate, ec)) return candidate;
  }
  return std::nullopt;
}

std::string AssetResolver::describeSearch(const std::string& path) const {
  std::vector<std::string> tried = candidates(path);
  if (tried.empty()) return "no search roots";
  return "searched: " + text::join(tried, ", ");
}

AssetResolver makeSceneResolver(const std::string& sceneDir, const std::vector<std::string>& sceneRoots,
                                const std::vector<std::string>& extraRoots, const std::string& isaacRoot) {
  std::vector<std::string> roots = {sceneDir.empty() ? "." : sceneDir};
  for (const std::string& r : sceneRoots)
    roots.push_back(fs::path(r).is_absolute() ? r : (fs::path(roots[0]) / r).lexically_normal().string());
  for (const std::string& r : extraRoots) roots.push_back(r);
  return AssetResolver(std::move(roots), isaacRoot);
}

}  // namespace sdg
