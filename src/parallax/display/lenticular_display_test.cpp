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

// rays16 (the render loop's lane kernel) is ray() written lane-wise: a second code path of the
// same formulas, checked lane by lane on every calibration feature it reads (subpixel cells in
// each pattern, mirrored images and subpixels, inverted views, both bundles), every filter and
// several spots, at film samples anywhere on the panel (edges and lens offsets past them
// included).
TEST(LenticularDisplay, SixteenLaneRaysAreTheSingleRays) {
  std::vector<LenticularDesign> designs;
  for (const bool flip : {false, true}) designs.push_back(smallLenticularDesign(120, flip));
  for (int mode = 0; mode <= 4; ++mode) {
    LenticularCalibration c = smallLenticularDesign().calibration;
    c.cellPatternMode = mode;
    c.subpixelCells = {{{-0.31, 0.28, 0.0}, {0.25, 0.25, -0.25}},
                       {{-0.25, -0.25, 0.25}, {-0.31, 0.28, 0.0}},
                       {{0.1, -0.2, 0.3}, {0.0, 0.15, -0.1}}};
    c.flipImageY = mode % 2 == 1;
    c.invView = mode != 2;
    designs.push_back(designLenticular(c));
  }
  LenticularCalibration bgr = smallLenticularDesign().calibration;
  bgr.flipSubpixels = true;
  designs.push_back(designLenticular(bgr));
  const ViewFilterKind filters[] = {ViewFilterKind::None, ViewFilterKind::View,
                                    ViewFilterKind::Tent, ViewFilterKind::Gaussian,
                                    ViewFilterKind::Period};
  uint32_t state = 12345;
  const auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24);
  };
  int checked = 0;
  for (const LenticularDesign& base : designs)
    for (const double spot : {0.0, 1.0, 3.0})
      for (const LensBundles bundles : {LensBundles::Converging, LensBundles::Parallel})
        for (const ViewFilterKind filter : filters) {
          LensOptics o;
          o.spotWidthSubpixels = spot;
          o.bundles = bundles;
          const LenticularDesign d = withOptics(base, o);
          const std::unique_ptr<DisplayModel> display = makeLenticularDisplay(d, {filter, 1.5});
          const FilmLayout film = display->film();
          alignas(64) float x[16], y[16], u[16], v[16];
          alignas(64) double origin[3][16], direction[3][16];
          for (int lane = 0; lane < 16; ++lane) {
            // Lanes 0 and 15 on the film's first and last columns and rows.
            const int column = lane == 0    ? 0
                               : lane == 15 ? film.columns - 1
                                            : int(next() * film.columns);
            const int row = lane == 0 ? 0 : lane == 15 ? film.rows - 1 : int(next() * film.rows);
            x[lane] = float(column) + next() * 0.999f, y[lane] = float(row) + next() * 0.999f;
            u[lane] = next(), v[lane] = next();
          }
          display->rays16(x, y, u, v, origin, direction);
          for (int lane = 0; lane < 16; ++lane) {
            const DisplayRay r = display->ray(x[lane], y[lane], u[lane], v[lane]);
            const double got[6] = {origin[0][lane],    origin[1][lane],    origin[2][lane],
                                   direction[0][lane], direction[1][lane], direction[2][lane]};
            const double want[6] = {r.origin.x,    r.origin.y,    r.origin.z,
                                    r.direction.x, r.direction.y, r.direction.z};
            for (int k = 0; k < 6; ++k)
              ASSERT_NEAR(got[k], want[k], 1e-9 * (1 + std::fabs(want[k])))
                  << "component " << k << " lane " << lane << " filter " << int(filter) << " spot "
                  << spot << " cells " << d.calibration.subpixelCells.size() << " mode "
                  << d.calibration.cellPatternMode;
            ++checked;
          }
        }
  EXPECT_EQ(checked, int(designs.size()) * 3 * 2 * 5 * 16);
}

}  // namespace
}  // namespace parallax
