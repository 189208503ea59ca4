// Image files (textures, and the image and mask layers that simulate and interlace read):
// PNG, JPEG, PFM and whatever else stb_image recognises, through io::readImage, which picks
// the decoder by content.
#include "fuzz_support.h"
#include "parallax/image/image.h"
#include "parallax/io/image_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace parallax::fuzz;
  const std::string path = writeScratch("fuzz.img", asText(data, size));
  return refuseCleanly([&] { parallax::readImage(path); });
}
