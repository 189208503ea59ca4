// An RGB image in linear light, float per channel, row 0 at the top.
#pragma once

#include <cstdint>
#include <vector>

#include "parallax/core/math.h"
#include "parallax/core/memory.h"

namespace parallax {

class Image {
 public:
  Image() = default;
  Image(int width, int height, Vec3f fill = Vec3f(0.0f))
      : width_(width), height_(height), pixels_(size_t(width) * size_t(height), fill) {}

  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return pixels_.empty(); }

  Vec3f& at(int x, int y) { return pixels_[size_t(y) * size_t(width_) + size_t(x)]; }
  const Vec3f& at(int x, int y) const { return pixels_[size_t(y) * size_t(width_) + size_t(x)]; }
  // Contiguous, row by row; in large blocks (core/memory.h) for whole pictures.
  const LargeVector<Vec3f>& pixels() const { return pixels_; }
  LargeVector<Vec3f>& pixels() { return pixels_; }

  // Bilinear lookup at texture coordinates (u, v) in [0,1) with wrap-around; v = 0 is the
  // bottom row, as in OBJ and glTF-flipped UVs (see docs/scene-format.md).
  Vec3f sampleBilinear(float u, float v) const;

 private:
  int width_ = 0;
  int height_ = 0;
  LargeVector<Vec3f> pixels_;
};

// Area resampling to width x height: each output pixel is the mean of the input area it covers
// (fractional overlaps weighted), so the image's mean is kept exactly.
Image resizeArea(const Image& image, int width, int height);

// The sRGB transfer function (IEC 61966-2-1), per channel.
float srgbToLinear(float encoded);
float linearToSrgb(float linear);
// Linear [0,1] value to the nearest 8-bit sRGB code (halves round up, decided in double
// precision); values outside [0,1] are clamped, NaN is 0. A table lookup: no pow per value.
uint8_t linearToSrgb8(float linear);
// The same for `count` values at once (the table is looked up once, the loop inlined). An
// Image's pixels are contiguous floats, x y z per pixel, so a row is 3 x width of them.
void linearToSrgb8(const float* linear, size_t count, uint8_t* codes);
static_assert(sizeof(Vec3f) == 3 * sizeof(float), "Vec3f pixels are packed floats");
// Table-based decode of 8-bit sRGB codes.
float srgb8ToLinear(uint8_t code);

}  // namespace parallax
