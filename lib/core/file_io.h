#pragma once
// Writing files so that a reader never sees a half-written one: bytes go to
// "<name>.tmp-<pid>" in the same folder, are flushed, then renamed over the
// final name. Errors (full disk, read-only folder) throw RunError naming the
// file; the temporary is removed.
#include <cstdint>
#include <span>
#include <string>

namespace sdg {

// Synced: the bytes reach the disk (fdatasync) before the rename, so the
// final name never points at lost data after a power cut; frames use it.
enum class Durability { Flushed, Synced };

void writeFileAtomic(const std::string& path, std::span<const uint8_t> bytes,
                     Durability durability = Durability::Flushed);
void writeFileAtomic(const std::string& path, const std::string& text, Durability durability = Durability::Flushed);
// fsync of a folder, so renames in it are durable too.
void syncDirectory(const std::string& dir);

// "fnv1a64:<16 hex digits>" of the file's bytes ("" when unreadable): a
// quick fingerprint for summaries (a run's identity uses SHA-256).
std::string fileHash(const std::string& path);

}  // namespace sdg
