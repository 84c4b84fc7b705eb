// The OpenImageIO back end of assets/image.h, built as its own module
// (sdgbehave_images.so) that image.cpp opens on the first image that is not
// a plain PNG: Debian's OpenImageIO brings about 260 shared libraries
// (OpenCV, FFmpeg, GDAL, OpenVDB...) whose loading alone takes 0.18 s and
// 130 MB, which every command would otherwise pay at start-up.
// Self-contained: it links none of the sdg_* libraries, and reports errors
// as text through the table (assets/image_backend.h), not as exceptions.
#include "assets/image_backend.h"
#include "assets/image_framing.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <string_view>

#include <stdexcept>

namespace sdg {

namespace {

using namespace std::string_view_literals;

// The sRGB curve, the module's own copy (it links nothing of sdgbehave's).
float decodeSrgb(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

float encodeSrgb(float linear) {
  return linear <= 0.0031308f ? linear * 12.92f : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

using namespace image_framing;


// Process-wide OpenImageIO settings, made before the first image is read.
void configureOiio() {
  static std::once_flag once;
  std::call_once(once, [] {
    // The callers (the renderer's thread, the write pool) already decide how
    // many threads work; OIIO's own pool would fan out under each of them.
    // Decoding gives the same pixels whatever the count.
    OIIO::attribute("threads", 1);
  });
}

// What went wrong, in one line, from the reader and OIIO's global queue;
// both are emptied so that no message waits there for a later call.
std::string oiioError(OIIO::ImageInput* in) {
  std::string text = in ? in->geterror() : std::string();
  std::string global = OIIO::geterror();
  if (text.empty()) text = global;
  std::replace(text.begin(), text.end(), '\n', ' ');
  const size_t end = text.find_last_not_of(' ');
  text.erase(end == std::string::npos ? 0 : end + 1);
  return text.empty() ? "no details given" : text;
}

// "PNG", "OpenEXR", ... for OIIO's format names, in messages.
std::string displayName(const std::string& format) {
  static const std::map<std::string, std::string> names = {
      {"png", "PNG"},       {"jpeg", "JPEG"}, {"tiff", "TIFF"}, {"openexr", "OpenEXR"}, {"hdr", "Radiance HDR"},
      {"targa", "TGA"},     {"bmp", "BMP"},   {"webp", "WebP"}, {"gif", "GIF"}};
  auto it = names.find(format);
  if (it != names.end()) return it->second;
  std::string upper = format;
  for (char& c : upper) c = char(std::toupper(static_cast<unsigned char>(c)));
  return upper;
}

// The format the first bytes announce, or "" (TGA, for one, has no
// signature). The bytes decide before the name does: a JPEG saved as
// ".png" is still read.
std::string sniffFormat(std::string_view head) {
  auto starts = [&](std::string_view magic) { return head.starts_with(magic); };
  if (starts("\x89PNG\r\n\x1a\n"sv)) return "png";
  if (starts("\xff\xd8\xff"sv)) return "jpeg";
  if (starts("II*\0"sv) || starts("MM\0*"sv) || starts("II+\0"sv) || starts("MM\0+"sv)) return "tiff";
  if (starts("\x76\x2f\x31\x01"sv)) return "openexr";
  if (starts("#?RADIANCE"sv) || starts("#?RGBE"sv)) return "hdr";
  if (starts("RIFF"sv) && head.size() >= 12 && head.substr(8).starts_with("WEBP"sv)) return "webp";
  if (starts("GIF87a"sv) || starts("GIF89a"sv)) return "gif";
  if (starts("BM"sv)) return "bmp";
  return "";
}

// OIIO readers that do not read still images: videos, volumes, and "null",
// which makes up pixels for any file name ending in .null.
bool isStillImageReader(const std::string& format) {
  return format != "ffmpeg" && format != "openvdb" && format != "null" && format != "term";
}

// The reader a file name's extension names ("" if none), for files whose
// first bytes name no format.
std::string formatFromExtension(const std::string& name) {
  static const std::map<std::string, std::string> byExtension = [] {
    std::map<std::string, std::string> m;
    for (const auto& [format, extensions] : OIIO::get_extension_map())
      if (isStillImageReader(format))
        for (const std::string& ext : extensions) m.emplace(ext, format);
    return m;
  }();
  // A package entry, "pkg.usdz[0/wood.tga]" (nested: "...tga]]"), by its entry's name.
  std::string file = name;
  while (!file.empty() && file.back() == ']' && file.find('[') != std::string::npos) file.pop_back();
  std::string ext = std::filesystem::path(file).extension().string();
  if (ext.empty()) return "";
  ext.erase(0, 1);
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  auto it = byExtension.find(ext);
  return it == byExtension.end() ? "" : it->second;
}

// Where the entropy-coded data of a JPEG scan starting at `pos` ends: at
// the next marker other than a stuffed 0xFF00 or a restart marker; npos if
// the data ends first.
uint64_t endOfScan(Source& src, uint64_t pos) {
  std::vector<unsigned char> block(64 << 10);
  for (;;) {
    const size_t n = src.readAt(pos, block.size(), block.data());
    if (n < 2) return std::string::npos;
    for (const unsigned char* p = block.data(); p < block.data() + n - 1; ++p) {
      p = static_cast<const unsigned char*>(std::memchr(p, 0xFF, size_t(block.data() + n - 1 - p)));
      if (!p) break;
      if (p[1] != 0x00 && !(p[1] >= 0xD0 && p[1] <= 0xD7)) return pos + uint64_t(p - block.data());
    }
    pos += n - 1;  // the last byte may be the 0xFF of a marker
  }
}

// libjpeg, as OIIO drives it, decodes a truncated JPEG without an error,
// filling the missing part with grey. So the markers are walked here,
// through every scan, to the end-of-image marker.
void checkJpegFraming(Source& src) {
  for (uint64_t pos = 2;;) {
    unsigned char m[2];
    if (!src.readAll(pos, 2, m)) truncated(src, "JPEG", "before its end-of-image marker");
    if (m[0] != 0xFF) corrupt(src, "JPEG", "no marker where one should be, at byte " + std::to_string(pos));
    if (m[1] == 0xFF) {  // a fill byte before the marker
      ++pos;
      continue;
    }
    pos += 2;
    if (m[1] == 0xD9) return;                                      // end of image
    if (m[1] == 0x01 || (m[1] >= 0xD0 && m[1] <= 0xD7)) continue;  // markers without a segment
    unsigned char len[2];
    if (!src.readAll(pos, 2, len)) truncated(src, "JPEG", "inside a marker segment");
    const uint32_t length = uint32_t(len[0]) << 8 | len[1];
    if (length < 2) corrupt(src, "JPEG", "a marker segment of impossible length at byte " + std::to_string(pos));
    if (!src.readAll(pos + length - 1, 1, len)) truncated(src, "JPEG", "inside a marker segment");
    pos += length;
    if (m[1] == 0xDA && (pos = endOfScan(src, pos)) == std::string::npos)
      truncated(src, "JPEG", "inside the compressed pixels, before the end-of-image marker");
  }
}

// An image opened by its reader, header read, no pixels decoded yet.
struct OpenImage {
  std::string name;
  std::string format;                                     // OIIO's reader name
  std::unique_ptr<OIIO::Filesystem::IOMemReader> memory;  // outlives `in`, which reads through it
  std::unique_ptr<OIIO::ImageInput> in;
  OIIO::ImageSpec spec;
};

// Limits and shapes sdgbehave reads, from the header alone.
void checkHeader(const OpenImage& img) {
  const OIIO::ImageSpec& s = img.spec;
  if (s.deep) fail(img.name, "holds deep (multi-sample) pixels, which sdgbehave does not read");
  if (s.depth > 1) fail(img.name, "is a volume, not a 2D image");
  if (s.width <= 0 || s.height <= 0 || s.nchannels <= 0) fail(img.name, "declares no pixels");
  checkLimits(img.name, displayName(img.format), uint64_t(s.width), uint64_t(s.height));
}

enum class Purpose { Header, Pixels };

// The format the bytes announce, else the one the name's extension names.
std::string formatOf(Source& src) {
  unsigned char head[16];
  const size_t n = src.readAt(0, sizeof head, head);
  if (n == 0) fail(src.name(), src.inMemory() ? "holds no bytes" : "the file is empty");
  std::string format = sniffFormat(std::string_view(reinterpret_cast<const char*>(head), n));
  if (format.empty()) format = formatFromExtension(src.name());
  if (format.empty())
    fail(src.name(), "not an image sdgbehave can read: neither its first bytes nor its file name's extension "
                     "name an image format (PNG, JPEG, TIFF, OpenEXR, Radiance HDR, TGA, BMP, WebP, ...)");
  return format;
}

OpenImage openImage(Source& src, Purpose purpose) {
  configureOiio();
  OpenImage img;
  img.name = src.name();
  img.format = formatOf(src);
  if (img.format == "png") checkPngFraming(src, purpose == Purpose::Pixels);
  if (img.format == "jpeg" && purpose == Purpose::Pixels) checkJpegFraming(src);
  // Created by format name, so only that reader is tried.
  img.in = OIIO::ImageInput::create(img.format);
  if (!img.in) fail(img.name, "cannot read " + displayName(img.format) + " images: " + oiioError(nullptr));
  if (src.inMemory()) {
    img.memory = std::make_unique<OIIO::Filesystem::IOMemReader>(src.bytes(), src.size());
    if (!img.in->set_ioproxy(img.memory.get()))
      fail(img.name, "cannot decode " + displayName(img.format) + " images held in memory");
  }
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // straight alpha, as stored (PNG, TIFF, TGA, WebP)
  if (!img.in->open(img.name, img.spec, config))
    fail(img.name, "not a readable " + displayName(img.format) + " image: " + oiioError(img.in.get()));
  checkHeader(img);
  return img;
}

ImageHeader headerOf(const OpenImage& img) {
  ImageHeader h;
  h.width = uint32_t(img.spec.width);
  h.height = uint32_t(img.spec.height);
  h.channels = img.spec.nchannels;
  h.bitsPerChannel = img.spec.get_int_attribute("oiio:BitsPerSample", int(img.spec.format.size() * 8));
  h.floatingPoint = img.spec.format.is_floating_point();
  h.format = img.in->format_name();
  return h;
}

// Which of the file's channels are read, and what they hold: grey (1) or
// R, G, B (3) first, then alpha where the file has one.
struct Layout {
  int colour = 3;
  int alpha = -1;  // channel index; -1: opaque
  int read = 3;    // channels 0 .. read-1 are decoded
  bool isRgba() const { return colour == 3 && alpha == 3 && read == 4; }
};

Layout layoutOf(const OIIO::ImageSpec& spec) {
  const int n = spec.nchannels;
  Layout l;
  l.colour = n >= 3 ? 3 : 1;
  // The channel OIIO calls alpha; without a name, the 2nd of two (grey +
  // alpha) or the 4th of four.
  l.alpha = spec.alpha_channel >= l.colour ? spec.alpha_channel : n == 2 ? 1 : n == 4 ? 3 : -1;
  l.read = std::max(l.colour, l.alpha + 1);
  return l;
}

// How the stored samples are decoded: 8-bit and other integers keep their
// precision (16 bits at most); half floats are read as stored and widened
// here through a table, which is cheaper than OIIO's conversion; other floating
// point as float.
enum class Sample { U8, U16, F16, F32 };

Sample sampleOf(const OIIO::ImageSpec& spec) {
  auto isHalf = [](OIIO::TypeDesc t) { return t == OIIO::TypeHalf; };
  const auto& perChannel = spec.channelformats;
  const bool allHalf = perChannel.empty() ? isHalf(spec.format) : std::all_of(perChannel.begin(), perChannel.end(), isHalf);
  if (allHalf) return Sample::F16;
  if (spec.format.is_floating_point()) return Sample::F32;
  return spec.format.size() == 1 ? Sample::U8 : Sample::U16;
}

// A half float as stored, widened through halfToFloatTable().
struct HalfBits {
  uint16_t bits;
};

float halfToFloat(uint16_t h) {
  const uint32_t sign = uint32_t(h & 0x8000u) << 16, exponent = (h >> 10) & 0x1fu, mantissa = h & 0x3ffu;
  if (exponent == 0) {  // zero and subnormals: mantissa * 2^-24
    const float magnitude = float(mantissa) * 0x1p-24f;
    return sign ? -magnitude : magnitude;
  }
  const uint32_t bits = exponent == 0x1f ? sign | 0x7f800000u | mantissa << 13  // infinity, NaN
                                         : sign | (exponent + 112) << 23 | mantissa << 13;
  return std::bit_cast<float>(bits);
}

// Every half's float value, built once: one lookup per sample.
const std::array<float, 65536>& halfToFloatTable() {
  static const auto table = [] {
    auto t = std::make_unique<std::array<float, 65536>>();
    for (uint32_t h = 0; h < 65536; ++h) (*t)[h] = halfToFloat(uint16_t(h));
    return t;
  }();
  return *table;
}

template <typename T>
OIIO::TypeDesc typeOf() {
  if constexpr (std::is_same_v<T, uint8_t>) return OIIO::TypeUInt8;
  else if constexpr (std::is_same_v<T, uint16_t>) return OIIO::TypeUInt16;
  else if constexpr (std::is_same_v<T, HalfBits>) return OIIO::TypeHalf;
  else return OIIO::TypeFloat;
}

size_t pixelCount(const OpenImage& img) { return size_t(img.spec.width) * size_t(img.spec.height); }

// Rows decoded per read of a scanline file: the buffer stays small (a few
// MB at 4k) and is reused, and 256 is a multiple of every OpenEXR block
// height, so no block is decompressed twice.
constexpr int kBandRows = 256;

// Decodes rows [y, y + rows) (of the data window) of channels
// 0 .. channels-1 into `out`, packed. Tiled files are read whole.
template <typename T>
void readRows(OpenImage& img, int y, int rows, int channels, T* out) {
  const OIIO::ImageSpec& s = img.spec;
  const bool ok = s.tile_width > 0
                      ? img.in->read_image(0, 0, 0, channels, typeOf<T>(), out)
                      : img.in->read_scanlines(0, 0, s.y + y, s.y + y + rows, 0, 0, channels, typeOf<T>(), out);
  if (!ok) fail(img.name, "the " + displayName(img.format) + " is corrupt or truncated: " + oiioError(img.in.get()));
}

// Packed samples of the layout's channels to RGBA: `colour` maps grey or
// R, G, B, `alpha` maps alpha; `opaque` fills a missing alpha. The lambdas
// inline, so this is one tight loop per conversion.
template <typename In, typename Out, typename ColourFn, typename AlphaFn>
void expandToRgba(const In* s, size_t pixels, const Layout& l, Out* dst, ColourFn colour, AlphaFn alpha, Out opaque) {
  for (size_t p = 0; p < pixels; ++p, s += l.read, dst += 4) {
    if (l.colour == 3) {
      dst[0] = colour(s[0]);
      dst[1] = colour(s[1]);
      dst[2] = colour(s[2]);
    } else {
      dst[0] = dst[1] = dst[2] = colour(s[0]);
    }
    dst[3] = l.alpha >= 0 ? alpha(s[l.alpha]) : opaque;
  }
}

// OIIO 2.4's WebP reader premultiplies colour by alpha whatever the
// configuration asks (later versions honour oiio:UnassociatedAlpha and say
// so in the spec). WebP stores straight alpha, like the other 8-bit
// formats, so that is undone: exactly where alpha is high, within
// 255 / (2 alpha) codes where it is low.
bool premultipliedByReader(const OpenImage& img) {
  return img.format == "webp" && img.spec.alpha_channel >= 0 &&
         !img.spec.get_int_attribute("oiio:UnassociatedAlpha");
}

void unpremultiply(uint8_t* s, size_t pixels, int stride, int colour, int alpha) {
  for (size_t p = 0; p < pixels; ++p, s += stride) {
    const unsigned a = s[alpha];
    if (a == 0 || a == 255) continue;
    for (int c = 0; c < colour; ++c) s[c] = uint8_t(std::min(255u, (s[c] * 255u + a / 2) / a));
  }
}

// Decodes the image as `In` samples, a band of rows at a time, and
// expands each band into the RGBA output while it is still in cache.
template <typename In, typename Out, typename ColourFn, typename AlphaFn>
void decodeToRgba(OpenImage& img, Out* dst, ColourFn colour, AlphaFn alpha, Out opaque) {
  const Layout l = layoutOf(img.spec);
  const int height = img.spec.height, band = img.spec.tile_width > 0 ? height : std::min(height, kBandRows);
  const size_t width = size_t(img.spec.width);
  std::vector<In> packed(width * size_t(band) * size_t(l.read));
  for (int y = 0; y < height; y += band) {
    const int rows = std::min(band, height - y);
    readRows(img, y, rows, l.read, packed.data());
    if constexpr (std::is_same_v<In, uint8_t>)
      if (premultipliedByReader(img)) unpremultiply(packed.data(), width * size_t(rows), l.read, l.colour, l.alpha);
    expandToRgba(packed.data(), width * size_t(rows), l, dst + width * size_t(y) * 4, colour, alpha, opaque);
  }
}

// [0, 1], with NaN as 0, for float samples that become 8-bit.
float unitClamp(float v) { return v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; }

uint8_t toByte(float unit) { return uint8_t(std::lround(255.0f * unit)); }

// Every half's 8-bit value, sRGB-encoded or not, clamped; built once.
const std::array<uint8_t, 65536>& halfToByteTable(bool srgb) {
  auto build = [](bool encode) {
    auto t = std::make_unique<std::array<uint8_t, 65536>>();
    const auto& floats = halfToFloatTable();
    for (size_t h = 0; h < t->size(); ++h) {
      const float v = unitClamp(floats[h]);
      (*t)[h] = toByte(encode ? encodeSrgb(v) : v);
    }
    return t;
  };
  static const auto encoded = build(true), plain = build(false);
  return srgb ? *encoded : *plain;
}

// Linear float samples to 8 bits: sRGB-encoded for colour, clamped.
void decodeFloatRgba8(OpenImage& img, uint8_t* dst, TextureData data) {
  auto plain = [](float v) { return toByte(unitClamp(v)); };
  auto encoded = [](float v) { return toByte(encodeSrgb(unitClamp(v))); };
  if (data == TextureData::Color) decodeToRgba<float>(img, dst, encoded, plain, uint8_t(255));
  else decodeToRgba<float>(img, dst, plain, plain, uint8_t(255));
}

ImageRgba8 decodeRgba8(OpenImage& img, TextureData data) {
  ImageRgba8 out;
  out.width = uint32_t(img.spec.width);
  out.height = uint32_t(img.spec.height);
  out.pixels.resize(pixelCount(img) * 4);
  uint8_t* dst = out.pixels.data();
  switch (sampleOf(img.spec)) {
    case Sample::U8: {
      if (layoutOf(img.spec).isRgba()) {  // as stored
        readRows(img, 0, img.spec.height, 4, dst);
        if (premultipliedByReader(img)) unpremultiply(dst, pixelCount(img), 4, 3, 3);
        return out;
      }
      auto same = [](uint8_t v) { return v; };
      decodeToRgba<uint8_t>(img, dst, same, same, uint8_t(255));
      break;
    }
    case Sample::U16: {
      auto round8 = [](uint16_t v) { return uint8_t((uint32_t(v) * 255u + 32767u) / 65535u); };
      decodeToRgba<uint16_t>(img, dst, round8, round8, uint8_t(255));
      break;
    }
    case Sample::F16: {
      // Every half's 8-bit value looked up: the bytes decodeFloatRgba8
      // would give, without a pow() per sample.
      const auto& colour = halfToByteTable(data == TextureData::Color);
      const auto& plain = halfToByteTable(false);
      decodeToRgba<HalfBits>(img, dst, [&](HalfBits v) { return colour[v.bits]; },
                             [&](HalfBits v) { return plain[v.bits]; }, uint8_t(255));
      break;
    }
    case Sample::F32: decodeFloatRgba8(img, dst, data); break;
  }
  return out;
}

// sRGB-decoded values of every code of an integer format, built once.
template <size_t N>
const std::array<float, N>& srgbDecodeTable() {
  static const auto table = [] {
    auto t = std::make_unique<std::array<float, N>>();
    for (size_t k = 0; k < N; ++k) (*t)[k] = decodeSrgb(float(k) / float(N - 1));
    return t;
  }();
  return *table;
}

ImageRgbaF decodeLinear(OpenImage& img) {
  ImageRgbaF out;
  out.width = uint32_t(img.spec.width);
  out.height = uint32_t(img.spec.height);
  out.pixels.resize(pixelCount(img) * 4);
  float* dst = out.pixels.data();
  switch (sampleOf(img.spec)) {
    case Sample::U8: {
      const auto& table = srgbDecodeTable<256>();
      decodeToRgba<uint8_t>(img, dst, [&](uint8_t v) { return table[v]; }, [](uint8_t v) { return v / 255.0f; }, 1.0f);
      break;
    }
    case Sample::U16: {
      const auto& table = srgbDecodeTable<65536>();
      decodeToRgba<uint16_t>(img, dst, [&](uint16_t v) { return table[v]; },
                             [](uint16_t v) { return v / 65535.0f; }, 1.0f);
      break;
    }
    case Sample::F16: {
      const auto& table = halfToFloatTable();
      auto widen = [&](HalfBits v) { return table[v.bits]; };
      decodeToRgba<HalfBits>(img, dst, widen, widen, 1.0f);
      break;
    }
    case Sample::F32: {
      auto same = [](float v) { return v; };
      decodeToRgba<float>(img, dst, same, same, 1.0f);
      break;
    }
  }
  return out;
}

// Each entry runs `body` and hands its error over as text.
template <typename Body>
bool guarded(std::string& error, Body body) {
  try {
    body();
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
}

bool readHeader(const std::string& path, ImageHeader& out, std::string& error) {
  return guarded(error, [&] {
    Source src(path);
    out = headerOf(openImage(src, Purpose::Header));
  });
}

bool loadRgba8(const std::string& path, TextureData data, ImageRgba8& out, std::string& error) {
  return guarded(error, [&] {
    Source src(path);
    OpenImage img = openImage(src, Purpose::Pixels);
    out = decodeRgba8(img, data);
  });
}

bool loadLinear(const std::string& path, ImageRgbaF& out, std::string& error) {
  return guarded(error, [&] {
    Source src(path);
    OpenImage img = openImage(src, Purpose::Pixels);
    out = decodeLinear(img);
  });
}

bool decodeBytesRgba8(const void* bytes, size_t size, const std::string& name, TextureData data, ImageRgba8& out,
                      std::string& error) {
  return guarded(error, [&] {
    Source src(bytes, size, name);
    OpenImage img = openImage(src, Purpose::Pixels);
    out = decodeRgba8(img, data);
  });
}

bool decodeBytesLinear(const void* bytes, size_t size, const std::string& name, ImageRgbaF& out, std::string& error) {
  return guarded(error, [&] {
    Source src(bytes, size, name);
    OpenImage img = openImage(src, Purpose::Pixels);
    out = decodeLinear(img);
  });
}

}  // namespace

}  // namespace sdg

extern "C" __attribute__((visibility("default"))) const sdg::ImageBackend* sdg_image_backend() {
  static const sdg::ImageBackend backend{sdg::kImageBackendVersion, sdg::readHeader, sdg::loadRgba8, sdg::loadLinear,
                                         sdg::decodeBytesRgba8, sdg::decodeBytesLinear};
  return &backend;
}
