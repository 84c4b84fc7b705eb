#include "assets/asset_resolver.h"

#include <filesystem>

#include "core/text.h"

namespace sdg {
namespace fs = std::filesystem;

std::vector<std::string> AssetResolver::candidates(const std::string& path) const {
  std::vector<std::string> out;
  if (path.empty()) return out;
  fs::path p(path);
  if (p.is_absolute()) {
    out.push_back(path);
    std::string relative = path.substr(path.find_first_not_of('/'));
    for (const std::string& root : roots_) out.push_back((fs::path(root) / relative).lexically_normal().string());
    return out;
  }
  for (const std::string& root : roots_) out.push_back((fs::path(root) / p).lexically_normal().string());
  return out;
}

std::optional<std::string> AssetResolver::resolve(const std::string& path) const {
  for (const std::string& candidate : candidates(path)) {
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec)) return candidate;
  }
  return std::nullopt;
}

std::string AssetResolver::describeSearch(const std::string& path) const {
  std::vector<std::string> tried = candidates(path);
  if (tried.empty()) return "no search roots";
  return "searched: " + text::join(tried, ", ");
}

AssetResolver makeSceneResolver(const std::string& sceneDir, const std::vector<std::string>& sceneRoots,
                                const std::vector<std::string>& extraRoots) {
  std::vector<std::string> roots = {sceneDir.empty() ? "." : sceneDir};
  for (const std::string& r : sceneRoots)
    roots.push_back(fs::path(r).is_absolute() ? r : (fs::path(roots[0]) / r).lexically_normal().string());
  for (const std::string& r : extraRoots) roots.push_back(r);
  return AssetResolver(std::move(roots));
}

}  // namespace sdg
