#include "writers/manifest.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>
#include <openssl/evp.h>

#include "core/diagnostics.h"
#include "core/file_io.h"
#include "writers/output_files.h"

namespace sdg {
namespace fs = std::filesystem;

namespace {

class Sha256 {
 public:
  Sha256() : ctx_(EVP_MD_CTX_new()) {
    if (!ctx_ || EVP_DigestInit_ex(ctx_, EVP_sha256(), nullptr) != 1) throw RunError("libcrypto: SHA-256 unavailable");
  }
  ~Sha256() { EVP_MD_CTX_free(ctx_); }
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void update(const void* data, size_t size) { EVP_DigestUpdate(ctx_, data, size); }
  std::string hex() {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int size = 0;
    EVP_DigestFinal_ex(ctx_, digest, &size);
    static const char* digits = "0123456789abcdef";
    std::string out;
    for (unsigned i = 0; i < size; ++i) out += digits[digest[i] >> 4], out += digits[digest[i] & 15];
    return out;
  }

 private:
  EVP_MD_CTX* ctx_;
};

bool parseLine(const std::string& line, ManifestEntry& entry) {
  nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("frame") || !j.contains("files")) return false;
  try {
    entry.frame = j.at("frame").get<uint64_t>();
    entry.product = j.value("product", 0u);
    entry.files.clear();
    for (const auto& f : j.at("files"))
      entry.files.push_back({f.at("path").get<std::string>(), f.at("bytes").get<uint64_t>(),
                             f.at("sha256").get<std::string>()});
  } catch (const nlohmann::json::exception&) {
    return false;
  }
  return true;
}

}  // namespace

std::string sha256Hex(std::span<const uint8_t> bytes) {
  Sha256 h;
  h.update(bytes.data(), bytes.size());
  return h.hex();
}

std::string sha256OfFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  Sha256 h;
  std::vector<char> buffer(1 << 16);
  while (in) {
    in.read(buffer.data(), std::streamsize(buffer.size()));
    h.update(buffer.data(), size_t(in.gcount()));
  }
  return h.hex();
}

std::string ManifestEntry::toLine() const {
  nlohmann::ordered_json j;
  j["frame"] = frame;
  j["product"] = product;
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const ManifestFile& f : files) list.push_back({{"path", f.path}, {"bytes", f.bytes}, {"sha256", f.sha256}});
  j["files"] = std::move(list);
  return j.dump() + "\n";
}

ManifestWriter::ManifestWriter(std::string path, std::string dataDir) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) throw RunError("cannot write the manifest " + path_ + ": " + std::strerror(errno));
  dataFd_ = ::open(dataDir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dataFd_ < 0) {
    const int error = errno;
    ::close(fd_);
    throw RunError("cannot open the output folder " + dataDir + ": " + std::strerror(error));
  }
  // A crash during an append can leave a line without its newline: cut it,
  // its frame is simply redone.
  off_t size = ::lseek(fd_, 0, SEEK_END);
  off_t keep = size;
  char c = 0;
  while (keep > 0 && ::pread(fd_, &c, 1, keep - 1) == 1 && c != '\n') --keep;
  if (keep != size && ::ftruncate(fd_, keep) != 0)
    throw RunError("cannot repair the manifest " + path_ + ": " + std::strerror(errno));
}

ManifestWriter::~ManifestWriter() {
  // No flush here: a run that ends well flushes; one that fails keeps what
  // its last flush made durable (keepFinishedFramesAfterFailure flushes too).
  if (fd_ >= 0) ::close(fd_);
  if (dataFd_ >= 0) ::close(dataFd_);
}

void ManifestWriter::commit(uint64_t sequence, ManifestEntry entry) {
  std::lock_guard lock(mutex_);
  pending_.emplace(sequence, std::move(entry));
  for (auto it = pending_.find(next_); it != pending_.end(); it = pending_.find(next_)) {
    if (batchLines_ == 0) batchStart_ = std::chrono::steady_clock::now();
    batch_ += it->second.toLine();
    ++batchLines_;
    pending_.erase(it);
    ++next_;
  }
  if (batchLines_ >= kGroupFrames ||
      (batchLines_ > 0 && std::chrono::steady_clock::now() - batchStart_ >= std::chrono::milliseconds(kGroupMillis)))
    flushLocked();
}

void ManifestWriter::flush() {
  std::lock_guard lock(mutex_);
  flushLocked();
}

void ManifestWriter::flushLocked() {
  if (batchLines_ == 0) return;
  // Every file the batch lists (and its folder entry) is durable first.
  if (::syncfs(dataFd_) != 0)
    throw RunError("cannot sync the output folder's file system (for " + path_ + "): " + std::strerror(errno));
  size_t done = 0;
  while (done < batch_.size()) {
    const ssize_t n = ::write(fd_, batch_.data() + done, batch_.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw RunError("cannot write the manifest " + path_ + ": " + std::strerror(errno));
    }
    done += size_t(n);
  }
  if (::fdatasync(fd_) != 0) throw RunError("cannot write the manifest " + path_ + ": " + std::strerror(errno));
  batch_.clear();
  batchLines_ = 0;
}

ManifestIndex indexManifests(const std::string& dir) {
  ManifestIndex index;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("manifest", 0) == 0 && e.path().extension() == ".jsonl") index.files.push_back(e.path().string());
  }
  std::sort(index.files.begin(), index.files.end());
  ManifestEntry entry;
  std::string line;
  for (uint32_t file = 0; file < index.files.size(); ++file) {
    std::ifstream in(index.files[file], std::ios::binary);
    uint64_t offset = 0;
    while (std::getline(in, line)) {
      // A last line without its '\n' is torn (a crash mid-append): not counted.
      const bool complete = !in.eof();
      if (complete && parseLine(line, entry)) index.lines.push_back({entry.frame, entry.product, file, offset, line.size()});
      offset += line.size() + 1;
    }
  }
  // Lines were gathered in file and line order; a stable sort keeps that
  // order within a key, whose last line wins.
  auto key = [](const ManifestIndex::Line& l) { return std::pair(l.frame, l.product); };
  std::stable_sort(index.lines.begin(), index.lines.end(),
                   [&](const ManifestIndex::Line& a, const ManifestIndex::Line& b) { return key(a) < key(b); });
  std::vector<ManifestIndex::Line> unique;
  unique.reserve(index.lines.size());
  for (size_t i = 0; i < index.lines.size(); ++i)
    if (i + 1 == index.lines.size() || key(index.lines[i + 1]) != key(index.lines[i])) unique.push_back(index.lines[i]);
  index.lines = std::move(unique);
  return index;
}

void forEachManifestEntry(const ManifestIndex& index, const std::function<void(const ManifestEntry&)>& visit) {
  std::vector<std::ifstream> files;
  files.reserve(index.files.size());
  for (const std::string& path : index.files) files.emplace_back(path, std::ios::binary);
  ManifestEntry entry;
  std::string line;
  for (const ManifestIndex::Line& l : index.lines) {
    std::ifstream& in = files[l.file];
    line.resize(l.length);
    in.seekg(std::streamoff(l.offset));
    if (!in.read(line.data(), std::streamsize(l.length)) || !parseLine(line, entry))
      throw RunError(index.files[l.file] + ": changed while it was read (line at byte " + std::to_string(l.offset) +
                     ")");
    visit(entry);
  }
}

std::vector<ManifestEntry> readManifests(const std::string& dir) {
  std::vector<ManifestEntry> out;
  forEachManifestEntry(indexManifests(dir), [&](const ManifestEntry& e) { out.push_back(e); });
  return out;
}

void writeCanonicalManifest(const std::string& dir, const ManifestIndex& index) {
  AtomicFileWriter out((fs::path(dir) / "manifest.jsonl").string());
  forEachManifestEntry(index, [&](const ManifestEntry& e) { out.append(e.toLine()); });
  out.commit();
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("manifest.", 0) == 0 && name != "manifest.jsonl" && e.path().extension() == ".jsonl")
      fs::remove(e.path(), ec);
  }
}

size_t countDatasetFiles(const std::string& dir) {
  size_t count = 0;
  std::error_code walkError;
  for (auto it = fs::recursive_directory_iterator(dir, walkError); !walkError && it != fs::recursive_directory_iterator();
       it.increment(walkError)) {
    if (it.depth() == 0 && it->path().filename() == kPartsFolder) {
      it.disable_recursion_pending();
      continue;
    }
    std::error_code ec;
    if (it->is_regular_file(ec)) ++count;
  }
  return count;
}

VerifyReport verifyManifest(const std::string& dir, const std::vector<ManifestEntry>& entries) {
  VerifyReport report;
  report.folderFiles = countDatasetFiles(dir);
  for (const ManifestEntry& e : entries)
    for (const ManifestFile& f : e.files) {
      ++report.files;
      if (f.path.starts_with(std::string(kPartsFolder) + "/")) ++report.hiddenParts;
      const std::string path = (fs::path(dir) / f.path).string();
      std::error_code ec;
      if (!fs::exists(path, ec)) {
        report.problems.push_back(f.path + ": missing");
        continue;
      }
      if (fs::file_size(path, ec) != f.bytes) {
        report.problems.push_back(f.path + ": " + std::to_string(fs::file_size(path, ec)) + " bytes, the manifest says " +
                                  std::to_string(f.bytes));
        continue;
      }
      if (sha256OfFile(path) != f.sha256) report.problems.push_back(f.path + ": sha256 differs from the manifest");
    }
  return report;
}

}  // namespace sdg
