#include "parallax/image/image.h"

#include <gtest/gtest.h>

namespace parallax {
namespace {

TEST(Srgb, RoundTripsEveryCode) {
  for (int i = 0; i < 256; ++i) EXPECT_EQ(linearToSrgb8(srgb8ToLinear(uint8_t(i))), i);
}

TEST(Srgb, MatchesStandardAnchors) {
  // IEC 61966-2-1: code 0.5 encodes linear 0.21404; the linear segment ends at 0.04045.
  EXPECT_NEAR(srgbToLinear(0.5f), 0.214041f, 1e-5f);
  EXPECT_NEAR(srgbToLinear(0.04045f), 0.04045f / 12.92f, 1e-7f);
  EXPECT_EQ(linearToSrgb8(-1.0f), 0);
  EXPECT_EQ(linearToSrgb8(2.0f), 255);
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
