#include "assets/jpeg_header.h"

namespace sdg {
namespace {

using image_framing::Source;

// Start-of-frame markers: C0-CF except DHT (C4), JPG (C8) and DAC (CC).
bool isStartOfFrame(unsigned char marker) {
  return marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
}

// Markers that stand alone, without a length: TEM and the restart markers.
bool standsAlone(unsigned char marker) { return marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7); }

// Documented bound on the marker segments walked before the frame header
// (real files have a handful: APPn, DQT, DHT, COM).
constexpr int kMaxSegmentsBeforeFrame = 4096;

}  // namespace

std::optional<ImageHeader> readJpegHeader(Source& src) {
  unsigned char soi[3];
  if (!src.readAll(0, 3, soi) || soi[0] != 0xFF || soi[1] != 0xD8 || soi[2] != 0xFF) return std::nullopt;
  uint64_t pos = 2;
  for (int segment = 0; segment < kMaxSegmentsBeforeFrame; ++segment) {
    unsigned char byte = 0;
    if (!src.readAll(pos, 1, &byte)) image_framing::truncated(src, "JPEG", "before its frame header");
    if (byte != 0xFF)
      image_framing::corrupt(src, "JPEG", "no marker starts where one should, at byte " + std::to_string(pos));
    // Any number of 0xFF fill bytes may come before a marker's code.
    do {
      ++pos;
      if (!src.readAll(pos, 1, &byte)) image_framing::truncated(src, "JPEG", "before its frame header");
    } while (byte == 0xFF);
    const unsigned char marker = byte;
    ++pos;
    if (standsAlone(marker)) continue;
    if (marker == 0x00 || marker == 0xD8 || marker == 0xD9 || marker == 0xDA)
      image_framing::corrupt(src, "JPEG", "it has no frame header (SOF) before its image data");
    unsigned char length[2];
    if (!src.readAll(pos, 2, length)) image_framing::truncated(src, "JPEG", "inside a marker segment");
    const uint32_t size = uint32_t(length[0]) << 8 | length[1];
    if (size < 2) image_framing::corrupt(src, "JPEG", "a marker segment declares a length under 2");
    if (isStartOfFrame(marker)) {
      unsigned char frame[6];  // precision, height, width, components
      if (size < 8) image_framing::corrupt(src, "JPEG", "its frame header is too short");
      if (!src.readAll(pos + 2, 6, frame)) image_framing::truncated(src, "JPEG", "inside its frame header");
      const uint32_t height = uint32_t(frame[1]) << 8 | frame[2];
      const uint32_t width = uint32_t(frame[3]) << 8 | frame[4];
      const int components = frame[5];
      if (width == 0 || height == 0)
        image_framing::corrupt(src, "JPEG", "its frame header declares no pixels (or a height left to a DNL marker)");
      if (components != 1 && components != 3 && components != 4)
        image_framing::corrupt(src, "JPEG",
                               "its frame header declares " + std::to_string(components) + " components");
      image_framing::checkLimits(src.name(), "JPEG", width, height);
      ImageHeader h;
      h.width = width;
      h.height = height;
      h.channels = components == 1 ? 1 : 3;  // CMYK and YCCK are read as RGB
      h.bitsPerChannel = frame[0] > 8 ? 16 : 8;
      h.format = "jpeg";
      return h;
    }
    pos += size;
  }
  image_framing::corrupt(src, "JPEG",
                         "more than " + std::to_string(kMaxSegmentsBeforeFrame) + " marker segments before its frame");
}

}  // namespace sdg
