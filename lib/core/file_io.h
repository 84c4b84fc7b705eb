#pragma once
// Writing files so that a reader never sees a half-written one: bytes go to
// "<name>.tmp-<pid>" in the same folder, are flushed, then renamed over the
// final name. Errors (full disk, read-only folder) throw RunError naming the
// file; the temporary is removed.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace sdg {

// Synced: the bytes reach the disk (fdatasync) before the rename, so the
// final name never points at lost data after a power cut; frames use it.
enum class Durability { Flushed, Synced };

void writeFileAtomic(const std::string& path, std::span<const uint8_t> bytes,
                     Durability durability = Durability::Flushed);
void writeFileAtomic(const std::string& path, const std::string& text, Durability durability = Durability::Flushed);

// The same guarantee for a file written piece by piece, when its whole text
// would not be held in memory (a long run's canonical manifest). Pieces are
// buffered; a writer destroyed before commit() removes its temporary.
class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(std::string path);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;
  void append(std::span<const uint8_t> bytes);
  void append(std::string_view text);
  void commit(Durability durability = Durability::Flushed);

 private:
  friend void writeFileAtomic(const std::string&, std::span<const uint8_t>, Durability);
  void writeAll(const char* data, size_t size);
  [[noreturn]] void fail(int error);
  std::string path_;
  std::string temporary_;
  int fd_ = -1;
  std::string buffer_;
};
// fsync of a folder, so renames in it are durable too.
void syncDirectory(const std::string& dir);

// "fnv1a64:<16 hex digits>" of the file's bytes ("" when unreadable): a
// quick fingerprint for summaries (a run's identity uses SHA-256).
std::string fileHash(const std::string& path);

}  // namespace sdg
