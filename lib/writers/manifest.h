#pragma once
// <out>/manifest.jsonl: one JSON line per finished (frame, render product)
// listing its files with their size and SHA-256 (OpenSSL's libcrypto). A
// line is appended only after its files are durable (written, fsynced and
// renamed), so after a crash every listed file is complete; --resume keeps
// the frames whose files still match and `sdgbehave verify` re-checks them.
// Lines are committed in submission order, whatever order the write
// threads finish in, so the file's bytes do not depend on the thread count.
#include <cstdint>
#include <chrono>
#include <functional>
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

// Group commit: a frame's files are written (atomically renamed, not synced
// one by one) before commit(); lines wait in sequence order until a batch
// of kGroupFrames lines or kGroupMillis is ready, then one syncfs() of the
// output's file system makes every file written so far durable, and only
// then are the batch's lines appended and the manifest synced. So a line is
// never on disk before its files (a crash loses at most the last batch's
// lines, whose frames --resume redoes), and processes sharing one disk pay
// one sync per batch instead of two per file.
class ManifestWriter {
 public:
  static constexpr size_t kGroupFrames = 64;
  static constexpr int kGroupMillis = 250;

  // Opens `path` for appending; a torn last line (a crash mid-append) is cut.
  // `dataDir` is the folder whose files the lines list (its file system is synced).
  ManifestWriter(std::string path, std::string dataDir);
  ~ManifestWriter();
  ManifestWriter(const ManifestWriter&) = delete;
  ManifestWriter& operator=(const ManifestWriter&) = delete;

  // Called by writer threads when job `sequence` (0, 1, 2, ... in
  // submission order) has written its files; lines go out in sequence order.
  void commit(uint64_t sequence, ManifestEntry entry);
  // Makes every line committed so far durable (the end of a run, a failure).
  void flush();

 private:
  void flushLocked();
  std::string path_;
  int fd_ = -1;
  int dataFd_ = -1;
  std::mutex mutex_;
  uint64_t next_ = 0;
  std::map<uint64_t, ManifestEntry> pending_;
  std::string batch_;        // lines in order, not yet durable
  size_t batchLines_ = 0;
  std::chrono::steady_clock::time_point batchStart_;
};

// Where the line that counts for each (frame, product) lies among the
// complete lines of a folder's manifest*.jsonl files: 32 bytes a line, so
// finishing, resuming or merging a long run never holds its manifest in
// memory (a 100,000-frame run's lines are tens of megabytes as entries).
struct ManifestIndex {
  struct Line {
    uint64_t frame = 0;
    uint32_t product = 0;
    uint32_t file = 0;    // into files
    uint64_t offset = 0;  // of the line's first byte
    uint64_t length = 0;  // without its '\n'
  };
  std::vector<std::string> files;  // the manifests, sorted by name
  std::vector<Line> lines;         // sorted by (frame, product); a later line for the same key wins
};
ManifestIndex indexManifests(const std::string& dir);
// Calls `visit` with each indexed line's entry in order, one entry in memory at a time.
void forEachManifestEntry(const ManifestIndex& index, const std::function<void(const ManifestEntry&)>& visit);
// Every entry at once (verify's report lists them; small folders).
std::vector<ManifestEntry> readManifests(const std::string& dir);
// Rewrites manifest.jsonl sorted and without duplicates, streaming, and
// removes the per-shard manifests it replaces.
void writeCanonicalManifest(const std::string& dir, const ManifestIndex& index);

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
