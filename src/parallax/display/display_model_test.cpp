// The display concept's contract, checked on every kind the same way: film layout, packets
// against single rays, rays through their film point, views and their eyes, the mask layer.
#include "parallax/display/display_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "parallax/display/lenticular_test_support.h"

namespace parallax {
namespace {

DisplaySpec smallBarrier() {
  DisplaySpec s = defaultDisplaySpec();
  s.imagePanel.width = s.maskPanel.width = 90;
  s.imagePanel.height = s.maskPanel.height = 30;
  s.imagePanel.pitchMm = s.maskPanel.pitchMm = 1.0;
  return s;
}

struct Kind {
  std::string name;
  std::function<std::unique_ptr<DisplayModel>()> make;
};

class DisplayContract : public testing::TestWithParam<Kind> {};

TEST_P(DisplayContract, FilmCoversThePanel) {
  const auto display = GetParam().make();
  const FilmLayout f = display->film();
  EXPECT_EQ(f.columns, f.panelWidth * (f.subpixelColumns ? 3 : 1));
  EXPECT_EQ(f.rows, f.panelHeight);
  const DisplayWindow w = display->window();
  EXPECT_GT(w.widthMm, 0);
  EXPECT_GT(w.heightMm, 0);
  EXPECT_GT(w.eyeMm.z, 0);
  if (f.subpixelColumns) {
    for (int c = 0; c < 6; ++c)
      EXPECT_EQ(display->channelOfColumn(c), display->channelOfColumn(c + 3));
  }
}

// The packet form is the single-ray form, lane by lane, for jittered samples anywhere.
TEST_P(DisplayContract, PacketsAreSingleRays) {
  const auto display = GetParam().make();
  const FilmLayout f = display->film();
  alignas(64) float x[16], y[16], u[16], v[16];
  for (int i = 0; i < 16; ++i) {
    x[i] = float(std::fmod(7.3 * i + 0.37, f.columns));
    y[i] = float(std::fmod(3.1 * i + 0.61, f.rows));
    u[i] = float(std::fmod(0.13 + 0.29 * i, 1.0));
    v[i] = float(std::fmod(0.71 + 0.17 * i, 1.0));
  }
  alignas(64) double o[3][16], d[3][16];
  display->rays16(x, y, u, v, o, d);
  for (int i = 0; i < 16; ++i) {
    const DisplayRay r = display->ray(x[i], y[i], u[i], v[i]);
    EXPECT_NEAR(o[0][i], r.origin.x, 1e-6);
    EXPECT_NEAR(o[1][i], r.origin.y, 1e-6);
    EXPECT_NEAR(o[2][i], r.origin.z, 1e-6);
    EXPECT_NEAR(d[0][i], r.direction.x, 1e-9);
    EXPECT_NEAR(d[1][i], r.direction.y, 1e-9);
    EXPECT_DOUBLE_EQ(d[2][i], -1.0);
  }
}

// A ray starts on the viewer's side and runs toward the display; traced back, the central ray
// reaches its view's design eye within a view's width. A barrier's rays of one view converge on
// their eye; a lenticular's are parallel (each lens sends a view at the same angle from its own
// axis), so there the ray is compared after moving its panel point to the centre.
TEST_P(DisplayContract, CentralRaysReachTheirViewsEyes) {
  const auto display = GetParam().make();
  const FilmLayout f = display->film();
  const int views = display->viewCount();
  ASSERT_GE(views, 2);
  const double viewWidth = display->viewZoneWidthMm() / views;
  for (int column = 1; column < f.columns; column += f.columns / 7)
    for (int row : {0, f.rows / 2, f.rows - 1}) {
      const DisplayRay r = display->ray(column + 0.5, row + 0.5, 0.5, 0.5);
      ASSERT_GT(r.origin.z, 0);
      ASSERT_LT(r.direction.z, 0);
      const int view = display->viewIndex(column, row);
      ASSERT_GE(view, 0);
      ASSERT_LT(view, views);
      const Vec3d eye = display->viewPosition(view);
      // Where the central ray, traced back, crosses the eye's plane.
      const double t = (eye.z - r.origin.z) / -r.direction.z;
      // Lenticular panels too: their bundles converge at the design distance (docs/lenticular.md).
      const double x = r.origin.x - r.direction.x * t;
      EXPECT_LT(std::fabs(x - eye.x), 0.75 * viewWidth) << "column " << column << " row " << row;
    }
}

// Across the zone from left to right; the zone's centre is the window's eye.
TEST_P(DisplayContract, EyesAcrossTheZoneRunLeftToRight) {
  const auto display = GetParam().make();
  const Vec3d centre = display->eyeAcrossZone(0.5);
  EXPECT_NEAR(centre.x, display->window().eyeMm.x, 1e-9);
  EXPECT_NEAR(centre.z, display->window().eyeMm.z, 1e-9);
  EXPECT_LT(display->eyeAcrossZone(0.0).x, centre.x);
  EXPECT_GT(display->eyeAcrossZone(1.0).x, centre.x);
  EXPECT_NEAR(display->eyeAcrossZone(1.0).x - display->eyeAcrossZone(0.0).x,
              display->viewZoneWidthMm(), 1e-6 * display->viewZoneWidthMm());
  // Views fill the zone, in one direction (a barrier-front counts them from the right): evenly
  // in x for a barrier, evenly in angle for a lenticular (within 5 % of even in x at the
  // centre of a 40 degree cone).
  const int mid = display->viewCount() / 2;
  const double step = display->viewPosition(mid).x - display->viewPosition(mid - 1).x;
  EXPECT_NEAR(std::fabs(step), display->viewZoneWidthMm() / display->viewCount(),
              0.05 * display->viewZoneWidthMm() / display->viewCount());
  for (int v = 1; v < display->viewCount(); ++v)
    EXPECT_GT((display->viewPosition(v).x - display->viewPosition(v - 1).x) * step, 0);
}

TEST_P(DisplayContract, MaskLayerOnlyForKindsThatHaveOne) {
  const auto display = GetParam().make();
  const Image mask = display->maskLayer();
  EXPECT_EQ(display->hasMaskLayer(), !mask.empty());
  EXPECT_EQ(display->hasMaskLayer(), display->barrierDesign() != nullptr);
  EXPECT_EQ(display->lenticularDesign() != nullptr, display->kind() == DisplayKind::Lenticular);
  EXPECT_FALSE(display->designReport().empty());
}

INSTANTIATE_TEST_SUITE_P(
    Kinds, DisplayContract,
    testing::Values(
        Kind{"barrier", [] { return makeBarrierDisplay(designDisplay(smallBarrier())); }},
        Kind{"barrier_front_subpixels",
             [] {
               DisplaySpec s = smallBarrier();
               s.order = LayerOrder::BarrierFront;
               BarrierCameraSettings camera;
               camera.subpixelRays = true;
               return makeBarrierDisplay(designDisplay(s, camera));
             }},
        Kind{"lenticular", [] { return makeLenticularDisplay(smallLenticularDesign()); }},
        Kind{"lenticular_filtered",
             [] {
               return makeLenticularDisplay(smallLenticularDesign(), {ViewFilterKind::Tent, 1.5});
             }}),
    [](const testing::TestParamInfo<Kind>& param) { return param.param.name; });

}  // namespace
}  // namespace parallax
