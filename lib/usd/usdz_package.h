#pragma once
// .usdz packages: a zip archive whose first USD layer is the package's root
// layer; the other entries (layers, textures, nested packages) are found by
// asset paths relative to the entry that names them. Read through Debian's
// libzip. USD writes entries stored (uncompressed); entries compressed with a
// method libzip supports (deflate) are read too, inflated against
// ReadLimits::maxInflatedEntryBytes (a zip bomb is refused, not held in
// memory); encrypted entries are an error.
//
// Entry names inside a nested package are written "outer.usdz[inner.usdc]"
// (as USD's package-relative paths do), to any depth up to
// ReadLimits::maxNesting.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "usd/layer.h"

struct zip;

namespace sdg::usd {

class UsdzPackage {
 public:
  // Opens the package file at `path`. Throws UsdError naming the file for a
  // file that is missing, not a zip archive, or corrupt.
  explicit UsdzPackage(const std::string& path, const ReadLimits& limits = {});
  // Opens a package held in memory (a package nested in another);
  // `identifier` names it in errors ("outer.usdz[inner.usdz]").
  UsdzPackage(std::vector<uint8_t> bytes, std::string identifier, const ReadLimits& limits = {});
  ~UsdzPackage();
  UsdzPackage(const UsdzPackage&) = delete;
  UsdzPackage& operator=(const UsdzPackage&) = delete;

  const std::string& identifier() const { return identifier_; }
  // Every file entry in archive order (folders left out).
  const std::vector<std::string>& entries() const { return entries_; }
  bool contains(const std::string& entry) const;
  // The root layer: the first entry named .usd, .usda or .usdc ("" if none).
  std::string firstLayer() const;

  // The bytes of `entry`; "a.usdz[b.usdc]" reads b.usdc inside the nested
  // package a.usdz. Throws UsdError naming the package and entry for a
  // missing entry, an encrypted one, one larger than limits.maxFileBytes, a
  // stored one larger than the package, a compressed one that inflates past
  // limits.maxInflatedEntryBytes, or data that does not decompress to its
  // recorded size and checksum. Memory stays within the recorded size (so
  // within the limit): the data is read in chunks and refused as soon as it
  // passes the size its header records.
  std::vector<uint8_t> read(const std::string& entry) const;

  // The entry that `assetPath`, written in the layer `fromEntry`, names:
  // relative to fromEntry's folder ("./" and ".." resolved). "" when it
  // leaves the package, is absolute, or names no entry.
  std::string resolve(const std::string& fromEntry, const std::string& assetPath) const;

 private:
  void open(zip* archive);
  // `inflated` (when given) is set to whether the entry was compressed.
  std::vector<uint8_t> readOwnEntry(const std::string& entry, bool* inflated = nullptr) const;

  std::string identifier_;
  ReadLimits limits_;
  // A nested package read from `entry` of this one: its compressed entries
  // share the inflation limit with the bytes inflated to reach it.
  std::unique_ptr<UsdzPackage> nested(const std::string& entry) const;

  std::vector<uint8_t> bytes_;  // the package's bytes when opened from memory
  uint64_t archiveBytes_ = 0;   // the package's size: a stored entry cannot be larger
  zip* archive_ = nullptr;
  std::vector<std::string> entries_;
};

// readPackagedLayer (declared in layer_io.h, defined in usdz_layer.cpp)
// reads one layer of a package through this class.

}  // namespace sdg::usd
