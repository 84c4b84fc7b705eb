#include "usd/usdz_package.h"

#include <zip.h>

#include <algorithm>
#include <filesystem>

namespace sdg::usd {

namespace {

[[noreturn]] void packageError(const std::string& identifier, const std::string& what) {
  throw usdErrorAt(SourceLoc(identifier, 0, 0), "usdz package: " + what);
}

bool hasLayerExtension(const std::string& name) {
  auto dot = name.rfind('.');
  if (dot == std::string::npos) return false;
  std::string ext = name.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == "usd" || ext == "usda" || ext == "usdc";
}

// "outer.usdz[inner/path]" -> ("outer.usdz", "inner/path"); no bracket -> (entry, "").
std::pair<std::string, std::string> splitNested(const std::string& entry) {
  auto open = entry.find('[');
  if (open == std::string::npos || entry.back() != ']') return {entry, ""};
  return {entry.substr(0, open), entry.substr(open + 1, entry.size() - open - 2)};
}

// Joins a relative path onto a folder and resolves "." and ".."; "" when
// ".." climbs out of the package.
std::string normalize(const std::string& folder, const std::string& relative) {
  std::vector<std::string> parts;
  auto push = [&parts](const std::string& path) {
    size_t start = 0;
    while (start <= path.size()) {
      size_t slash = path.find('/', start);
      if (slash == std::string::npos) slash = path.size();
      std::string part = path.substr(start, slash - start);
      if (part == "..") {
        if (parts.empty()) return false;
        parts.pop_back();
      } else if (!part.empty() && part != ".") {
        parts.push_back(part);
      }
      start = slash + 1;
    }
    return true;
  };
  if (!push(folder) || !push(relative)) return "";
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : "/") + p;
  return out;
}

}  // namespace

UsdzPackage::UsdzPackage(const std::string& path, const ReadLimits& limits) : identifier_(path), limits_(limits) {
  int error = 0;
  zip_t* archive = zip_open(path.c_str(), ZIP_RDONLY | ZIP_CHECKCONS, &error);
  if (!archive) {
    zip_error_t ze;
    zip_error_init_with_code(&ze, error);
    std::string message = zip_error_strerror(&ze);
    zip_error_fini(&ze);
    packageError(path, "cannot open it as a zip archive: " + message);
  }
  std::error_code ec;
  archiveBytes_ = std::filesystem::file_size(path, ec);
  if (ec) archiveBytes_ = 0;
  open(archive);
}

UsdzPackage::UsdzPackage(std::vector<uint8_t> bytes, std::string identifier, const ReadLimits& limits)
    : identifier_(std::move(identifier)), limits_(limits), bytes_(std::move(bytes)), archiveBytes_(bytes_.size()) {
  zip_error_t ze;
  zip_error_init(&ze);
  zip_source_t* source = zip_source_buffer_create(bytes_.data(), bytes_.size(), 0, &ze);
  zip_t* archive = source ? zip_open_from_source(source, ZIP_RDONLY | ZIP_CHECKCONS, &ze) : nullptr;
  if (!archive) {
    std::string message = zip_error_strerror(&ze);
    if (source) zip_source_free(source);
    zip_error_fini(&ze);
    packageError(identifier_, "cannot open it as a zip archive: " + message);
  }
  zip_error_fini(&ze);
  open(archive);
}

UsdzPackage::~UsdzPackage() {
  if (archive_) zip_discard(archive_);
}

void UsdzPackage::open(zip_t* archive) {
  archive_ = archive;
  zip_int64_t count = zip_get_num_entries(archive_, 0);
  if (count < 0) packageError(identifier_, "cannot list its entries");
  for (zip_int64_t i = 0; i < count; ++i) {
    const char* name = zip_get_name(archive_, zip_uint64_t(i), ZIP_FL_ENC_GUESS);
    if (!name) packageError(identifier_, "entry " + std::to_string(i) + " has no readable name");
    std::string s = name;
    if (!s.empty() && s.back() != '/') entries_.push_back(std::move(s));
  }
}

bool UsdzPackage::contains(const std::string& entry) const {
  return std::find(entries_.begin(), entries_.end(), entry) != entries_.end();
}

std::string UsdzPackage::firstLayer() const {
  for (const auto& e : entries_)
    if (hasLayerExtension(e)) return e;
  return "";
}

std::unique_ptr<UsdzPackage> UsdzPackage::nested(const std::string& entry) const {
  if (limits_.maxNesting == 0) packageError(identifier_, "packages nest deeper than the limit");
  bool inflated = false;
  std::vector<uint8_t> bytes = readOwnEntry(entry, &inflated);
  ReadLimits nestedLimits = limits_;
  --nestedLimits.maxNesting;
  // The package's bytes stay in memory while its entries are read: a chain
  // of packages, each inflating to the limit, must not hold the limit at
  // every level.
  if (inflated) nestedLimits.maxInflatedEntryBytes -= std::min<uint64_t>(bytes.size(), limits_.maxInflatedEntryBytes);
  return std::make_unique<UsdzPackage>(std::move(bytes), identifier_ + "[" + entry + "]", nestedLimits);
}

std::vector<uint8_t> UsdzPackage::read(const std::string& entry) const {
  auto [outer, inner] = splitNested(entry);
  if (inner.empty()) return readOwnEntry(entry);
  return nested(outer)->read(inner);
}

std::vector<uint8_t> UsdzPackage::readOwnEntry(const std::string& entry, bool* inflated) const {
  const std::string where = "entry '" + entry + "'";
  zip_int64_t index = zip_name_locate(archive_, entry.c_str(), ZIP_FL_ENC_GUESS);
  if (index < 0 || !contains(entry)) packageError(identifier_, where + " does not exist");
  zip_stat_t st;
  zip_stat_init(&st);
  if (zip_stat_index(archive_, zip_uint64_t(index), 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE))
    packageError(identifier_, where + ": cannot read its size: " + zip_strerror(archive_));
  if ((st.valid & ZIP_STAT_ENCRYPTION_METHOD) && st.encryption_method != ZIP_EM_NONE)
    packageError(identifier_, where + " is encrypted");
  if (st.size > limits_.maxFileBytes)
    packageError(identifier_, where + " has " + std::to_string(st.size) + " bytes, more than the limit of " +
                                  std::to_string(limits_.maxFileBytes));
  const bool stored = !(st.valid & ZIP_STAT_COMP_METHOD) || st.comp_method == ZIP_CM_STORE;
  if (!stored && !zip_compression_method_supported(st.comp_method, 0))
    packageError(identifier_, where + " is compressed with method " + std::to_string(st.comp_method) +
                                  ", which libzip cannot decompress (usdz entries are stored uncompressed)");
  // The sizes the header records, checked before anything is allocated: a
  // stored entry is its own bytes in the package, a compressed one inflates
  // to at most the limit (a 1 MB package must not claim a 1 GiB entry).
  if (stored && archiveBytes_ != 0 && st.size > archiveBytes_)
    packageError(identifier_, where + " records " + std::to_string(st.size) + " stored bytes, but the package has " +
                                  std::to_string(archiveBytes_));
  if (!stored && st.size > limits_.maxInflatedEntryBytes)
    packageError(identifier_, where + " inflates to " + std::to_string(st.size) +
                                  " bytes, more than the limit of " + std::to_string(limits_.maxInflatedEntryBytes) +
                                  " for a compressed entry (ReadLimits::maxInflatedEntryBytes)");
  if (inflated) *inflated = !stored;
  zip_file_t* file = zip_fopen_index(archive_, zip_uint64_t(index), 0);
  if (!file) packageError(identifier_, where + ": cannot open it: " + zip_strerror(archive_));
  // The recorded size is not trusted: read in chunks, the buffer grown only
  // as data arrives and never past the recorded size, and stop at the first
  // byte beyond it. Reading to the end also checks the CRC.
  constexpr size_t kChunk = size_t(1) << 20;
  std::vector<uint8_t> bytes;
  std::vector<uint8_t> chunk(size_t(std::min<uint64_t>(kChunk, st.size + 1)));
  bool overrun = false;
  zip_int64_t n = 0;
  while ((n = zip_fread(file, chunk.data(), chunk.size())) > 0) {
    if (bytes.size() + uint64_t(n) > st.size) {
      overrun = true;
      break;
    }
    if (bytes.capacity() < bytes.size() + size_t(n))
      bytes.reserve(size_t(std::min<uint64_t>(st.size, std::max(bytes.capacity() * 2, bytes.size() + size_t(n)))));
    bytes.insert(bytes.end(), chunk.begin(), chunk.begin() + n);
  }
  std::string fileError = zip_file_strerror(file);
  zip_fclose(file);
  if (overrun)
    packageError(identifier_, where + " inflates past the " + std::to_string(st.size) + " bytes its header records");
  if (n < 0) packageError(identifier_, where + ": cannot read it: " + fileError);
  if (bytes.size() != st.size)
    packageError(identifier_, where + " does not hold the " + std::to_string(st.size) + " bytes its header records");
  return bytes;
}

std::string UsdzPackage::resolve(const std::string& fromEntry, const std::string& assetPath) const {
  if (assetPath.empty() || assetPath[0] == '/' || assetPath.find(':') != std::string::npos) return "";
  auto [outer, inner] = splitNested(fromEntry);
  if (!inner.empty()) {
    if (limits_.maxNesting == 0) return "";
    ReadLimits nestedLimits = limits_;
    --nestedLimits.maxNesting;
    UsdzPackage nested(readOwnEntry(outer), identifier_ + "[" + outer + "]", nestedLimits);
    std::string found = nested.resolve(inner, assetPath);
    return found.empty() ? "" : outer + "[" + found + "]";
  }
  auto slash = fromEntry.rfind('/');
  std::string folder = slash == std::string::npos ? "" : fromEntry.substr(0, slash);
  std::string entry = normalize(folder, assetPath);
  return !entry.empty() && contains(entry) ? entry : "";
}

}  // namespace sdg::usd
