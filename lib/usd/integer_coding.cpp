#include "usd/integer_coding.h"

#include <limits>
#include <map>
#include <string>
#include <type_traits>

#include "usd/lz4_chunks.h"

namespace sdg::usd {

namespace {

// The signed types of one integer width and its small and medium forms.
template <class Int>
struct Widths {
  using Signed = std::make_signed_t<Int>;
  using Unsigned = std::make_unsigned_t<Int>;
  using Small = std::conditional_t<sizeof(Int) == 4, int8_t, int16_t>;
  using Medium = std::conditional_t<sizeof(Int) == 4, int16_t, int32_t>;
};

enum Code : uint8_t { kCommon = 0, kSmall = 1, kMedium = 2, kFull = 3 };

uint64_t codesBytes(uint64_t count) { return (count * 2 + 7) / 8; }

template <class T>
T loadLE(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

}  // namespace

uint64_t maxEncodedIntegersSize(uint64_t count, int width) {
  return count == 0 ? 0 : uint64_t(width) + codesBytes(count) + count * uint64_t(width);
}

uint64_t minEncodedIntegersSize(uint64_t count, int width) {
  return count == 0 ? 0 : uint64_t(width) + codesBytes(count);
}

template <class Int>
void decodeIntegers(std::span<const uint8_t> encoded, std::span<Int> out) {
  using W = Widths<Int>;
  using U = typename W::Unsigned;
  const uint64_t count = out.size();
  if (count == 0) return;
  if (encoded.size() < minEncodedIntegersSize(count, sizeof(Int)))
    throw CodingError("integer coding of " + std::to_string(count) + " values needs at least " +
                      std::to_string(minEncodedIntegersSize(count, sizeof(Int))) + " bytes, has " +
                      std::to_string(encoded.size()));
  const uint8_t* p = encoded.data();
  const uint8_t* end = p + encoded.size();
  const U common = U(loadLE<typename W::Signed>(p));
  const uint8_t* codes = p + sizeof(Int);
  const uint8_t* vints = codes + codesBytes(count);
  // Differences are summed in the unsigned type: wrapping, as two's complement.
  U previous = 0;
  for (uint64_t i = 0; i < count; ++i) {
    auto code = Code((codes[i / 4] >> (2 * (i % 4))) & 3);
    U delta;
    size_t size = code == kCommon ? 0 : code == kSmall ? sizeof(typename W::Small)
                                    : code == kMedium  ? sizeof(typename W::Medium)
                                                       : sizeof(Int);
    if (size_t(end - vints) < size)
      throw CodingError("integer coding ends early at value " + std::to_string(i) + " of " +
                        std::to_string(count));
    switch (code) {
      case kCommon: delta = common; break;
      case kSmall: delta = U(typename W::Signed(loadLE<typename W::Small>(vints))); break;
      case kMedium: delta = U(typename W::Signed(loadLE<typename W::Medium>(vints))); break;
      default: delta = U(loadLE<typename W::Signed>(vints)); break;
    }
    vints += size;
    previous = U(previous + delta);
    out[i] = Int(previous);
  }
}

template <class Int>
void decompressIntegers(std::span<const uint8_t> framed, std::span<Int> out) {
  if (out.empty()) return;
  const uint64_t maxSize = maxEncodedIntegersSize(out.size(), sizeof(Int));
  if (minEncodedIntegersSize(out.size(), sizeof(Int)) > maxLz4Expansion(framed.size()))
    throw CodingError(std::to_string(out.size()) + " compressed integers cannot fit in " +
                      std::to_string(framed.size()) + " bytes");
  std::vector<uint8_t> encoded(maxSize);
  size_t n = decompressLz4Chunks(framed, encoded);
  decodeIntegers<Int>(std::span<const uint8_t>(encoded.data(), n), out);
}

template <class Int>
std::vector<Int> readCompressedIntegers(ByteCursor& in, uint64_t count, uint64_t maxCount, const char* what) {
  auto size = in.read<uint64_t>(what);
  auto framed = in.take(size, what);
  if (count > maxCount)
    throw CodingError(std::string(what) + ": " + std::to_string(count) + " entries exceed the limit of " +
                      std::to_string(maxCount));
  if (minEncodedIntegersSize(count, sizeof(Int)) > maxLz4Expansion(size))
    throw CodingError(std::string(what) + ": " + std::to_string(count) + " entries cannot be coded in " +
                      std::to_string(size) + " bytes");
  std::vector<Int> values(count);
  decompressIntegers<Int>(framed, values);
  return values;
}

template <class Int>
std::vector<uint8_t> encodeIntegers(std::span<const Int> values) {
  using W = Widths<Int>;
  using S = typename W::Signed;
  using U = typename W::Unsigned;
  std::vector<uint8_t> out;
  if (values.empty()) return out;
  // The most common difference (the larger one on a tie, as USD picks).
  std::map<S, size_t> counts;
  U previous = 0;
  for (Int v : values) {
    ++counts[S(U(U(v) - previous))];
    previous = U(v);
  }
  S common = 0;
  size_t best = 0;
  for (auto [value, n] : counts)
    if (n >= best) common = value, best = n;

  auto append = [&out](auto v) {
    size_t at = out.size();
    out.resize(at + sizeof(v));
    std::memcpy(out.data() + at, &v, sizeof(v));
  };
  append(common);
  const size_t codesAt = out.size();
  out.resize(codesAt + codesBytes(values.size()), 0);
  previous = 0;
  for (size_t i = 0; i < values.size(); ++i) {
    S delta = S(U(U(values[i]) - previous));
    previous = U(values[i]);
    using Small = typename W::Small;
    using Medium = typename W::Medium;
    Code code;
    if (delta == common) {
      code = kCommon;
    } else if (delta >= std::numeric_limits<Small>::min() && delta <= std::numeric_limits<Small>::max()) {
      code = kSmall, append(Small(delta));
    } else if (delta >= std::numeric_limits<Medium>::min() && delta <= std::numeric_limits<Medium>::max()) {
      code = kMedium, append(Medium(delta));
    } else {
      code = kFull, append(delta);
    }
    out[codesAt + i / 4] = uint8_t(out[codesAt + i / 4] | (code << (2 * (i % 4))));
  }
  return out;
}

#define SDG_INTEGER_CODING(Int)                                                              \
  template void decodeIntegers<Int>(std::span<const uint8_t>, std::span<Int>);              \
  template void decompressIntegers<Int>(std::span<const uint8_t>, std::span<Int>);          \
  template std::vector<uint8_t> encodeIntegers<Int>(std::span<const Int>);                  \
  template std::vector<Int> readCompressedIntegers<Int>(ByteCursor&, uint64_t, uint64_t, const char*);
SDG_INTEGER_CODING(int32_t)
SDG_INTEGER_CODING(uint32_t)
SDG_INTEGER_CODING(int64_t)
SDG_INTEGER_CODING(uint64_t)
#undef SDG_INTEGER_CODING

}  // namespace sdg::usd
