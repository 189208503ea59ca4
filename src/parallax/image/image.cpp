#include "parallax/image/image.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace parallax {

Vec3f Image::sampleBilinear(float u, float v) const {
  if (pixels_.empty()) return Vec3f(0.0f);
  // Texel centres at (i + 0.5) / width; row 0 is the top, so v = 1 is y = 0.
  const float fx = (u - std::floor(u)) * float(width_) - 0.5f;
  const float fy = (1.0f - (v - std::floor(v))) * float(height_) - 0.5f;
  const float x0f = std::floor(fx), y0f = std::floor(fy);
  const float tx = fx - x0f, ty = fy - y0f;
  auto wrap = [](int i, int n) { return ((i % n) + n) % n; };
  const int x0 = wrap(int(x0f), width_), x1 = wrap(int(x0f) + 1, width_);
  const int y0 = wrap(int(y0f), height_), y1 = wrap(int(y0f) + 1, height_);
  const Vec3f top = at(x0, y0) * (1 - tx) + at(x1, y0) * tx;
  const Vec3f bottom = at(x0, y1) * (1 - tx) + at(x1, y1) * tx;
  return top * (1 - ty) + bottom * ty;
}

float srgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float l) {
  return l <= 0.0031308f ? l * 12.92f : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
}

uint8_t linearToSrgb8(float l) {
  if (!(l > 0.0f)) return 0;  // also maps NaN to 0
  if (l >= 1.0f) return 255;
  return uint8_t(std::lround(linearToSrgb(l) * 255.0f));
}

float srgb8ToLinear(uint8_t code) {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[size_t(i)] = srgbToLinear(float(i) / 255.0f);
    return t;
  }();
  return table[code];
}

}  // namespace parallax
