#pragma once
// What both image readers share (assets/image.cpp, which decodes plain PNGs
// with libpng, and the OpenImageIO module, assets/image_oiio.cpp): the
// encoded bytes of a file or of memory, the size limits, and the checks of
// a PNG's framing made before libpng sees it. Header-only, so the module
// links nothing of sdgbehave's.
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "assets/image.h"

namespace sdg::image_framing {

// An unreadable image; its text starts with the file's (or memory's) name.
struct ImageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] inline void fail(const std::string& name, const std::string& what) {
  throw ImageError(name + ": " + what);
}

// The encoded bytes: a file, or memory standing for the file `name`.
class Source {
 public:
  // Throws ImageError when the file is missing or cannot be opened.
  explicit Source(const std::string& path) : name_(path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) fail(path, "not found");
    if (std::filesystem::is_directory(path, ec)) fail(path, "is a folder, not an image file");
    file_.open(path, std::ios::binary);
    if (!file_) fail(path, std::string("cannot be opened: ") + std::strerror(errno));
  }
  Source(const void* bytes, size_t size, const std::string& name)
      : name_(name), bytes_(static_cast<const unsigned char*>(bytes)), size_(size), inMemory_(true) {}

  const std::string& name() const { return name_; }
  bool inMemory() const { return inMemory_; }
  const unsigned char* bytes() const { return bytes_; }
  size_t size() const { return size_; }

  // Up to `n` bytes from `offset` into `dst`; fewer where the data ends.
  size_t readAt(uint64_t offset, size_t n, unsigned char* dst) {
    if (inMemory_) {
      if (offset >= size_) return 0;
      n = std::min<size_t>(n, size_ - size_t(offset));
      std::memcpy(dst, bytes_ + offset, n);
      return n;
    }
    file_.clear();
    file_.seekg(std::streamoff(offset));
    file_.read(reinterpret_cast<char*>(dst), std::streamsize(n));
    return size_t(file_.gcount());
  }
  bool readAll(uint64_t offset, size_t n, unsigned char* dst) { return readAt(offset, n, dst) == n; }

 private:
  std::string name_;
  const unsigned char* bytes_ = nullptr;
  size_t size_ = 0;
  bool inMemory_ = false;
  std::ifstream file_;
};

inline uint32_t bigEndian32(const unsigned char* b) {
  return uint32_t(b[0]) << 24 | uint32_t(b[1]) << 16 | uint32_t(b[2]) << 8 | uint32_t(b[3]);
}

[[noreturn]] inline void corrupt(const Source& src, const std::string& format, const std::string& what) {
  fail(src.name(), "the " + format + " is corrupt: " + what);
}

[[noreturn]] inline void truncated(const Source& src, const std::string& format, const std::string& where) {
  fail(src.name(), "the " + format + " is truncated: the data ends " + where);
}

// Refuses an image of w x h pixels over the limits.
inline void checkLimits(const std::string& name, const std::string& format, uint64_t w, uint64_t h) {
  if (w <= kMaxTextureSide && h <= kMaxTextureSide && w * h <= kMaxTexturePixels) return;
  fail(name, "the " + format + " is too large: its header declares " + std::to_string(w) + " x " + std::to_string(h) +
                 " pixels; images are limited to " + std::to_string(kMaxTextureSide) + " a side and " +
                 std::to_string(kMaxTexturePixels >> 20) + " Mpixel");
}

// The 13 bytes of IHDR: a size within the limits and a pixel format PNG has.
inline void checkPngHeader(const Source& src, const unsigned char* ihdr) {
  const uint32_t w = bigEndian32(ihdr), h = bigEndian32(ihdr + 4);
  if (w == 0 || h == 0) corrupt(src, "PNG", "its header declares no pixels");
  checkLimits(src.name(), "PNG", w, h);
  const int depth = ihdr[8], colour = ihdr[9];
  const bool low = depth == 1 || depth == 2 || depth == 4, byte = depth == 8, wide = depth == 16;
  const bool valid = colour == 0   ? low || byte || wide
                     : colour == 3 ? low || byte
                                   : (colour == 2 || colour == 4 || colour == 6) && (byte || wide);
  if (!valid) corrupt(src, "PNG", "its header declares an impossible pixel format");
  if (ihdr[10] != 0 || ihdr[11] != 0 || ihdr[12] > 1)
    corrupt(src, "PNG", "its header declares an unknown compression, filter or interlace method");
}

// The CRC of a chunk's type and data, read in blocks; `block` keeps the
// start of the data (IHDR's fields).
inline uLong chunkCrc(Source& src, uint64_t pos, const unsigned char* type, uint32_t length,
               std::vector<unsigned char>& block) {
  uLong crc = crc32(0, type, 4);
  for (uint32_t done = 0; done < length;) {
    const size_t n = src.readAt(pos + 8 + done, std::min<size_t>(block.size(), length - done), block.data());
    crc = crc32(crc, block.data(), uInt(n));
    done += uint32_t(n);
  }
  return crc;
}

// libpng, as OIIO drives it, prints its errors to stderr itself. So what
// libpng would stop at before decoding a pixel is checked here first: the
// signature, IHDR first and sound, only the critical chunks PNG defines
// (PLTE before the pixel data of a palette image, IDAT before IEND), and
// every chunk whole with its critical chunks' checksums intact. That finds
// truncated and damaged files; only a broken compressed stream under
// correct checksums still reaches libpng. Up to the first IDAT for the
// header, to IEND for the pixels.
inline void checkPngFraming(Source& src, bool wholeFile) {
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  unsigned char sig[8];
  if (!src.readAll(0, 8, sig) || !std::equal(sig, sig + 8, kSignature))
    corrupt(src, "PNG", "its first bytes are not the PNG signature");
  std::vector<unsigned char> block(64 << 10);
  bool palette = false, sawPalette = false, sawData = false;
  for (uint64_t pos = 8;;) {
    unsigned char head[8], stored[4];
    if (!src.readAll(pos, 8, head)) truncated(src, "PNG", "before its last chunk (IEND)");
    const uint32_t length = bigEndian32(head);
    const std::string type(reinterpret_cast<const char*>(head + 4), 4);
    if (!std::all_of(type.begin(), type.end(), [](char c) { return std::isalpha(static_cast<unsigned char>(c)); }))
      corrupt(src, "PNG", "no chunk starts where one should, at byte " + std::to_string(pos));
    const bool critical = !(head[4] & 0x20);  // an upper-case first letter
    if ((pos == 8) != (type == "IHDR") || (type == "IHDR" && length != 13))
      corrupt(src, "PNG", "its header chunk (IHDR) is missing, out of place or of the wrong size");
    if (critical && type != "IHDR" && type != "PLTE" && type != "IDAT" && type != "IEND")
      corrupt(src, "PNG", "it has a critical '" + type + "' chunk, which PNG does not define");
    if (type == "PLTE" && (sawData || length == 0 || length % 3 != 0 || length > 768))
      corrupt(src, "PNG", "its palette (PLTE) is out of place or of an impossible length");
    if (type == "IDAT" && palette && !sawPalette) corrupt(src, "PNG", "its palette (PLTE) is missing");
    if (type == "IDAT" && !wholeFile) return;
    if (type == "IEND" && !sawData) corrupt(src, "PNG", "it ends (IEND) before any pixel data (IDAT)");
    if (length > 0x7fffffffu || !src.readAll(pos + 8 + length, 4, stored))
      truncated(src, "PNG", "inside its '" + type + "' chunk");
    if (critical && chunkCrc(src, pos, head + 4, length, block) != bigEndian32(stored))
      corrupt(src, "PNG", "the checksum of its '" + type + "' chunk does not match the chunk's data");
    if (type == "IHDR") {
      checkPngHeader(src, block.data());
      palette = block[9] == 3;
    }
    sawPalette |= type == "PLTE";
    sawData |= type == "IDAT";
    if (type == "IEND") return;
    pos += 12 + uint64_t(length);
  }
}

}  // namespace sdg::image_framing
