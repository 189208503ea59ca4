// The lenticular panel as a DisplayModel: its central rays are the published formula's, its views
// the quilt's slices of the view fraction, its eyes evenly in angle across the cone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "parallax/display/display_model.h"
#include "parallax/display/lenticular_test_support.h"

namespace parallax {
namespace {

TEST(LenticularDisplay, CentralRaysAreTheFormulasAndViewsSliceTheFraction) {
  const LenticularDesign d = smallLenticularDesign();
  const std::unique_ptr<DisplayModel> display = makeLenticularDisplay(d, {ViewFilterKind::None, 1});
  EXPECT_EQ(display->viewCount(), d.quiltViews);
  for (int x = 0; x < 180; x += 13)
    for (int c = 0; c < 3; ++c) {
      const int column = 3 * x + c, row = 37;
      const LenticularRay expected = lenticularRay(d, x + 0.5, row + 0.5, c);
      const DisplayRay got = display->ray(column + 0.9, row + 0.2, 0.1, 0.7);  // none: central
      EXPECT_NEAR(got.origin.x, expected.origin.x, 1e-9);
      EXPECT_NEAR(got.direction.x, expected.direction.x, 1e-12);
      const double f = viewFraction(d, x, row, c);
      EXPECT_EQ(display->viewIndex(column, row), int(std::floor(f * d.quiltViews)));
    }
  // Eyes evenly in angle: the view's eye sits at the angle of its fraction's centre.
  for (int v : {0, 10, 47}) {
    const Vec3d eye = display->viewPosition(v);
    EXPECT_NEAR(std::atan2(eye.x, eye.z), viewAngle(d, (v + 0.5) / d.quiltViews), 1e-12);
  }
  EXPECT_FALSE(display->hasMaskLayer());
  EXPECT_TRUE(display->maskLayer().empty());
}

// The prefilter (filter view) adds what an eye does not integrate by itself: the eye already
// blends the subpixels' spans through the spot W delta, so a sample's place across its
// subpixel moves its view over (1 - W) delta of the span only, none from W = 1 on: mean the own
// view, variance ((1 - W)+ delta)^2 / 12, within (1 - W)+ delta / 2.
TEST(LenticularDisplay, ViewFilterSpreadsTheRaysOverWhatAnEyeIntegrates) {
  const LenticularDesign base = smallLenticularDesign();
  for (const double spot : {0.0, 0.5, 1.0, 3.0}) {
    LensOptics o;
    o.spotWidthSubpixels = spot;
    const LenticularDesign d = withOptics(base, o);
    const std::unique_ptr<DisplayModel> display = makeLenticularDisplay(d);
    const double delta = subpixelViewWidth(d), D = d.viewDistanceMm;
    const int column = 3 * 90 + 1, row = 60, n = 64;
    const double own = viewFraction(d, 90, row, 1);
    double mean = 0, square = 0, widest = 0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const DisplayRay r = display->ray(column + (i + 0.5) / n, row + 0.5, (j + 0.5) / n, 0.5);
        // Converging at D: the ray crosses the design line at its view's eye point.
        const double f = viewFractionOfAngle(d, std::atan(r.origin.x / D)) - own;
        mean += f / (n * n), square += f * f / (n * n);
        widest = std::max(widest, std::fabs(f));
      }
    EXPECT_NEAR(mean, 0.0, 1e-9 * delta) << spot;
    // A box over the part of the subpixel's span that the spot does not blend: (1 - W) delta,
    // nothing from W = 1 on (every ray then carries the subpixel's own view).
    const double box = std::max(0.0, 1 - spot) * delta;
    const double variance = box * box / 12;
    EXPECT_NEAR(square - mean * mean, variance, 0.01 * variance + 1e-18) << spot;
    EXPECT_LE(widest, 0.5 * box + 1e-12) << spot;
    EXPECT_GE(widest, 0.45 * box) << spot;
  }
  // And the rays leave from across the whole lens the subpixel sits under (an eye sees it over
  // that lens's width): where along the lens, t from view 0 to view 1, covers [0, 1) and no more
  // than the subpixel's own width beyond.
  const std::unique_ptr<DisplayModel> display = makeLenticularDisplay(base);
  const double delta = subpixelViewWidth(base), lens = base.horizontalLensPitchMm;
  const Vec3d p0 = subpixelPointMm(base, 90.5, 60.5, 1), p1 = subpixelPointMm(base, 91.5, 60.5, 1);
  const double step = viewFraction(base, 91, 60, 1) - viewFraction(base, 90, 60, 1);
  const double sign = (step - std::round(step)) * (p1.x - p0.x) > 0 ? 1.0 : -1.0;
  const double own = viewFraction(base, 90, 60, 1);
  double lowest = 2, highest = -2;
  for (int i = 0; i < 32; ++i)
    for (int j = 0; j < 32; ++j) {
      const DisplayRay r = display->ray(3 * 90 + 1 + (i + 0.5) / 32, 60.5, 0.5, (j + 0.5) / 32);
      const double panelX = r.origin.x + r.direction.x * r.origin.z;  // where it leaves, z = 0
      const double t = own + sign * (panelX - p0.x) / lens;
      lowest = std::min(lowest, t), highest = std::max(highest, t);
    }
  EXPECT_GT(lowest, -0.5 * delta - 1e-9);
  EXPECT_LT(highest, 1 + 0.5 * delta + 1e-9);
  EXPECT_LT(lowest, 0.05);
  EXPECT_GT(highest, 0.95);
}

// Down the panel the rays of a subpixel cover the lenses' colour cycle, |slope| rows centred on
// its own row, while the spot leaves rows in which the eye does not see its channel (W <= 1);
// from W = 2 on, every row shows every channel and the rays stay in their own row; in between
// the span shrinks linearly. Where a ray leaves the panel (z = 0), in rows from the subpixel's
// centre, is uniform over that span: mean 0, half-width rows / 2.
TEST(LenticularDisplay, RaysCoverTheRowsOfTheColourCycleTheEyeDoesNotSee) {
  const LenticularDesign base = smallLenticularDesign();
  const double cycle = std::fabs(base.calibration.slope);
  ASSERT_GT(cycle, 2.0);
  for (const double spot : {0.0, 1.0, 1.5, 2.0, 3.0}) {
    LensOptics o;
    o.spotWidthSubpixels = spot;
    const LenticularDesign d = withOptics(base, o);
    const std::unique_ptr<DisplayModel> display = makeLenticularDisplay(d);
    const double own = subpixelPointMm(d, 90.5, 60.5, 1).y;
    const double expected = 1 + (cycle - 1) * std::clamp(2 - spot, 0.0, 1.0);
    double lowest = 1e9, highest = -1e9, mean = 0;
    constexpr int n = 64;
    for (int j = 0; j < n; ++j) {
      const DisplayRay r = display->ray(3 * 90 + 1.5, 60 + (j + 0.5) / n, 0.5, 0.5);
      const double rows = (r.origin.y + r.direction.y * r.origin.z - own) / d.pixelPitchMm;
      lowest = std::min(lowest, rows), highest = std::max(highest, rows), mean += rows / n;
    }
    EXPECT_NEAR(mean, 0.0, 1e-6) << spot;
    EXPECT_NEAR(highest - lowest, expected * (n - 1) / n, 1e-6) << spot;
  }
}

}  // namespace
}  // namespace parallax
