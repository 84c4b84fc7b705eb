#pragma once
// Finds asset files: absolute paths as given; relative paths against the
// search roots in order (the scene file's folder, the scene's asset_roots,
// then --asset-root flags). A path starting with '/' that does not exist is
// also tried below each root without the '/', as Isaac Sim prefixes its
// assets root to such paths. A miss reports every place searched.
#include <optional>
#include <string>
#include <vector>

namespace sdg {

class AssetResolver {
 public:
  AssetResolver() = default;
  explicit AssetResolver(std::vector<std::string> roots) : roots_(std::move(roots)) {}

  const std::vector<std::string>& roots() const { return roots_; }
  std::optional<std::string> resolve(const std::string& path) const;
  // The candidates resolve() tries, in order (for error messages).
  std::vector<std::string> candidates(const std::string& path) const;
  // "searched: a, b, c" for messages.
  std::string describeSearch(const std::string& path) const;

 private:
  std::vector<std::string> roots_;
};

// The roots of a scene: its folder, its asset_roots (relative to it), extras.
AssetResolver makeSceneResolver(const std::string& sceneDir, const std::vector<std::string>& sceneRoots,
                                const std::vector<std::string>& extraRoots);

}  // namespace sdg
