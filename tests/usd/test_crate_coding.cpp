// The two codings under every crate section: USD's LZ4 framing and its
// integer coding, each against its inverse and against broken input.
#include <catch2/catch.hpp>

#include <limits>
#include <random>

#include "usd/integer_coding.h"
#include "usd/lz4_chunks.h"

using namespace sdg::usd;

TEST_CASE("LZ4 framing round-trips and rejects lies", "[usd][crate]") {
  std::vector<uint8_t> text(5000);
  for (size_t i = 0; i < text.size(); ++i) text[i] = uint8_t("crate tokens "[i % 13]);
  auto framed = compressLz4Chunks(text);
  CHECK(framed[0] == 0);  // one chunk
  std::vector<uint8_t> out(text.size());
  CHECK(decompressLz4Chunks(framed, out) == text.size());
  CHECK(out == text);

  std::vector<uint8_t> small(text.size() - 1);
  CHECK_THROWS_AS(decompressLz4Chunks(framed, small), CodingError);  // output would not fit
  CHECK_THROWS_AS(decompressLz4Chunks({}, out), CodingError);
  auto truncated = framed;
  truncated.resize(framed.size() / 2);
  CHECK_THROWS_AS(decompressLz4Chunks(truncated, out), CodingError);

  // The multi-chunk form: a count, then (size, block) per chunk.
  std::vector<uint8_t> chunked{2};
  auto block = compressLz4Chunks(std::span(text).first(3000));
  auto block2 = compressLz4Chunks(std::span(text).subspan(3000));
  for (auto* b : {&block, &block2}) {
    int32_t size = int32_t(b->size() - 1);
    chunked.insert(chunked.end(), reinterpret_cast<uint8_t*>(&size), reinterpret_cast<uint8_t*>(&size) + 4);
    chunked.insert(chunked.end(), b->begin() + 1, b->end());
  }
  std::fill(out.begin(), out.end(), 0);
  CHECK(decompressLz4Chunks(chunked, out) == text.size());
  CHECK(out == text);
  auto lying = chunked;
  int32_t huge = 1 << 30;
  std::memcpy(lying.data() + 1, &huge, 4);  // the first chunk claims more bytes than follow
  CHECK_THROWS_WITH(decompressLz4Chunks(lying, out), Catch::Contains("claims 1073741824 bytes"));
  lying[0] = 200;  // more chunks than the framing allows
  CHECK_THROWS_WITH(decompressLz4Chunks(lying, out), Catch::Contains("claims 200 chunks"));
}

TEMPLATE_TEST_CASE("integer coding round-trips every width class", "[usd][crate]", int32_t, uint32_t, int64_t,
                   uint64_t) {
  std::mt19937_64 rng(7);
  std::vector<TestType> values;
  using U = std::make_unsigned_t<TestType>;  // wrapping arithmetic, as the coding's
  TestType v = 0;
  for (int i = 0; i < 1000; ++i) {
    switch (i % 5) {
      case 0: v = TestType(U(v) + 1); break;                 // the common difference
      case 1: v = TestType(U(v) + U(rng() % 100)); break;    // small
      case 2: v = TestType(U(v) - U(rng() % 20000)); break;  // medium
      case 3: v = TestType(rng()); break;                    // full width
      default: v = std::numeric_limits<TestType>::min(); break;
    }
    values.push_back(v);
  }
  auto encoded = encodeIntegers<TestType>(values);
  CHECK(encoded.size() <= maxEncodedIntegersSize(values.size(), sizeof(TestType)));
  std::vector<TestType> decoded(values.size());
  decodeIntegers<TestType>(encoded, decoded);
  CHECK(decoded == values);

  auto framed = compressLz4Chunks(encoded);
  std::fill(decoded.begin(), decoded.end(), 0);
  decompressIntegers<TestType>(framed, decoded);
  CHECK(decoded == values);

  // Cut anywhere, the coding fails cleanly.
  for (size_t cut : {size_t(0), size_t(3), encoded.size() / 2, encoded.size() - 1})
    CHECK_THROWS_AS(decodeIntegers<TestType>(std::span(encoded).first(cut), decoded), CodingError);
}

TEST_CASE("integer coding matches USD's documented example", "[usd][crate]") {
  // USD's integerCoding.cpp explains its scheme on these integers: the
  // differences are 123, 1, 1, 100000, 0, 1, 0 and 1 is the common one.
  std::vector<int32_t> values{123, 124, 125, 100125, 100125, 100126, 100126};
  auto encoded = encodeIntegers<int32_t>(values);
  // Codes, two bits each from the low end: small, common, common, full |
  // small, common, small. Then the small and full differences in order.
  std::vector<uint8_t> expected{1, 0, 0, 0,  // the common difference
                                uint8_t(0b01 | 0b00 << 2 | 0b00 << 4 | 0b11 << 6), uint8_t(0b01 | 0b00 << 2 | 0b01 << 4),
                                123, 0xa0, 0x86, 0x01, 0x00, 0, 0};
  CHECK(encoded == expected);
  std::vector<int32_t> decoded(values.size());
  decodeIntegers<int32_t>(encoded, decoded);
  CHECK(decoded == values);
}
