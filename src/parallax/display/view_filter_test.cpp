// The view filters' offsets against their closed-form distributions: a box of width w has
// variance w^2 / 12, a triangle on [-w, w] w^2 / 6, a Gaussian of FWHM w (sigma = w / 2.3548)
// cut at 2 sigma sigma^2 (1 - 2 c phi(c) / (2 Phi(c) - 1)) with c = 2.
#include "parallax/display/view_filter.h"

#include <gtest/gtest.h>

#include <cmath>

namespace parallax {
namespace {

// Mean and variance of the warped offsets over a fine uniform grid of u (a quadrature).
std::pair<double, double> moments(const ViewFilter& filter) {
  const ViewFilterWarp warp(filter);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = warp((i + 0.5) / n);
    sum += x, sum2 += x * x;
  }
  const double mean = sum / n;
  return {mean, sum2 / n - mean * mean};
}

TEST(ViewFilter, BoxTentAndGaussianHaveTheirVariances) {
  for (double w : {0.5, 1.0, 2.0}) {
    const auto [boxMean, boxVar] = moments({ViewFilterKind::View, w});
    EXPECT_NEAR(boxMean, 0.0, 1e-9);
    EXPECT_NEAR(boxVar, w * w / 12, 1e-6 * w * w);
    const auto [tentMean, tentVar] = moments({ViewFilterKind::Tent, w});
    EXPECT_NEAR(tentMean, 0.0, 1e-9);
    EXPECT_NEAR(tentVar, w * w / 6, 1e-6 * w * w);
    const double sigma = w / (2 * std::sqrt(2 * std::log(2.0)));
    const double c = 2.0, phi = std::exp(-0.5 * c * c) / std::sqrt(2 * M_PI);
    const double truncated = sigma * sigma * (1 - 2 * c * phi / std::erf(c / std::sqrt(2.0)));
    const auto [gMean, gVar] = moments({ViewFilterKind::Gaussian, w});
    EXPECT_NEAR(gMean, 0.0, 1e-9);
    EXPECT_NEAR(gVar, truncated, 2e-3 * truncated);
  }
}

TEST(ViewFilter, SupportAndMonotonicity) {
  for (ViewFilterKind kind :
       {ViewFilterKind::View, ViewFilterKind::Tent, ViewFilterKind::Gaussian}) {
    const ViewFilterWarp warp({kind, 1.0});
    EXPECT_NEAR(warp(0.0), -warp.halfSupport(), 1e-9);
    EXPECT_NEAR(warp(1.0), warp.halfSupport(), 1e-9);
    EXPECT_NEAR(warp(0.5), 0.0, 1e-9);
    for (int i = 1; i <= 1000; ++i) EXPECT_LE(warp((i - 1) / 1000.0), warp(i / 1000.0));
  }
  EXPECT_DOUBLE_EQ(ViewFilterWarp({ViewFilterKind::View, 1.0}).halfSupport(), 0.5);
  EXPECT_DOUBLE_EQ(ViewFilterWarp({ViewFilterKind::Tent, 1.0}).halfSupport(), 1.0);
  EXPECT_EQ(ViewFilterWarp({ViewFilterKind::None, 1.0})(0.9), 0.0);
}

TEST(ViewFilter, NamesRoundTrip) {
  for (ViewFilterKind kind : {ViewFilterKind::None, ViewFilterKind::View, ViewFilterKind::Tent,
                              ViewFilterKind::Gaussian, ViewFilterKind::Period}) {
    ViewFilterKind parsed = ViewFilterKind::None;
    ASSERT_TRUE(parseViewFilterKind(viewFilterName(kind), parsed));
    EXPECT_EQ(parsed, kind);
  }
  ViewFilterKind unused;
  EXPECT_FALSE(parseViewFilterKind("box", unused));
}

}  // namespace
}  // namespace parallax
