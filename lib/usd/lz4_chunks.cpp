#include "usd/lz4_chunks.h"

#include <lz4.h>

#include <algorithm>
#include <climits>
#include <string>

namespace sdg::usd {

namespace {

constexpr int kMaxChunks = 127;

int decompressBlock(std::span<const uint8_t> block, std::span<uint8_t> out, int chunk) {
  if (block.size() > size_t(INT_MAX))
    throw CodingError("LZ4 chunk " + std::to_string(chunk) + " is larger than LZ4 allows");
  int capacity = int(std::min<size_t>(out.size(), LZ4_MAX_INPUT_SIZE));
  int n = LZ4_decompress_safe(reinterpret_cast<const char*>(block.data()), reinterpret_cast<char*>(out.data()),
                              int(block.size()), capacity);
  if (n < 0)
    throw CodingError("LZ4 chunk " + std::to_string(chunk) + " of " + std::to_string(block.size()) +
                      " bytes is corrupt or decompresses to more than the " + std::to_string(capacity) +
                      " bytes expected");
  return n;
}

}  // namespace

size_t decompressLz4Chunks(std::span<const uint8_t> framed, std::span<uint8_t> out) {
  if (framed.empty()) throw CodingError("LZ4 data is empty (no chunk-count byte)");
  int chunks = framed[0];
  auto rest = framed.subspan(1);
  if (chunks == 0) return size_t(decompressBlock(rest, out, 0));
  if (chunks > kMaxChunks)
    throw CodingError("LZ4 data claims " + std::to_string(chunks) + " chunks (at most " +
                      std::to_string(kMaxChunks) + ")");
  size_t written = 0;
  for (int i = 0; i < chunks; ++i) {
    if (rest.size() < 4)
      throw CodingError("LZ4 chunk " + std::to_string(i) + " of " + std::to_string(chunks) +
                        " is missing its size");
    int32_t size = 0;
    std::memcpy(&size, rest.data(), 4);
    rest = rest.subspan(4);
    if (size < 0 || size_t(size) > rest.size())
      throw CodingError("LZ4 chunk " + std::to_string(i) + " claims " + std::to_string(size) + " bytes, but " +
                        std::to_string(rest.size()) + " remain");
    written += size_t(decompressBlock(rest.first(size_t(size)), out.subspan(written), i));
    rest = rest.subspan(size_t(size));
  }
  return written;
}

std::vector<uint8_t> compressLz4Chunks(std::span<const uint8_t> input) {
  std::vector<uint8_t> out;
  auto compressBlock = [&out](std::span<const uint8_t> block) {
    size_t at = out.size();
    int bound = LZ4_compressBound(int(block.size()));
    out.resize(at + size_t(bound));
    int n = LZ4_compress_default(reinterpret_cast<const char*>(block.data()),
                                 reinterpret_cast<char*>(out.data() + at), int(block.size()), bound);
    out.resize(at + size_t(n));
    return n;
  };
  if (input.size() <= size_t(LZ4_MAX_INPUT_SIZE)) {
    out.push_back(0);
    compressBlock(input);
    return out;
  }
  size_t chunks = (input.size() + LZ4_MAX_INPUT_SIZE - 1) / LZ4_MAX_INPUT_SIZE;
  if (chunks > size_t(kMaxChunks)) throw CodingError("input too large for USD's LZ4 framing");
  out.push_back(uint8_t(chunks));
  for (size_t at = 0; at < input.size(); at += LZ4_MAX_INPUT_SIZE) {
    size_t sizeAt = out.size();
    out.resize(sizeAt + 4);
    int32_t n = compressBlock(input.subspan(at, std::min<size_t>(LZ4_MAX_INPUT_SIZE, input.size() - at)));
    std::memcpy(out.data() + sizeAt, &n, 4);
  }
  return out;
}

}  // namespace sdg::usd
