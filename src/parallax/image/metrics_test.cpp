// Metrics against hand-computed values: PSNR of a known offset, SSIM's luminance term in closed
// form, box filters against brute-force integration.
#include "parallax/image/metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/core/random.h"
#include "parallax/image/srgb_arithmetic.h"

namespace parallax {
namespace {

// An image whose sRGB-encoded grey values are encoded(x, y).
template <class F>
Image fromEncoded(int width, int height, const F& encoded) {
  Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.at(x, y) = Vec3f(srgbToLinear(float(encoded(x, y))));
  return image;
}

TEST(Metrics, PsnrOfAConstantOffsetIsTenLogOfOneOverItsSquare) {
  Rng rng(5);
  std::vector<double> values(40 * 30);
  for (double& v : values) v = 0.1 + 0.7 * rng.uniform();
  const auto base = [&](int x, int y) { return values[size_t(y * 40 + x)]; };
  const Image a = fromEncoded(40, 30, base);
  const Image b = fromEncoded(40, 30, [&](int x, int y) { return base(x, y) + 0.05; });
  // Encoded values differ by 0.05 everywhere: MSE = 0.0025.
  EXPECT_NEAR(psnr(a, b), 10 * std::log10(1 / 0.0025), 1e-3);
  EXPECT_NEAR(psnr(a, b, 2.0), 10 * std::log10(4 / 0.0025), 1e-3);
  EXPECT_TRUE(std::isinf(psnr(a, a)));
  // In linear light: an offset of 0.1 gives 20 dB.
  Image c = a;
  for (Vec3f& p : c.pixels()) p += Vec3f(0.1f);
  EXPECT_NEAR(psnr(a, c, 1.0, MetricEncoding::Linear), 20.0, 1e-4);
}

// The dense measure's one-pass comparison against the separate metrics and a brute-force
// flicker sum, on rows that leave every remainder of 16 values.
TEST(Metrics, OnePassComparisonEqualsTheSeparateMetrics) {
  Rng rng(23);
  const auto randomImage = [&](int width, int height) {
    Image image(width, height);
    for (Vec3f& p : image.pixels())
      for (int c = 0; c < 3; ++c) p[c] = float(1.2 * rng.uniform() - 0.1);  // some clamped
    return image;
  };
  for (const int width : {1, 6, 16, 37}) {
    const Image picture = randomImage(width, 5), ideal = randomImage(width, 5);
    const Image before = randomImage(width, 5), idealBefore = randomImage(width, 5);
    const Image idealEncoded = srgbEncoded(ideal);
    const EncodedComparison alone = compareEncoded(picture, idealEncoded);
    const Image beforeEncoded = srgbEncoded(before), idealBeforeEncoded = srgbEncoded(idealBefore);
    const EncodedComparison c =
        compareEncoded(picture, idealEncoded, &beforeEncoded, &idealBeforeEncoded);
    const double values = 3.0 * double(picture.pixels().size());
    EXPECT_TRUE(std::isnan(alone.flickerSquares));
    EXPECT_EQ(alone.squaredError, c.squaredError);
    EXPECT_NEAR(c.squaredError / values,
                meanSquaredError(srgbEncoded(picture), idealEncoded, MetricEncoding::Linear),
                1e-12);
    EXPECT_NEAR(c.squaredError / values, meanSquaredError(picture, ideal), 1e-6);
    EXPECT_NEAR(c.luminance / double(picture.pixels().size()), meanLuminance(picture), 1e-12);
    double flicker = 0;
    const Image encoded = srgbEncoded(picture);
    for (size_t i = 0; i < picture.pixels().size(); ++i)
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(c.encoded.pixels()[i][k], encoded.pixels()[i][k]);
        const double now = double(encoded.pixels()[i][k]) - double(idealEncoded.pixels()[i][k]);
        const double then =
            double(beforeEncoded.pixels()[i][k]) - double(idealBeforeEncoded.pixels()[i][k]);
        flicker += (now - then) * (now - then);
      }
    EXPECT_NEAR(c.flickerSquares, flicker, 1e-9 * values);
  }
}

// The mean squared error (in lanes of 16 along each row, in double) against the sum of every
// squared difference one by one, on rows of lengths that leave every remainder of 16 values.
TEST(Metrics, MeanSquaredErrorIsTheBruteForceSum) {
  Rng rng(11);
  for (const int width : {1, 5, 16, 21, 333}) {
    Image a(width, 3), b(width, 3);
    for (size_t i = 0; i < a.pixels().size(); ++i)
      for (int c = 0; c < 3; ++c) {
        a.pixels()[i][c] = float(rng.uniform());
        b.pixels()[i][c] = float(rng.uniform());
      }
    double sum = 0;
    for (size_t i = 0; i < a.pixels().size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const double d = double(a.pixels()[i][c]) - double(b.pixels()[i][c]);
        sum += d * d;
      }
    const double expected = sum / (3.0 * double(a.pixels().size()));
    EXPECT_NEAR(meanSquaredError(a, b, MetricEncoding::Linear), expected, 1e-12 * expected)
        << width;
  }
}

TEST(Metrics, SsimOfAnImageWithItselfIsOne) {
  Rng rng(9);
  Image a(32, 24);
  for (Vec3f& p : a.pixels()) p = Vec3f(rng.uniform(), rng.uniform(), rng.uniform());
  EXPECT_NEAR(ssim(a, a), 1.0, 1e-12);
  Image b = a;
  for (Vec3f& p : b.pixels()) p = p * 0.5f;
  EXPECT_LT(ssim(a, b), 0.99);
}

TEST(Metrics, SsimOfAShiftedCheckerboardIsItsLuminanceTerm) {
  // x = m + a (-1)^(i+j) (encoded), y = x + c. Then y - x is constant inside every window, so
  // sigma_x = sigma_y = sigma_xy and the contrast-structure term is exactly 1; SSIM is the
  // luminance term (2 mu_x mu_y + C1) / (mu_x^2 + mu_y^2 + C1) with mu_y = mu_x + c. The
  // Gaussian window (11 x 11, sigma 1.5) sees mean m + a (-1)^(i0+j0) beta, where
  // beta = (sum_d g_d (-1)^d)^2 with g the normalised 1-D weights.
  const double m = 0.4, a = 0.1, c = 0.2, C1 = 1e-4;
  const int w = 30, h = 20;
  const Image x = fromEncoded(w, h, [&](int i, int j) { return m + a * ((i + j) % 2 ? -1 : 1); });
  const Image y =
      fromEncoded(w, h, [&](int i, int j) { return m + c + a * ((i + j) % 2 ? -1 : 1); });
  double g[11], total = 0, alternating = 0;
  for (int d = -5; d <= 5; ++d) total += g[d + 5] = std::exp(-d * d / (2 * 1.5 * 1.5));
  for (int d = -5; d <= 5; ++d) alternating += (d % 2 ? -1 : 1) * g[d + 5] / total;
  const double beta = alternating * alternating;
  double expected = 0;
  int windows = 0;
  for (int j0 = 5; j0 < h - 5; ++j0)
    for (int i0 = 5; i0 < w - 5; ++i0, ++windows) {
      const double mx = m + a * ((i0 + j0) % 2 ? -1 : 1) * beta, my = mx + c;
      expected += (2 * mx * my + C1) / (mx * mx + my * my + C1);
    }
  EXPECT_NEAR(ssim(x, y), expected / windows, 1e-5);
  EXPECT_LT(ssim(x, y), 0.97);  // the shift is not free
}

// The dense measure's sRGB pictures (srgbEncoded, a vectorised arithmetic encoding) are the
// standard's formula in double, the value clamped to [0, 1] first: both segments, below 0,
// above 1, rows of odd lengths (the loops' remainders).
TEST(Metrics, SrgbEncodedIsTheStandardsFormula) {
  for (const int width : {1, 7, 333}) {
    Image image(width, 40);
    int i = 0;
    for (Vec3f& p : image.pixels())
      for (int c = 0; c < 3; ++c, ++i) p[c] = -0.05f + 1.2f * float(i % 9973) / 9972.0f;
    const Image encoded = srgbEncoded(image);
    double worst = 0;
    for (size_t k = 0; k < image.pixels().size(); ++k)
      for (int c = 0; c < 3; ++c) {
        const double x = std::clamp(double(image.pixels()[k][c]), 0.0, 1.0);
        const double s = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
        worst = std::max(worst, std::abs(double(encoded.pixels()[k][c]) - s));
      }
    EXPECT_LT(worst, 3e-7) << width;
  }
}

// The encoding of 16 lanes at once (FloatLanes16, what the dense measure's pictures and the
// layer solvers' errors use) is the one-value encoding bit for bit: the same operations in the
// same order, wherever the lanes come from: both segments, the clamps below 0 and above 1, the
// values next to the segments' border, 1 and the smallest ones, infinities.
TEST(SrgbEncode, LanesSideBySideAreSingleValues) {
  std::vector<float> values = {-INFINITY,
                               -1.0f,
                               -0.0f,
                               0.0f,
                               1e-45f,
                               1e-31f,
                               1e-30f,
                               1e-20f,
                               0.0031308f,
                               std::nextafter(0.0031308f, 0.0f),
                               std::nextafter(0.0031308f, 1.0f),
                               0.5f,
                               std::nextafter(1.0f, 0.0f),
                               1.0f,
                               std::nextafter(1.0f, 2.0f),
                               2.0f,
                               1e30f,
                               INFINITY};
  Rng rng(5);
  for (int i = 0; i < 4000; ++i) values.push_back(float(rng.uniform()));
  for (int i = 0; i < 400; ++i) values.push_back(std::ldexp(float(rng.uniform()), -int(i % 90)));
  while (values.size() % 48) values.push_back(0.25f);
  for (size_t base = 0; base < values.size(); base += 16) {
    FloatLanes16 x, encoded, slope;
    for (int l = 0; l < 16; ++l) x[l] = values[base + size_t(l)];
    srgbEncodeArithmetic<FloatLanes16, IntLanes16>(x, encoded, slope);
    for (int l = 0; l < 16; ++l) {
      float oneEncoded = 0, oneSlope = 0;
      srgbEncodeArithmetic(x[l], oneEncoded, oneSlope);
      EXPECT_EQ(std::bit_cast<uint32_t>(encoded[l]), std::bit_cast<uint32_t>(oneEncoded)) << x[l];
      EXPECT_EQ(std::bit_cast<uint32_t>(slope[l]), std::bit_cast<uint32_t>(oneSlope)) << x[l];
    }
  }
  // Three vectors side by side (the steps interleaved) give each value's own bits as well.
  for (size_t base = 0; base < values.size(); base += 48) {
    FloatLanes16 x[3], encoded[3], slope[3];
    for (int v = 0; v < 3; ++v)
      for (int l = 0; l < 16; ++l) x[v][l] = values[base + 16 * size_t(v) + size_t(l)];
    srgbEncodeArithmetic<FloatLanes16, IntLanes16, 3>(x, encoded, slope);
    for (int v = 0; v < 3; ++v)
      for (int l = 0; l < 16; ++l) {
        float oneEncoded = 0, oneSlope = 0;
        srgbEncodeArithmetic(x[v][l], oneEncoded, oneSlope);
        EXPECT_EQ(std::bit_cast<uint32_t>(encoded[v][l]), std::bit_cast<uint32_t>(oneEncoded));
        EXPECT_EQ(std::bit_cast<uint32_t>(slope[v][l]), std::bit_cast<uint32_t>(oneSlope));
      }
  }
}

TEST(Metrics, BoxFilterMatchesBruteForceIntegration) {
  Rng rng(2);
  Image image(50, 2);
  for (Vec3f& p : image.pixels()) p = Vec3f(rng.uniform(), rng.uniform(), rng.uniform());
  for (double width : {1.0, 4.3, 9.045}) {
    const Image filtered = boxFilterX(image, width);
    for (int x = 0; x < 50; ++x) {
      // Midpoint rule over the clipped box, 20000 points.
      const double lo = std::max(0.0, x + 0.5 - width / 2),
                   hi = std::min(50.0, x + 0.5 + width / 2);
      double sum = 0;
      const int n = 20000;
      for (int s = 0; s < n; ++s) sum += image.at(int(lo + (s + 0.5) * (hi - lo) / n), 1).y;
      EXPECT_NEAR(filtered.at(x, 1).y, sum / n, 2e-4) << width << " " << x;
    }
  }
}

TEST(Metrics, BoxFilterOfOnePeriodFlattensStripesAndKeepsTheirMean) {
  for (int period : {9, 7}) {
    Image stripes(90, 3);
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 90; x += period) stripes.at(x, y) = Vec3f(1.0f);
    const Image flat = boxFilterX(stripes, period);
    for (int x = period; x < 90 - period; ++x)
      EXPECT_NEAR(flat.at(x, 1).x, 1.0 / period, 1e-6) << period << " " << x;
    // A mismatched width does not flatten them.
    const Image ripple = boxFilterX(stripes, period + 0.5);
    double lo = 1, hi = 0;
    for (int x = period; x < 90 - period; ++x)
      lo = std::min(lo, double(ripple.at(x, 1).x)), hi = std::max(hi, double(ripple.at(x, 1).x));
    EXPECT_GT(hi - lo, 0.02);
  }
  const Image grey(20, 2, Vec3f(0.3f));
  const Image greyFiltered = boxFilterX(grey, 6.5);
  for (const Vec3f& p : greyFiltered.pixels()) EXPECT_NEAR(p.x, 0.3f, 1e-6f);
}

TEST(Metrics, AreaResizeAveragesTheCoveredArea) {
  Image image(4, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) image.at(x, y) = Vec3f(float(x + 4 * y));
  const Image half = resizeArea(image, 2, 1);
  EXPECT_NEAR(half.at(0, 0).x, (0 + 1 + 4 + 5) / 4.0, 1e-6);
  EXPECT_NEAR(half.at(1, 0).x, (2 + 3 + 6 + 7) / 4.0, 1e-6);
  // 4 -> 3 columns: the middle output covers [4/3, 8/3): 2/3 of pixel 1 and 2/3 of pixel 2.
  const Image thirds = resizeArea(image, 3, 2);
  EXPECT_NEAR(thirds.at(1, 0).x, (1 + 2) / 2.0, 1e-6);
  EXPECT_NEAR(thirds.at(0, 0).x, (1.0 * 0 + 1.0 / 3 * 1) / (4.0 / 3), 1e-6);
  // Mass is kept for any ratio.
  Rng rng(4);
  Image random(17, 11);
  for (Vec3f& p : random.pixels()) p = Vec3f(rng.uniform());
  EXPECT_NEAR(meanLuminance(resizeArea(random, 5, 4)), meanLuminance(random), 1e-6);
}

TEST(Metrics, RejectMismatchedImages) {
  EXPECT_THROW(psnr(Image(4, 4), Image(4, 5)), InputError);
  EXPECT_THROW(ssim(Image(10, 10), Image(10, 10)), InputError);  // smaller than the window
  EXPECT_THROW(boxFilterX(Image(4, 4), 0.0), InputError);
}

}  // namespace
}  // namespace parallax

namespace parallax {
namespace {

TEST(Metrics, BoxFilterYIsBoxFilterXOfTheTranspose) {
  Image image(5, 7);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 5; ++x) image.at(x, y) = Vec3f(float((x * 3 + y * y) % 5));
  Image transposed(7, 5);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 5; ++x) transposed.at(y, x) = image.at(x, y);
  const Image a = boxFilterY(image, 2.5), b = boxFilterX(transposed, 2.5);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 5; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.at(x, y)[c], b.at(y, x)[c], 1e-6);
}

}  // namespace
}  // namespace parallax
