#pragma once
// Finds asset files: absolute paths as given; relative paths against the
// search roots in order (the scene file's folder, the scene's asset_roots,
// then --asset-root flags). A path starting with '/' that does not exist is
// also tried below each root without the '/', as Isaac Sim prefixes its
// assets root to such paths. Paths of Isaac Sim's asset pack ("/Isaac/...")
// are tried first below the Isaac asset root, when one is configured
// (--isaac-assets, SDGBEHAVE_ISAAC_ASSETS or the scene's isaac_assets). A
// miss reports every place searched, each once.
//
// A confined resolver (the studio's) finds only files inside its roots and
// the Isaac root, compared lexically ('..' resolved, symbolic links not
// followed): a path that names a place outside them resolves to nothing, so
// no file outside them is opened.
#include <optional>
#include <string>
#include <vector>

namespace sdg {

class AssetResolver {
 public:
  AssetResolver() = default;
  explicit AssetResolver(std::vector<std::string> roots, std::string isaacRoot = "");

  const std::vector<std::string>& roots() const { return roots_; }
  // The local copy of Isaac Sim's asset pack ("" when none is configured).
  const std::string& isaacRoot() const { return isaacRoot_; }
  std::optional<std::string> resolve(const std::string& path) const;
  void confineToRoots() { confined_ = true; }
  bool confined() const { return confined_; }
  // Whether a confined resolver dropped a candidate of `path` because it
  // lies outside the roots (false for a resolver that is not confined).
  bool leavesRoots(const std::string& path) const;
  // The same for a folder.
  std::optional<std::string> resolveFolder(const std::string& path) const;
  // The candidates resolve() tries, in order and without repeats.
  std::vector<std::string> candidates(const std::string& path) const;
  // "searched: a, b, c" for messages.
  std::string describeSearch(const std::string& path) const;

 private:
  std::vector<std::string> roots_;
  std::string isaacRoot_;
  bool confined_ = false;

  std::vector<std::string> allCandidates(const std::string& path) const;
  bool insideRoots(const std::string& candidate) const;
};

// True for a path of Isaac Sim's asset pack, e.g. "/Isaac/Props/Box.usd".
bool isIsaacAssetPath(const std::string& path);

// The roots of a scene: its folder, its asset_roots (relative to it), extras;
// each folder once.
AssetResolver makeSceneResolver(const std::string& sceneDir, const std::vector<std::string>& sceneRoots,
                                const std::vector<std::string>& extraRoots, const std::string& isaacRoot = "");

}  // namespace sdg
