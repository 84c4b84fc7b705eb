// libFuzzer harness: the input is an image file's bytes. `validate` reads
// every texture's header without decoding it (the JPEG frame header and the
// PNG chunk framing, lib/assets/): each must end in a header or an
// ImageError naming the file, never a crash or an out-of-bounds read.
#include <cstddef>
#include <cstdint>

#include "assets/image_framing.h"
#include "assets/jpeg_header.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    sdg::image_framing::Source jpeg(data, size, "fuzz.jpg");
    sdg::readJpegHeader(jpeg);
  } catch (const sdg::image_framing::ImageError&) {
  }
  try {
    sdg::image_framing::Source png(data, size, "fuzz.png");
    sdg::image_framing::checkPngFraming(png, /*wholeFile=*/true);
  } catch (const sdg::image_framing::ImageError&) {
  }
  return 0;
}
