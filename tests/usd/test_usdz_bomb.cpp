// .usdz zip bombs: a 1 MB package whose one entry inflates to 1 GiB, one
// whose header lies about the size, one nested in a package. Each is
// refused before its size is allocated (the header's size against
// ReadLimits::maxInflatedEntryBytes) or as soon as the inflated bytes pass
// the size the header records, and the process's peak memory shows it.
// The archives are written here byte by byte (zlib's raw deflate, the zip
// headers by hand), since libzip writes only honest headers.
#include <catch2/catch.hpp>

#include <sys/resource.h>
#include <unistd.h>
#include <zlib.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "usd/layer_io.h"
#include "usd/usdz_package.h"
#include "scratch_name.h"

using namespace sdg::usd;
namespace fs = std::filesystem;

namespace {

constexpr uint64_t kMiB = uint64_t(1) << 20;

// Raw deflate of `mib` MiB of zeros. Each MiB is deflated after a full
// flush (which resets the compressor), so after the first its output
// repeats: one MiB is compressed twice and the rest copied, and a 1 GiB
// bomb costs milliseconds to build.
std::vector<uint8_t> deflatedZeros(uint64_t mib) {
  z_stream z{};
  REQUIRE(deflateInit2(&z, 9, Z_DEFLATED, -15, 9, Z_DEFAULT_STRATEGY) == Z_OK);
  std::vector<uint8_t> zeros(kMiB, 0), out(kMiB);
  auto block = [&](int flush, size_t inputBytes) {
    z.next_in = zeros.data();
    z.avail_in = uInt(inputBytes);
    z.next_out = out.data();
    z.avail_out = uInt(out.size());
    const int rc = deflate(&z, flush);
    REQUIRE((rc == Z_OK || rc == Z_STREAM_END));
    REQUIRE(z.avail_in == 0);
    return std::vector<uint8_t>(out.begin(), out.begin() + ptrdiff_t(out.size() - z.avail_out));
  };
  std::vector<uint8_t> first = block(Z_FULL_FLUSH, kMiB), second = block(Z_FULL_FLUSH, kMiB),
                       third = block(Z_FULL_FLUSH, kMiB);
  REQUIRE(second == third);  // the periodic part
  std::vector<uint8_t> stream = first;
  for (uint64_t i = 1; i < mib; ++i) stream.insert(stream.end(), second.begin(), second.end());
  std::vector<uint8_t> end = block(Z_FINISH, 0);
  stream.insert(stream.end(), end.begin(), end.end());
  deflateEnd(&z);
  return stream;
}

uint32_t crcOfZeros(uint64_t mib) {
  std::vector<uint8_t> zeros(kMiB, 0);
  const uLong one = crc32(0, zeros.data(), uInt(kMiB));
  uLong crc = 0;
  for (uint64_t i = 0; i < mib; ++i) crc = crc32_combine(crc, one, z_off_t(kMiB));
  return uint32_t(crc);
}

struct RawEntry {
  std::string name;
  std::vector<uint8_t> data;  // as stored in the archive
  uint16_t method = 8;        // 8 deflate, 0 stored
  uint32_t crc = 0;
  uint32_t size = 0;  // the uncompressed size the headers record (true or not)
};

void put16(std::vector<uint8_t>& b, uint32_t v) {
  b.push_back(uint8_t(v));
  b.push_back(uint8_t(v >> 8));
}
void put32(std::vector<uint8_t>& b, uint32_t v) {
  put16(b, v & 0xffff);
  put16(b, v >> 16);
}

// A zip archive of the entries, local and central headers agreeing.
std::vector<uint8_t> zipOf(const std::vector<RawEntry>& entries) {
  std::vector<uint8_t> out, central;
  for (const RawEntry& e : entries) {
    const uint32_t offset = uint32_t(out.size());
    auto common = [&](std::vector<uint8_t>& b) {
      put16(b, 20);  // version needed
      put16(b, 0);   // flags
      put16(b, e.method);
      put16(b, 0);  // time
      put16(b, 0x21);  // date: 1980-01-01
      put32(b, e.crc);
      put32(b, uint32_t(e.data.size()));
      put32(b, e.size);
      put16(b, uint16_t(e.name.size()));
      put16(b, 0);  // extra
    };
    put32(out, 0x04034b50);
    common(out);
    out.insert(out.end(), e.name.begin(), e.name.end());
    out.insert(out.end(), e.data.begin(), e.data.end());
    put32(central, 0x02014b50);
    put16(central, 20);  // version made by
    common(central);
    put16(central, 0);  // comment
    put16(central, 0);  // disk
    put16(central, 0);  // internal attributes
    put32(central, 0);  // external attributes
    put32(central, offset);
    central.insert(central.end(), e.name.begin(), e.name.end());
  }
  const uint32_t centralOffset = uint32_t(out.size());
  out.insert(out.end(), central.begin(), central.end());
  put32(out, 0x06054b50);
  put16(out, 0);
  put16(out, 0);
  put16(out, uint16_t(entries.size()));
  put16(out, uint16_t(entries.size()));
  put32(out, uint32_t(central.size()));
  put32(out, centralOffset);
  put16(out, 0);
  return out;
}

const fs::path& scratch() {
  static const sdg::test::ScratchFolder dir("sdg_usdz_bomb");
  return dir.path();
}

fs::path writeBytes(const std::string& name, const std::vector<uint8_t>& bytes) {
  fs::path path = scratch() / name;
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  return path;
}

// Peak resident memory of this process so far, in MiB.
double peakMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // Linux: KiB
}

}  // namespace

TEST_CASE("usdz bomb: an entry that inflates to 1 GiB is refused before it is inflated", "[usd][usdz][hostile]") {
  const uint64_t mib = 1024;
  const std::vector<uint8_t> stream = deflatedZeros(mib);
  const uint32_t crc = crcOfZeros(mib);
  CHECK(stream.size() < 2 * kMiB);  // about 1 MB

  // Honest headers: 1 GiB recorded. Refused by the size check, not by reading.
  const fs::path honest = writeBytes("honest.usdz", zipOf({{"bomb.usdc", stream, 8, crc, uint32_t(mib * kMiB)}}));
  const double before = peakMiB();
  const auto start = std::chrono::steady_clock::now();
  CHECK_THROWS_WITH(readPackagedLayer(honest.string(), "", ReadLimits{}),
             Catch::Equals(honest.string() + ": usdz package: entry 'bomb.usdc' inflates to 1073741824 bytes, more "
                                             "than the limit of 268435456 for a compressed entry "
                                             "(ReadLimits::maxInflatedEntryBytes)"));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Through readLayerFile, as `validate bomb.usdz` reads it.
  CHECK_THROWS_WITH(readLayerFile(honest.string()), Catch::Contains("inflates to 1073741824 bytes"));
  INFO("refused in " << seconds << " s");
  CHECK(peakMiB() - before < 64);

  // Lying headers: 1000 bytes recorded (CRC of nothing in particular). The
  // reading stops at the first chunk past them.
  const fs::path liar = writeBytes("liar.usdz", zipOf({{"bomb.usdc", stream, 8, crc, 1000}}));
  CHECK_THROWS_WITH(readPackagedLayer(liar.string(), "", ReadLimits{}),
             Catch::Equals(liar.string() + ": usdz package: entry 'bomb.usdc' inflates past the 1000 bytes its "
                                           "header records"));
  CHECK(peakMiB() - before < 64);
}

TEST_CASE("usdz bomb: within the limit an entry reads, past it, honest or lying, it is refused", "[usd][usdz][hostile]") {
  const std::vector<uint8_t> stream = deflatedZeros(4);
  const uint32_t crc = crcOfZeros(4);
  const fs::path path = writeBytes("four.usdz", zipOf({{"zeros.bin", stream, 8, crc, uint32_t(4 * kMiB)}}));
  CHECK(UsdzPackage(path.string()).read("zeros.bin") == std::vector<uint8_t>(4 * kMiB, 0));
  ReadLimits small;
  small.maxInflatedEntryBytes = 3 * kMiB;
  CHECK_THROWS_WITH(UsdzPackage(path.string(), small).read("zeros.bin"),
             Catch::Contains("entry 'zeros.bin' inflates to 4194304 bytes, more than the limit of 3145728"));
  // Recorded larger than it is: the data ends early (and the CRC is checked).
  const fs::path longer = writeBytes("longer.usdz", zipOf({{"zeros.bin", stream, 8, crc, uint32_t(4 * kMiB + 1)}}));
  CHECK_THROWS_WITH(UsdzPackage(longer.string()).read("zeros.bin"),
             Catch::Contains("entry 'zeros.bin': cannot read it") ||
                 Catch::Contains("does not hold the 4194305 bytes its header records"));
  // A stored entry that claims more than the package holds.
  const fs::path stored = writeBytes("stored.usdz", zipOf({{"big.usdc", std::vector<uint8_t>(64, 0), 0, 0, 1u << 30}}));
  CHECK_THROWS_WITH(UsdzPackage(stored.string()).read("big.usdc"),
             Catch::Contains("entry 'big.usdc' records 1073741824 stored bytes, but the package has"));
}

TEST_CASE("usdz bomb: packages inside packages share the limit", "[usd][usdz][hostile]") {
  // inner.usdz: 1 MiB of zeros deflated, and 1 MiB stored.
  const std::vector<uint8_t> bomb = deflatedZeros(1);
  const std::vector<uint8_t> inner =
      zipOf({{"zeros.bin", bomb, 8, crcOfZeros(1), uint32_t(kMiB)}, {"pad.bin", std::vector<uint8_t>(kMiB, 0), 0,
                                                                      crcOfZeros(1), uint32_t(kMiB)}});
  // The inner package stored in the outer one: its stored pad is its own
  // bytes, so only the zeros.bin inflation counts.
  const fs::path storedOuter = writeBytes("outer_stored.usdz", zipOf({{"inner.usdz", inner, 0,
                                                                      uint32_t(crc32(0, inner.data(), uInt(inner.size()))),
                                                                      uint32_t(inner.size())}}));
  ReadLimits limits;
  limits.maxInflatedEntryBytes = kMiB + kMiB / 2;
  CHECK(UsdzPackage(storedOuter.string(), limits).read("inner.usdz[zeros.bin]").size() == kMiB);
  // The inner package deflated in the outer one: the 1 MiB inflated to
  // reach it stays held, so the same limit leaves its entry 0.5 MiB.
  z_stream z{};
  REQUIRE(deflateInit2(&z, 9, Z_DEFLATED, -15, 9, Z_DEFAULT_STRATEGY) == Z_OK);
  std::vector<uint8_t> deflated(deflateBound(&z, uLong(inner.size())));
  z.next_in = const_cast<uint8_t*>(inner.data());
  z.avail_in = uInt(inner.size());
  z.next_out = deflated.data();
  z.avail_out = uInt(deflated.size());
  REQUIRE(deflate(&z, Z_FINISH) == Z_STREAM_END);
  deflated.resize(deflated.size() - z.avail_out);
  deflateEnd(&z);
  const fs::path deflatedOuter = writeBytes(
      "outer_deflated.usdz",
      zipOf({{"inner.usdz", deflated, 8, uint32_t(crc32(0, inner.data(), uInt(inner.size()))), uint32_t(inner.size())}}));
  CHECK_THROWS_WITH(UsdzPackage(deflatedOuter.string(), limits).read("inner.usdz[zeros.bin]"),
             Catch::Contains("[inner.usdz]: usdz package: entry 'zeros.bin' inflates to 1048576 bytes, more than the "
                             "limit of " + std::to_string(kMiB + kMiB / 2 - inner.size())));
  limits.maxInflatedEntryBytes = 2 * kMiB + kMiB / 2;
  CHECK(UsdzPackage(deflatedOuter.string(), limits).read("inner.usdz[zeros.bin]").size() == kMiB);
}
