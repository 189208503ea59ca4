// The layer problem's targets (layer_problem.h): the sRGB encoding they are fitted in, and the
// 16-bit codes a training view keeps them as.
#include "parallax/layers/layer_problem.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "parallax/layers/layer_solvers_test_support.h"

namespace parallax {
namespace {

using namespace layer_test;

// The arithmetic sRGB encoding against IEC 61966-2-1's formula in double, over [0, 1] (both
// segments), below 0 and above 1 (clamped: slope 0).
TEST(SrgbEncode, IsTheStandardsFormula) {
  double worstValue = 0, worstSlope = 0;
  for (int i = -100; i <= 120000; ++i) {
    const float x = float(i) / 100000.0f;
    float encoded = 0, slope = 0;
    detail::srgbEncode(x, encoded, slope);
    const double c = std::clamp(double(x), 0.0, 1.0);
    const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
    const double ds = x > 1.0f         ? 0.0
                      : c <= 0.0031308 ? 12.92
                                       : 1.055 / 2.4 * std::pow(c, 1 / 2.4 - 1);
    worstValue = std::max(worstValue, std::abs(encoded - s));
    worstSlope = std::max(worstSlope, std::abs(slope - ds) / std::max(1.0, ds));
  }
  EXPECT_LT(worstValue, 3e-7);
  EXPECT_LT(worstSlope, 1e-6);
}

// TrainingView::encodeTarget's codes are round(65535 S(t / c)), S the standard's formula in
// double: exactly wherever 65535 S lies more than 0.025 from a half (the float encoding is
// within 3e-7 of S, 0.02 of a code), and within one code nearer a half. A fine sweep
// over [0, 1.2] (both segments of S, the clamp above 1) and values whose 65535 S is a half.
TEST(TrainingView, EncodedTargetIsTheRoundedEncoding) {
  std::vector<float> values;
  for (int i = 0; i <= 240000; ++i) values.push_back(float(i) / 200000.0f);
  for (int code = 0; code < 65535; code += 97) {
    const double s = (code + 0.5) / 65535.0;  // S^-1 of it, in S's power segment or linear one
    values.push_back(float(s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4)));
  }
  while (values.size() % 3 != 0) values.push_back(0.5f);
  const int width = int(values.size() / 3);
  const DisplayDesign d = smallImageInFront();
  TrainingView view{SeenLayers(d, eyesAcross(d).front()), Image(width, 1)};
  for (int x = 0; x < width; ++x)
    for (int c = 0; c < 3; ++c) view.target.at(x, 0)[c] = 0.8f * values[size_t(3 * x + c)];
  view.encodingScale = 0.8f;
  const Image target = view.target;
  view.encodeTarget(2);
  ASSERT_EQ(view.encodedTarget.size(), 3 * size_t(width));
  int exactOnes = 0;
  for (int x = 0; x < width; ++x)
    for (int c = 0; c < 3; ++c) {
      const double t = std::clamp(double(target.at(x, 0)[c] * (1.0f / 0.8f)), 0.0, 1.0);
      const double scaled =
          65535.0 * (t <= 0.0031308 ? 12.92 * t : 1.055 * std::pow(t, 1 / 2.4) - 0.055);
      const long exact = std::lround(scaled), code = long(view.encodedTarget[size_t(3 * x + c)]);
      const bool nearHalf = std::abs(scaled - std::floor(scaled) - 0.5) <= 0.025;
      if (nearHalf) {
        EXPECT_LE(std::abs(code - exact), 1) << scaled;
      } else {
        EXPECT_EQ(code, exact) << scaled;
        exactOnes += 1;
      }
    }
  EXPECT_GT(exactOnes, 3 * width * 9 / 10);  // most values are far from a half
}

}  // namespace
}  // namespace parallax
