#pragma once
// <out>/manifest.jsonl: one JSON line per finished (frame, render product)
// listing its files with their size and SHA-256 (OpenSSL's libcrypto). A
// line is appended only after its files are durable (written, fsynced and
// renamed), so after a crash every listed file is complete; --resume keeps
// the frames whose files still match and `sdgbehave verify` re-checks them.
// Lines are committed in submission order, whatever order the write
// threads finish in, so the file's bytes do not depend on the thread count.
#include <cstdint>
#include <map>
#include <mutex>
#include <span>
#include <string>
#include <vector>

namespace sdg {

std::string sha256Hex(std::span<const uint8_t> bytes);
// "" when the file cannot be read.
std::string sha256OfFile(const std::string& path);

struct ManifestFile {
  std::string path;  // relative to the output folder
  uint64_t bytes = 0;
  std::string sha256;
};

struct ManifestEntry {
  uint64_t frame = 0;
  uint32_t product = 0;
  std::vector<ManifestFile> files;
  std::string toLine() const;  // one JSON object and '\n'
};

class ManifestWriter {
 public:
  // Opens `path` for appending; a torn last line (a crash mid-append) is cut.
  explicit ManifestWriter(std::string path);
  ~ManifestWriter();
  ManifestWriter(const ManifestWriter&) = delete;
  ManifestWriter& operator=(const ManifestWriter&) = delete;

  // Called by writer threads when job `sequence` (0, 1, 2, ... in
  // submission order) is durable; lines go out in sequence order.
  void commit(uint64_t sequence, ManifestEntry entry);

 private:
  void append(const ManifestEntry& entry);
  std::string path_;
  int fd_ = -1;
  std::mutex mutex_;
  uint64_t next_ = 0;
  std::map<uint64_t, ManifestEntry> pending_;
};

// Every complete line of every manifest*.jsonl in `dir` (sorted by frame,
// product; a later line for the same frame and product wins).
std::vector<ManifestEntry> readManifests(const std::string& dir);
// Rewrites manifest.jsonl sorted and without duplicates, and removes the
// per-shard manifests it replaces.
void writeCanonicalManifest(const std::string& dir, const std::vector<ManifestEntry>& entries);

struct VerifyReport {
  size_t folderFiles = 0;  // regular files in the folder outside .sdgbehave/: a run's files_written
  size_t files = 0;        // files the manifests list, all checked; of them,
  size_t hiddenParts = 0;  // those below .sdgbehave/ (contact-sheet tiles, COCO fragments)
  std::vector<std::string> problems;  // "path: missing" / "path: sha256 differs" ...
};
VerifyReport verifyManifest(const std::string& dir, const std::vector<ManifestEntry>& entries);
// Regular files below `dir` outside .sdgbehave/: a dataset's files as
// files_written and verify count them.
size_t countDatasetFiles(const std::string& dir);

}  // namespace sdg
