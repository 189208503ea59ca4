// Photos from a phone (calibration from photos): JPEG and PNG bytes through decodePhoto, which
// reads the header with our own parser (size, EXIF orientation) before OpenCV decodes anything,
// then turns the picture upright. The limit of 4 megapixels keeps a lying header from asking
// for more memory than libFuzzer allows.
#include "fuzz_support.h"
#include "parallax/vision/vision.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return parallax::fuzz::refuseCleanly([&] {
    const parallax::vision::Photo photo =
        parallax::vision::decodePhoto({data, size}, "fuzz.jpg", 4'000'000);
    // The picture is as large as the header said once turned, every pixel there.
    if (photo.rgb.size() != size_t(photo.width) * size_t(photo.height) * 3) std::abort();
  });
}
