#pragma once
// Writing files so that a reader never sees a half-written one: bytes go to
// "<name>.tmp-<pid>" in the same folder, are flushed, then renamed over the
// final name. Errors (full disk, read-only folder) throw RunError naming the
// file; the temporary is removed.
#include <cstdint>
#include <span>
#include <string>

namespace sdg {

void writeFileAtomic(const std::string& path, std::span<const uint8_t> bytes);
void writeFileAtomic(const std::string& path, const std::string& text);

}  // namespace sdg
