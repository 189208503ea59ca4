#include "parallax/image/image.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

namespace parallax {
namespace {

TEST(Srgb, RoundTripsEveryCode) {
  for (int i = 0; i < 256; ++i) EXPECT_EQ(linearToSrgb8(srgb8ToLinear(uint8_t(i))), i);
}

// The encoder's definition written out the slow way: the forward transfer function in double
// precision, rounded to the nearest code (halves up).
int slowSrgb8(float linear) {
  const double l = std::clamp(double(linear), 0.0, 1.0);
  const double encoded = l <= 0.0031308 ? l * 12.92 : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
  return int(std::floor(encoded * 255.0 + 0.5));
}

TEST(Srgb, TableEncoderEqualsTheTransferFunctionEverywhere) {
  // Every 61st float in [0, 1] (17 million values, every run of the table many times over),
  // and the floats on either side of every code's step.
  int mismatches = 0;
  for (uint32_t bits = 0; bits <= 0x3f800000u; bits += 61) {
    const float l = std::bit_cast<float>(bits);
    mismatches += linearToSrgb8(l) != slowSrgb8(l);
  }
  for (int code = 1; code < 256; ++code) {
    const double encoded = (code - 0.5) / 255.0;
    const float step =
        float(encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4));
    float l = std::nextafter(std::nextafter(step, 0.0f), 0.0f);
    for (int i = 0; i < 5; ++i, l = std::nextafter(l, 2.0f))
      mismatches += linearToSrgb8(l) != slowSrgb8(l);
  }
  EXPECT_EQ(mismatches, 0);
  // The batch form is the same function.
  std::vector<float> values;
  for (uint32_t bits = 0; bits <= 0x3f900000u; bits += 4099)
    values.push_back(std::bit_cast<float>(bits));
  values.push_back(-1.0f);
  values.push_back(std::nanf(""));
  std::vector<uint8_t> codes(values.size());
  linearToSrgb8(values.data(), values.size(), codes.data());
  for (size_t i = 0; i < values.size(); ++i) ASSERT_EQ(codes[i], linearToSrgb8(values[i])) << i;
  EXPECT_EQ(linearToSrgb8(std::nanf("")), 0);
  EXPECT_EQ(linearToSrgb8(1.0f), 255);
  EXPECT_EQ(linearToSrgb8(std::nextafter(1.0f, 0.0f)), 255);
}

TEST(Srgb, MatchesStandardAnchors) {
  // IEC 61966-2-1: code 0.5 encodes linear 0.21404; the linear segment ends at 0.04045.
  EXPECT_NEAR(srgbToLinear(0.5f), 0.214041f, 1e-5f);
  EXPECT_NEAR(srgbToLinear(0.04045f), 0.04045f / 12.92f, 1e-7f);
  EXPECT_EQ(linearToSrgb8(-1.0f), 0);
  EXPECT_EQ(linearToSrgb8(2.0f), 255);
}

TEST(Image, WholePicturesLieInHugePageAlignedBlocks) {
  const Image picture(1024, 1024, Vec3f(0.25f));
  EXPECT_EQ(reinterpret_cast<uintptr_t>(picture.pixels().data()) % (size_t(2) << 20), 0u);
  EXPECT_EQ(picture.at(1023, 1023), Vec3f(0.25f));
}

TEST(Image, BilinearHitsTexelCentresAndWraps) {
  Image img(2, 1);
  img.at(0, 0) = Vec3f(0.0f);
  img.at(1, 0) = Vec3f(1.0f);
  EXPECT_FLOAT_EQ(img.sampleBilinear(0.25f, 0.5f).x, 0.0f);
  EXPECT_FLOAT_EQ(img.sampleBilinear(0.75f, 0.5f).x, 1.0f);
  EXPECT_FLOAT_EQ(img.sampleBilinear(0.5f, 0.5f).x, 0.5f);
  // u = 0 lies halfway between the last texel (wrapped) and the first.
  EXPECT_FLOAT_EQ(img.sampleBilinear(0.0f, 0.5f).x, 0.5f);
  EXPECT_FLOAT_EQ(img.sampleBilinear(1.25f, 0.5f).x, 0.0f);
}

}  // namespace
}  // namespace parallax
