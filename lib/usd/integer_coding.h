#pragma once
// The integer coding of crate files (USD's Usd_IntegerCompression): a list of
// 32- or 64-bit integers is stored as the differences between neighbours;
// the most common difference is written once, then a 2-bit code per integer
// (common / small / medium / full width), then the small (8- or 16-bit),
// medium (16- or 32-bit) and full-width differences in order; the whole
// encoding is then LZ4-framed (lz4_chunks.h). Crate files use it for the
// structural sections and for int, uint, int64 and uint64 arrays (and for
// float arrays whose values are all integers or few distinct values).
#include <cstdint>
#include <span>
#include <vector>

#include "usd/crate_bytes.h"

namespace sdg::usd {

// The largest encoding of `count` integers of `width` bytes (4 or 8).
uint64_t maxEncodedIntegersSize(uint64_t count, int width);
// The smallest: the common value and the codes (every integer common).
uint64_t minEncodedIntegersSize(uint64_t count, int width);

// Decodes `out.size()` integers from an (unframed) encoding; throws
// CodingError when the encoding ends early. Int: int32_t, uint32_t, int64_t
// or uint64_t (sums wrap as in two's complement).
template <class Int>
void decodeIntegers(std::span<const uint8_t> encoded, std::span<Int> out);

// Decodes `out.size()` integers from LZ4-framed data of a crate file.
template <class Int>
void decompressIntegers(std::span<const uint8_t> framed, std::span<Int> out);

// Reads a compressed integer stream of a crate file at `in`: its byte count,
// then the framed coding of `count` integers. Refuses a count above
// `maxCount` or one that the stream's size cannot hold before allocating.
template <class Int>
std::vector<Int> readCompressedIntegers(ByteCursor& in, uint64_t count, uint64_t maxCount, const char* what);

// The inverse of decodeIntegers (tests build crate files with it).
template <class Int>
std::vector<uint8_t> encodeIntegers(std::span<const Int> values);

}  // namespace sdg::usd
