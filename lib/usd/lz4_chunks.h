#pragma once
// USD's framing of LZ4 data (TfFastCompression), used by crate files for
// tokens, field value reps and every compressed integer stream: one leading
// byte, 0 for a single raw LZ4 block filling the rest of the buffer, or a
// chunk count n (1..127) followed by n chunks, each an int32 byte count and
// an LZ4 block of at most LZ4_MAX_INPUT_SIZE decompressed bytes.
// Decompression goes through Debian's liblz4 (LZ4_decompress_safe), which
// never writes past the output it is given.
#include <cstdint>
#include <span>
#include <vector>

#include "usd/crate_bytes.h"

namespace sdg::usd {

// Decompresses `framed` into `out` and returns the number of bytes written
// (at most out.size()). Throws CodingError for a bad chunk count, a chunk
// size that overruns the input, corrupt LZ4 data or output that would not
// fit in `out`.
size_t decompressLz4Chunks(std::span<const uint8_t> framed, std::span<uint8_t> out);

// The inverse (used by tests that build crate files by hand).
std::vector<uint8_t> compressLz4Chunks(std::span<const uint8_t> input);

// How many bytes LZ4 data of `compressedBytes` can expand to at most (LZ4's
// best ratio is about 255:1): a claimed decompressed size above this is a lie
// and is refused before anything is allocated.
inline uint64_t maxLz4Expansion(uint64_t compressedBytes) { return compressedBytes * 255 + 64; }

}  // namespace sdg::usd
