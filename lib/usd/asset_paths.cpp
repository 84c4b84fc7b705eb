// Anchoring asset paths (compose.h's resolveAssetPath) and the package-path
// helpers it needs (asset_paths.h). USD's rule: a relative asset path
// resolves from the folder of the layer that wrote it; for a layer inside a
// package that folder is the layer's folder in its innermost package, and a
// path that climbs out of a package continues from the package's own place.
#include "usd/asset_paths.h"

#include <algorithm>
#include <filesystem>

#include "usd/compose.h"
#include "usd/layer_io.h"

namespace sdg::usd {

namespace {

namespace fs = std::filesystem;

std::string normal(const fs::path& p) { return p.lexically_normal().generic_string(); }

std::string folderOf(const std::string& path) { return fs::path(path).parent_path().generic_string(); }

// `relative` from the folder `folder` of `package` (an entry's folder, "" for
// the package's root).
std::string anchorInPackage(const std::string& package, const std::string& folder, const std::string& relative) {
  const std::string inner = normal(fs::path(folder) / relative);
  if (inner != ".." && inner.rfind("../", 0) != 0) return joinPackagePath(package, inner);
  // Out of the package: the rest continues from where the package itself is.
  const std::string rest = inner == ".." ? "." : inner.substr(3);
  auto [outer, entry] = splitPackagePathInner(package);
  if (entry.empty()) return normal(fs::path(folderOf(package)) / rest);
  return anchorInPackage(outer, folderOf(entry), rest);
}

}  // namespace

std::pair<std::string, std::string> splitPackagePathInner(const std::string& path) {
  if (path.empty() || path.back() != ']') return {path, ""};
  const size_t open = path.rfind('[');
  if (open == std::string::npos) return {path, ""};
  const size_t close = path.find(']', open);
  return {path.substr(0, open) + path.substr(close + 1), path.substr(open + 1, close - open - 1)};
}

std::string joinPackagePath(const std::string& package, const std::string& packaged) {
  auto [outer, inner] = splitPackagePath(package);
  if (inner.empty()) return package + "[" + packaged + "]";
  return outer + "[" + joinPackagePath(inner, packaged) + "]";
}

bool namesPackage(const std::string& path) {
  auto [package, entry] = splitPackagePathInner(path);
  std::string name = entry.empty() ? path : entry;
  if (name.size() < 5) return false;
  std::transform(name.end() - 5, name.end(), name.end() - 5, [](unsigned char c) { return char(std::tolower(c)); });
  return name.compare(name.size() - 5, 5, ".usdz") == 0;
}

std::string resolveAssetPath(const std::string& assetPath, const std::string& anchorIdentifier) {
  // "pkg.usdz[inner]" as written: the package anchored, the entry inside it.
  if (auto [package, entry] = splitPackagePath(assetPath); !entry.empty())
    return joinPackagePath(resolveAssetPath(package, anchorIdentifier), normal(entry));
  if (!assetPath.empty() && assetPath[0] == '/') return normal(assetPath);
  if (assetPath.find("://") != std::string::npos) return assetPath;  // a URL ("dynamic://", "omniverse://")
  // A package opened by its own name anchors at its root (its root layer
  // is found by opening it: the layer cache names that layer by its entry).
  if (namesPackage(anchorIdentifier)) return anchorInPackage(anchorIdentifier, "", assetPath);
  auto [package, entry] = splitPackagePathInner(anchorIdentifier);
  if (!entry.empty()) return anchorInPackage(package, folderOf(entry), assetPath);
  return normal(fs::path(folderOf(anchorIdentifier)) / assetPath);
}

}  // namespace sdg::usd
