#include "parallax/scene/look.h"

#include <gtest/gtest.h>

#include <cmath>

namespace parallax {
namespace {

double srgbEncode(double x) {
  return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
}

TEST(Look, StandardIsTheExposureAlone) {
  const Vec3f light(0.3f, 1.7f, 0.0f);
  EXPECT_TRUE(Look{}.identity());
  EXPECT_EQ(Look{}.apply(light), light);
  for (const double stops : {-2.0, 1.0, 3.0}) {
    const Look look{stops, ViewTransform::Standard};
    EXPECT_FALSE(look.identity());
    const Vec3f seen = look.apply(light);
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(seen[c], light[c] * float(std::exp2(stops)));
  }
}

// The filmic curve against its definition (look.h): 16.5 stops from 10 below middle grey, black
// below them and white above, middle grey at its standard sRGB code, increasing and continuous
// in between, and a shoulder: light the standard transform clips stays below white.
TEST(Look, FilmicRollsOffOverSixteenAndAHalfStops) {
  EXPECT_EQ(filmicCurve(0.0f), 0.0f);
  EXPECT_EQ(filmicCurve(-1.0f), 0.0f);
  EXPECT_EQ(filmicCurve(float(0.18 * std::exp2(-10.5))), 0.0f);
  EXPECT_EQ(filmicCurve(float(0.18 * std::exp2(6.6))), 1.0f);
  EXPECT_NEAR(srgbEncode(filmicCurve(0.18f)), srgbEncode(0.18), 1e-4);
  EXPECT_LT(filmicCurve(2.0f), 1.0f);
  EXPECT_GT(filmicCurve(2.0f), filmicCurve(1.0f));
  float previous = 0.0f;
  for (int i = -1050; i <= 650; ++i) {
    const float x = float(0.18 * std::exp2(i / 100.0));
    const float y = filmicCurve(x);
    EXPECT_GE(y, previous) << x;
    EXPECT_LE(y - previous, 0.02f) << x;  // no jump: a smooth curve over 0.01-stop steps
    EXPECT_GE(y, 0.0f);
    EXPECT_LE(y, 1.0f);
    previous = y;
  }
  const Look look{1.0, ViewTransform::Filmic};
  const Vec3f seen = look.apply(Vec3f(0.09f, 0.5f, 8.0f));
  EXPECT_FLOAT_EQ(seen.x, filmicCurve(0.18f));
  EXPECT_FLOAT_EQ(seen.y, filmicCurve(1.0f));
  EXPECT_FLOAT_EQ(seen.z, filmicCurve(16.0f));
}

TEST(Look, NamesItsTransforms) {
  EXPECT_EQ(parseViewTransform("standard"), ViewTransform::Standard);
  EXPECT_EQ(parseViewTransform("filmic"), ViewTransform::Filmic);
  EXPECT_FALSE(parseViewTransform("Filmic").has_value());
  EXPECT_STREQ(viewTransformName(ViewTransform::Filmic), "filmic");
  EXPECT_STREQ(viewTransformName(ViewTransform::Standard), "standard");
}

}  // namespace
}  // namespace parallax
