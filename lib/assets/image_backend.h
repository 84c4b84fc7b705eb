#pragma once
// The table through which assets/image.cpp calls the OpenImageIO module
// (assets/image_oiio.cpp, built as sdgbehave_images.so and opened on first
// use). Errors come back as text, never as exceptions across the boundary.
#include <cstddef>
#include <string>

#include "assets/image.h"

namespace sdg {

inline constexpr int kImageBackendVersion = 1;

struct ImageBackend {
  int version;  // kImageBackendVersion of the module's build
  bool (*readHeader)(const std::string& path, ImageHeader& out, std::string& error);
  bool (*loadRgba8)(const std::string& path, TextureData data, ImageRgba8& out, std::string& error);
  bool (*loadLinear)(const std::string& path, ImageRgbaF& out, std::string& error);
  bool (*decodeRgba8)(const void* bytes, size_t size, const std::string& name, TextureData data, ImageRgba8& out,
                      std::string& error);
  bool (*decodeLinear)(const void* bytes, size_t size, const std::string& name, ImageRgbaF& out, std::string& error);
};

}  // namespace sdg

// The module's one exported symbol.
extern "C" const sdg::ImageBackend* sdg_image_backend();
