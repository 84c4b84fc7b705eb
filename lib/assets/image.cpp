#include "assets/image.h"

#include <dlfcn.h>
#include <png.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <optional>

#include "assets/image_backend.h"
#include "assets/image_framing.h"
#include "assets/jpeg_header.h"
#include "core/diagnostics.h"

#ifndef SDG_IMAGES_MODULE_BUILD_PATH
#define SDG_IMAGES_MODULE_BUILD_PATH ""
#endif

namespace sdg {
namespace {

namespace fs = std::filesystem;
using image_framing::ImageError;
using image_framing::Source;

// Plain PNGs (8 bits a channel: what sdgbehave's own assets and most
// textures are) decode here through libpng; everything else goes to the
// OpenImageIO module, opened on first use (image_oiio.cpp says why).
bool isPng(Source& src) {
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  unsigned char head[8];
  return src.readAll(0, 8, head) && std::equal(head, head + 8, kSignature);
}

// The 8-bit PNG's pixels as RGBA8, or nullopt for a 16-bit one (which the
// module reads: libpng's simplified reader would gamma-convert it).
std::optional<ImageRgba8> decodePng(Source& src) {
  image_framing::checkPngFraming(src, true);
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  const bool begun = src.inMemory() ? png_image_begin_read_from_memory(&image, src.bytes(), src.size())
                                    : png_image_begin_read_from_file(&image, src.name().c_str());
  if (!begun) image_framing::fail(src.name(), std::string("the PNG is corrupt: ") + image.message);
  if (image.format & PNG_FORMAT_FLAG_LINEAR) {  // 16 bits a channel
    png_image_free(&image);
    return std::nullopt;
  }
  image.format = PNG_FORMAT_RGBA;
  ImageRgba8 out{image.width, image.height, std::vector<uint8_t>(PNG_IMAGE_SIZE(image))};
  if (!png_image_finish_read(&image, nullptr, out.pixels.data(), 0, nullptr)) {
    const std::string message = image.message;
    png_image_free(&image);
    image_framing::fail(src.name(), "the PNG is corrupt: " + message);
  }
  return out;
}

ImageHeader pngHeader(Source& src) {
  image_framing::checkPngFraming(src, false);
  unsigned char ihdr[13];
  src.readAll(16, 13, ihdr);
  ImageHeader h;
  h.width = image_framing::bigEndian32(ihdr);
  h.height = image_framing::bigEndian32(ihdr + 4);
  h.bitsPerChannel = ihdr[8] == 16 ? 16 : 8;
  const int colour = ihdr[9];
  h.channels = colour == 0 ? 1 : colour == 4 ? 2 : colour == 6 ? 4 : 3;
  h.format = "png";
  return h;
}

const std::array<float, 256>& srgbTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int k = 0; k < 256; ++k) t[size_t(k)] = srgbToLinear(float(k) / 255.0f);
    return t;
  }();
  return table;
}

ImageRgbaF linearOf(const ImageRgba8& image) {
  ImageRgbaF out{image.width, image.height, std::vector<float>(image.pixels.size())};
  const auto& table = srgbTable();
  for (size_t i = 0; i < image.pixels.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) out.pixels[i + c] = table[image.pixels[i + c]];
    out.pixels[i + 3] = float(image.pixels[i + 3]) / 255.0f;
  }
  return out;
}

// Where the module lies: $SDGBEHAVE_IMAGES_MODULE, else beside an installed
// executable (<prefix>/lib/sdgbehave/), else in the build tree.
std::vector<std::string> moduleCandidates() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("SDGBEHAVE_IMAGES_MODULE"); env && *env) candidates.emplace_back(env);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back((exe.parent_path().parent_path() / "lib" / "sdgbehave" / "sdgbehave_images.so").string());
  if (*SDG_IMAGES_MODULE_BUILD_PATH) candidates.emplace_back(SDG_IMAGES_MODULE_BUILD_PATH);
  return candidates;
}

const ImageBackend& backend() {
  static const ImageBackend* loaded = nullptr;
  static std::string problem;
  static std::once_flag once;
  std::call_once(once, [] {
    std::string tried;
    for (const std::string& path : moduleCandidates()) {
      std::error_code ec;
      if (!fs::exists(path, ec)) {
        tried += (tried.empty() ? "" : ", ") + path;
        continue;
      }
      void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        problem = "cannot load " + path + ": " + dlerror();
        return;
      }
      auto entry = reinterpret_cast<const ImageBackend* (*)()>(dlsym(handle, "sdg_image_backend"));
      if (!entry || entry()->version != kImageBackendVersion) {
        problem = path + " is not this build's image module";
        return;
      }
      loaded = entry();
      return;
    }
    problem = "sdgbehave's image module (sdgbehave_images.so) is missing; looked at " + tried;
  });
  if (!loaded) throw RunError("reading images other than 8-bit PNG: " + problem);
  return *loaded;
}

template <typename T>
T viaModule(bool ok, T&& value, const std::string& error) {
  if (!ok) throw RunError(error);
  return std::move(value);
}

// Runs a fast-path step, turning its ImageError into the RunError callers see.
template <typename Body>
auto framed(Body body) {
  try {
    return body();
  } catch (const ImageError& e) {
    throw RunError(e.what());
  }
}

}  // namespace

float srgbToLinear(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float linear) {
  return linear <= 0.0031308f ? linear * 12.92f : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

ImageHeader readImageHeader(const std::string& path) {
  // PNG and JPEG headers are read here: `validate` then never opens the
  // image module, whose loading costs more than reading a stage.
  std::optional<ImageHeader> native = framed([&]() -> std::optional<ImageHeader> {
    Source src(path);
    if (isPng(src)) return pngHeader(src);
    return readJpegHeader(src);
  });
  if (native) return *native;
  ImageHeader header;
  std::string error;
  return viaModule(backend().readHeader(path, header, error), std::move(header), error);
}

ImageRgba8 loadImageRgba8(const std::string& path, TextureData data) {
  std::optional<ImageRgba8> png = framed([&]() -> std::optional<ImageRgba8> {
    Source src(path);
    return isPng(src) ? decodePng(src) : std::nullopt;
  });
  if (png) return std::move(*png);  // 8-bit values are what both kinds of data keep
  ImageRgba8 image;
  std::string error;
  return viaModule(backend().loadRgba8(path, data, image, error), std::move(image), error);
}

ImageRgbaF loadImageLinear(const std::string& path) {
  std::optional<ImageRgba8> png = framed([&]() -> std::optional<ImageRgba8> {
    Source src(path);
    return isPng(src) ? decodePng(src) : std::nullopt;
  });
  if (png) return linearOf(*png);
  ImageRgbaF image;
  std::string error;
  return viaModule(backend().loadLinear(path, image, error), std::move(image), error);
}

ImageRgba8 decodeImageRgba8(const void* bytes, size_t size, const std::string& name, TextureData data) {
  std::optional<ImageRgba8> png = framed([&]() -> std::optional<ImageRgba8> {
    Source src(bytes, size, name);
    return isPng(src) ? decodePng(src) : std::nullopt;
  });
  if (png) return std::move(*png);
  ImageRgba8 image;
  std::string error;
  return viaModule(backend().decodeRgba8(bytes, size, name, data, image, error), std::move(image), error);
}

ImageRgbaF decodeImageLinear(const void* bytes, size_t size, const std::string& name) {
  std::optional<ImageRgba8> png = framed([&]() -> std::optional<ImageRgba8> {
    Source src(bytes, size, name);
    return isPng(src) ? decodePng(src) : std::nullopt;
  });
  if (png) return linearOf(*png);
  ImageRgbaF image;
  std::string error;
  return viaModule(backend().decodeLinear(bytes, size, name, image, error), std::move(image), error);
}

}  // namespace sdg
