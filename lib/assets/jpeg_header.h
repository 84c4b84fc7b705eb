#pragma once
// The header of a JPEG file read here, without the image module: `validate`
// checks every texture's header, and opening OpenImageIO's module costs more
// than reading a whole stage (docs/usd.md). Only the frame header (SOFn)
// is read: size, components and sample precision.
#include <optional>

#include "assets/image.h"
#include "assets/image_framing.h"

namespace sdg {

// nullopt when the data does not start with a JPEG's SOI marker (FF D8 FF).
// Otherwise the frame's header, or image_framing::ImageError naming the file
// when the markers before the frame are truncated or malformed, the frame
// declares no pixels (or leaves its height to a DNL marker), or it exceeds
// the size limits.
std::optional<ImageHeader> readJpegHeader(image_framing::Source& src);

}  // namespace sdg
