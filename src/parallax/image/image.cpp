#include "parallax/image/image.h"

#include "parallax/core/lane_kernel.h"

#include "parallax/core/error.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

namespace parallax {

namespace {

// Weights of input cells [i, i + 1) in the output cells [o r, (o + 1) r), r = in / out.
struct AreaWeight {
  int input;
  double weight;
};
std::vector<std::vector<AreaWeight>> areaWeights(int inSize, int outSize) {
  const double r = double(inSize) / double(outSize);
  std::vector<std::vector<AreaWeight>> weights(static_cast<size_t>(outSize));
  for (int o = 0; o < outSize; ++o) {
    const double lo = o * r, hi = (o + 1) * r;
    for (int i = int(std::floor(lo)); i < std::min(inSize, int(std::ceil(hi))); ++i) {
      const double overlap = std::min(hi, i + 1.0) - std::max(lo, double(i));
      if (overlap > 0) weights[size_t(o)].push_back({i, overlap / r});
    }
  }
  return weights;
}

}  // namespace

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

Image resizeArea(const Image& image, int width, int height) {
  if (width < 1 || height < 1 || image.empty())
    throw InputError("", "", "area resampling needs a non-empty image and a positive size");
  const auto across = areaWeights(image.width(), width), down = areaWeights(image.height(), height);
  Image wide(width, image.height());
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < width; ++x) {
      Vec3f sum(0.0f);
      for (const AreaWeight& a : across[size_t(x)]) sum += image.at(a.input, y) * float(a.weight);
      wide.at(x, y) = sum;
    }
  Image out(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      Vec3f sum(0.0f);
      for (const AreaWeight& a : down[size_t(y)]) sum += wide.at(x, a.input) * float(a.weight);
      out.at(x, y) = sum;
    }
  return out;
}

float srgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float l) {
  return l <= 0.0031308f ? l * 12.92f : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
}

namespace {

// linearToSrgb8 without a pow per value: the 255 linear thresholds where the code steps up,
// and, for each run of 2^16 consecutive floats (their bit patterns' top 16 bits), the code of
// the run's first float. A run spans 1/128 of an octave, across which the code climbs by less
// than one step (at most 112 codes per e-fold, at l = 1), so a lookup ends after at most two
// comparisons.
struct SrgbEncodeTable {
  std::array<float, 255> threshold{};  // threshold[k]: the least float whose code exceeds k
  std::vector<uint8_t> runStart;       // the code of the float (run << 16)

  SrgbEncodeTable() {
    for (int k = 0; k < 255; ++k) {
      // The linear value whose sRGB code is exactly k + 1/2, in double precision.
      const double encoded = (k + 0.5) / 255.0;
      const double linear =
          encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
      float t = float(linear);
      if (double(t) < linear) t = std::nextafter(t, 2.0f);
      threshold[size_t(k)] = t;
    }
    const uint32_t runs = 0x3f800000u >> 16;  // the runs of floats in [0, 1)
    runStart.resize(runs);
    for (uint32_t run = 0; run < runs; ++run) {
      const float first = std::bit_cast<float>(run << 16);
      runStart[run] =
          uint8_t(std::upper_bound(threshold.begin(), threshold.end(), first) - threshold.begin());
    }
  }
};

const SrgbEncodeTable& srgbEncodeTable() {
  static const SrgbEncodeTable table;
  return table;
}

inline uint8_t encodeWith(const SrgbEncodeTable& table, float l) {
  if (!(l > 0.0f)) return 0;  // also maps NaN to 0
  if (l >= 1.0f) return 255;
  unsigned code = table.runStart[std::bit_cast<uint32_t>(l) >> 16];
  while (code < 255 && l >= table.threshold[code]) ++code;
  return uint8_t(code);
}

}  // namespace

uint8_t linearToSrgb8(float l) {
  return encodeWith(srgbEncodeTable(), l);
}

PARALLAX_LANE_KERNEL void linearToSrgb8(const float* linear, size_t count, uint8_t* codes) {
  const SrgbEncodeTable& table = srgbEncodeTable();
  for (size_t i = 0; i < count; ++i) codes[i] = encodeWith(table, linear[i]);
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
