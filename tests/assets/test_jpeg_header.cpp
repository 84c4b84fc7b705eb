// The built-in JPEG header reader (assets/jpeg_header.h): the frame header
// of real files, hand-built marker sequences, every truncation of a real
// file's header, and hostile bytes: each either a header or an ImageError
// naming the data, never a crash or a read past the end.
#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "assets/jpeg_header.h"

using namespace sdg;
using image_framing::ImageError;
using image_framing::Source;

namespace {

const std::string kFormats = SDG_SOURCE_DIR "/tests/data/images/formats/";

std::vector<unsigned char> fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::optional<ImageHeader> headerOf(const std::vector<unsigned char>& bytes) {
  Source src(bytes.data(), bytes.size(), "mem.jpg");
  return readJpegHeader(src);
}

// SOI, an APP0 segment, fill bytes, then a baseline frame header of w x h
// with `components` components.
std::vector<unsigned char> handMade(uint32_t w, uint32_t h, unsigned char components) {
  auto byte = [](uint32_t x) { return static_cast<unsigned char>(x & 0xFF); };
  return {0xFF, 0xD8, 0xFF, 0xE0, 0x00, 0x06, 'J', 'F', 'I', 'F',   // SOI, APP0
          0xFF, 0xFF, 0xFF, 0xC0, 0x00, 0x0B, 8,                    // fill bytes, SOF0, precision
          byte(h >> 8), byte(h), byte(w >> 8), byte(w), components,  // height, width, components
          1, 0x11, 0};                                               // one component's id, sampling, table
}

}  // namespace

TEST_CASE("jpeg header: a real file's frame as OpenImageIO reports it", "[assets][images][jpeg]") {
  Source src(kFormats + "pattern.jpg");
  const std::optional<ImageHeader> h = readJpegHeader(src);
  REQUIRE(h);
  CHECK(h->width == 8);
  CHECK(h->height == 4);
  CHECK(h->channels == 3);
  CHECK(h->bitsPerChannel == 8);
  CHECK(h->format == "jpeg");
  CHECK(readImageHeader(kFormats + "pattern.jpg").width == 8);
}

TEST_CASE("jpeg header: hand-made frames, fill bytes, grey and CMYK", "[assets][images][jpeg]") {
  const std::optional<ImageHeader> grey = headerOf(handMade(640, 480, 1));
  REQUIRE(grey);
  CHECK((grey->width == 640 && grey->height == 480 && grey->channels == 1));
  CHECK(headerOf(handMade(3, 2, 4))->channels == 3);
  // Not a JPEG at all: left to the other readers.
  CHECK_FALSE(headerOf({0x89, 'P', 'N', 'G'}));
  CHECK_FALSE(headerOf({}));
}

TEST_CASE("jpeg header: bad frames and markers are located errors", "[assets][images][jpeg]") {
  CHECK_THROWS_WITH(headerOf(handMade(0, 480, 3)), Catch::StartsWith("mem.jpg: the JPEG is corrupt: ") &&
                                                       Catch::Contains("declares no pixels"));
  CHECK_THROWS_WITH(headerOf(handMade(20000, 20000, 3)), Catch::Contains("declares 20000 x 20000 pixels"));
  CHECK_THROWS_WITH(headerOf(handMade(8, 8, 2)), Catch::Contains("declares 2 components"));
  // Image data (SOS) before any frame header.
  CHECK_THROWS_WITH(headerOf({0xFF, 0xD8, 0xFF, 0xDA, 0x00, 0x02}), Catch::Contains("no frame header (SOF)"));
  // A byte that is no marker where a segment should start.
  CHECK_THROWS_WITH(headerOf({0xFF, 0xD8, 0xFF, 0xE0, 0x00, 0x02, 0x12}), Catch::Contains("no marker starts"));
  CHECK_THROWS_WITH(headerOf({0xFF, 0xD8, 0xFF, 0xE0, 0x00, 0x01}), Catch::Contains("length under 2"));
  // A segment that claims to run past the end.
  CHECK_THROWS_WITH(headerOf({0xFF, 0xD8, 0xFF, 0xE0, 0xFF, 0xF0, 0x00}), Catch::Contains("is truncated"));
}

TEST_CASE("jpeg header: every truncation of a real header is an error, never a read past the end",
          "[assets][images][jpeg]") {
  const std::vector<unsigned char> whole = fileBytes(kFormats + "pattern.jpg");
  REQUIRE(whole.size() > 32);
  // Where the frame header ends: the shortest prefix that reads.
  size_t shortest = 0;
  for (size_t n = 3; n <= whole.size() && !shortest; ++n) {
    std::vector<unsigned char> cut(whole.begin(), whole.begin() + std::ptrdiff_t(n));
    try {
      if (headerOf(cut)) shortest = n;
    } catch (const ImageError& e) {
      CHECK_THAT(e.what(), Catch::StartsWith("mem.jpg: the JPEG is truncated"));
    }
  }
  REQUIRE(shortest > 0);
  CHECK(headerOf(whole)->width == 8);
}

TEST_CASE("jpeg header: random bytes after SOI give a header or an ImageError", "[assets][images][jpeg]") {
  std::mt19937 rng(29);
  const std::vector<unsigned char> real = fileBytes(kFormats + "pattern.jpg");
  for (int round = 0; round < 3000; ++round) {
    std::vector<unsigned char> b = real;
    b.resize(std::uniform_int_distribution<size_t>(3, real.size())(rng));
    for (int flips = 0; flips < 4 && b.size() > 3; ++flips)
      b[std::uniform_int_distribution<size_t>(3, b.size() - 1)(rng)] = static_cast<unsigned char>(rng() & 0xFF);
    try {
      if (std::optional<ImageHeader> h = headerOf(b)) CHECK((h->width > 0 && h->height > 0));
    } catch (const ImageError&) {
    }
  }
}
