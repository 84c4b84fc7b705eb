#pragma once
// Bounds-checked reading of the little-endian bytes of a crate file. Every
// read of the crate reader goes through a ByteCursor that is confined to one
// region (a section, or the whole file for out-of-line values), so a lying
// offset or count fails here with a CodingError instead of reading past the
// buffer; the crate reader adds the file and section to the message.
#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace sdg::usd {

static_assert(std::endian::native == std::endian::little,
              "crate files are little-endian and are read by copying bytes");

// A malformed encoding: the crate reader turns it into a UsdError naming the
// file and the section being read.
class CodingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ByteCursor {
 public:
  // Reads bytes[begin, end); the caller has checked end <= bytes.size().
  ByteCursor(std::span<const uint8_t> bytes, uint64_t begin, uint64_t end)
      : bytes_(bytes), begin_(begin), end_(end), pos_(begin) {}
  explicit ByteCursor(std::span<const uint8_t> bytes) : ByteCursor(bytes, 0, bytes.size()) {}

  uint64_t tell() const { return pos_; }
  uint64_t end() const { return end_; }
  uint64_t remaining() const { return end_ - pos_; }

  void seek(uint64_t pos) {
    if (pos < begin_ || pos > end_)
      throw CodingError("offset " + std::to_string(pos) + " lies outside bytes " + std::to_string(begin_) +
                        ".." + std::to_string(end_));
    pos_ = pos;
  }

  // Skips `n` bytes and returns them.
  std::span<const uint8_t> take(uint64_t n, const char* what) {
    require(n, what);
    auto s = bytes_.subspan(pos_, n);
    pos_ += n;
    return s;
  }

  template <class T>
  T read(const char* what) {
    static_assert(std::is_trivially_copyable_v<T>);
    require(sizeof(T), what);
    T value;
    std::memcpy(&value, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }

  // A count of items of at least `minItemBytes` each that must still fit in
  // the region (so a huge count fails before anything is allocated).
  uint64_t readCount(const char* what, uint64_t minItemBytes) {
    auto n = read<uint64_t>(what);
    if (minItemBytes > 0 && n > remaining() / minItemBytes)
      throw CodingError(std::string(what) + " claims " + std::to_string(n) + " items of at least " +
                        std::to_string(minItemBytes) + " bytes, but only " + std::to_string(remaining()) +
                        " bytes remain");
    return n;
  }

 private:
  void require(uint64_t n, const char* what) const {
    if (n > end_ - pos_)
      throw CodingError(std::string(what) + " needs " + std::to_string(n) + " bytes at offset " +
                        std::to_string(pos_) + ", but only " + std::to_string(end_ - pos_) + " remain");
  }

  std::span<const uint8_t> bytes_;
  uint64_t begin_, end_, pos_;
};

}  // namespace sdg::usd
