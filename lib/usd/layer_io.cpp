// Reading layer files: the bytes of a file with its size checked, and text
// layers. Binary crate files and packages go through readLayerFile
// (layer_io_binary.cpp), which dispatches on the file's first bytes.
#include "usd/layer_io.h"

#include <cerrno>
#include <cstring>
#include <fstream>

#include "core/git_lfs.h"

namespace sdg::usd {

std::string readFileBytes(const std::string& path, const ReadLimits& limits) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw usdErrorAt(SourceLoc(path, 0, 0), std::string("cannot open the layer: ") + std::strerror(errno));
  std::streamoff size = in.tellg();
  if (size < 0) throw usdErrorAt(SourceLoc(path, 0, 0), "cannot read the layer: it is not a regular file");
  if (static_cast<uint64_t>(size) > limits.maxFileBytes)
    throw usdErrorAt(SourceLoc(path, 0, 0), "the layer is " + std::to_string(size) + " bytes, beyond the limit of " +
                                                 std::to_string(limits.maxFileBytes));
  std::string bytes(static_cast<size_t>(size), '\0');
  in.seekg(0);
  if (!in.read(bytes.data(), size)) throw usdErrorAt(SourceLoc(path, 0, 0), "cannot read the layer");
  return bytes;
}

Layer readTextLayerFile(const std::string& path, const ReadLimits& limits) {
  std::string bytes = readFileBytes(path, limits);
  if (isGitLfsPointer(bytes)) throw gitLfsPointerError(path);
  if (bytes.compare(0, 8, "PXR-USDC") == 0)
    throw usdErrorAt(SourceLoc(path, 0, 0), "is a binary crate layer, not a text layer");
  if (bytes.compare(0, 4, "PK\x03\x04") == 0)
    throw usdErrorAt(SourceLoc(path, 0, 0), "is a zip package (usdz), not a text layer");
  Layer layer = readUsdaLayer(bytes, path, limits);
  layer.realPath = path;
  return layer;
}

UsdError gitLfsPointerError(const std::string& path) {
  return UsdError(SourceLoc(path, 0, 0), gitLfsPointerMessage(path, "a USD layer"));
}

std::pair<std::string, std::string> splitPackagePath(const std::string& path) {
  if (path.empty() || path.back() != ']') return {path, ""};
  size_t open = path.find('[');
  if (open == std::string::npos) return {path, ""};
  return {path.substr(0, open), path.substr(open + 1, path.size() - open - 2)};
}

}  // namespace sdg::usd
