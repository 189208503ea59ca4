// Image files. Reading: PNG, JPEG (8-bit sRGB, decoded to linear) and PFM (linear float).
// Writing, by extension: .png (8-bit sRGB) and .pfm (linear float). Writes go to a temporary
// name beside the target and are renamed into place, so no half-written file is ever left.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "parallax/image/image.h"

namespace parallax {

// Images larger than this are refused from their header, before decoding: at most
// kMaxImageSide pixels a side and about kMaxImageDecodeBytes for the decoded pixels plus the
// linear image (a few hundred bytes can announce gigabytes).
inline constexpr int64_t kMaxImageSide = 1 << 16;
inline constexpr int64_t kMaxImageDecodeBytes = int64_t(2) << 30;

// Throws InputError (naming the file) if it is missing, not a regular file, unreadable, not
// an image, another format than its extension claims, too large (see above), or a PFM with
// NaN or infinite pixels.
Image readImage(const std::string& path);
// What a file's header announces, read without decoding it (stb_image's info): its size, its
// channels and bytes per sample, and the file's bytes; all 0 when the header is not readable
// (readImage then refuses the file). For memory estimates before reading.
struct ImageInfo {
  int width = 0, height = 0, channels = 0, bytesPerSample = 0;
  double fileBytes = 0;
};
ImageInfo readImageInfo(const std::string& path);
// The samples of an image file as stored, without the sRGB transfer function: what a depth map
// holds. 8- and 16-bit codes are divided by 255 or 65535 (a 16-bit PNG keeps its 16 bits), PFM
// and Radiance HDR floats are as stored (a grey PFM as three equal channels). The same checks
// and InputErrors as readImage.
struct ImageSamples {
  int width = 0, height = 0;
  int channels = 0;            // as in the file: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA
  int bitsPerSample = 0;       // 8, 16, or 32 for floats
  std::vector<float> samples;  // width x height x channels, row 0 at the top
};
ImageSamples readImageSamples(const std::string& path);
// The same for bytes in memory (an image embedded in a glTF file); `name` names them in
// errors, and its extension, if any, must agree with the contents.
Image decodeImage(std::string_view bytes, const std::string& name);
// Throws InputError for an unknown extension and std::runtime_error for an I/O failure.
void writeImage(const std::string& path, const Image& image);
// The bytes of an 8-bit sRGB PNG of `image` (linear light, clamped to [0,1]), in memory, encoded
// on every core (io/png_encoder.h). A grey picture is written with one channel unless
// `greyAsOneChannel` is false (frames of one animation must share their colour type).
// Throws std::invalid_argument for an empty image.
std::string pngBytes(const Image& image, bool greyAsOneChannel = true);
// The same from 8-bit sRGB codes already made (width x height RGB triples, row 0 at the top;
// the buffer is reused for the one-channel copy of a grey picture).
std::string pngBytesFromSrgb8(std::vector<uint8_t>& rgbCodes, int width, int height,
                              bool greyAsOneChannel = true);
// Writes bytes to `path` atomically (temporary file PATH.tmp-PID + rename); creates missing
// parent folders, and removes the PATH.tmp-PID and PATH.partial-PID of killed runs.
void writeFileAtomically(const std::string& path, std::string_view bytes);

}  // namespace parallax
