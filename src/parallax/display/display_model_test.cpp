// The display concept's contract, checked on every kind the same way: film layout, packets
// against single rays, rays through their film point, views and their eyes, the mask layer.
#include "parallax/display/display_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "parallax/display/depth_scaled_display.h"
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

TEST_P(DisplayContract, DenseEyesSpanTheZoneAndScaleWithDistance) {
  const auto display = GetParam().make();
  const int views = display->denseViewCount();
  ASSERT_GE(views, 1);
  // At the design distance the dense eyes run from one edge of the zone to the other: the first
  // view's window starts where the zone does, the last one's ends where it ends.
  const Vec3d first = display->denseEye(0, 0.0, 1.0), last = display->denseEye(views - 1, 1.0, 1.0);
  EXPECT_NEAR(first.x, display->eyeAcrossZone(0.0).x, 1e-9);
  EXPECT_NEAR(last.x, display->eyeAcrossZone(1.0).x, 1e-9);
  EXPECT_NEAR(first.z, display->window().eyeMm.z, 1e-9);
  // Nearer and farther, each eye moves with the distance about the zone's centre: x from the
  // centre and z both scale by the factor.
  const double cx = display->window().eyeMm.x;
  for (const double f : {0.8, 1.25})
    for (int v = 0; v < views; v += std::max(1, views / 4)) {
      const Vec3d at1 = display->denseEye(v, 0.5, 1.0), atF = display->denseEye(v, 0.5, f);
      EXPECT_NEAR(atF.x - cx, f * (at1.x - cx), 1e-9);
      EXPECT_NEAR(atF.z, f * at1.z, 1e-9);
      EXPECT_NEAR(atF.y, at1.y, 1e-9);
    }
  // A design eye per dense view, at the design distance, left to right.
  const std::vector<Vec3d> design = display->denseDesignEyes();
  ASSERT_EQ(int(design.size()), views);
  for (const Vec3d& e : design) EXPECT_NEAR(e.z, display->window().eyeMm.z, 1e-6);
}

TEST_P(DisplayContract, TheViewersPictureIsTheFrontPanels) {
  const auto display = GetParam().make();
  const PanelSize panel = display->viewerPanel();
  if (const DisplayDesign* d = display->barrierDesign()) {
    const Panel& front =
        d->spec.order == LayerOrder::BarrierBack ? d->spec.imagePanel : d->spec.maskPanel;
    EXPECT_EQ(panel.width, front.width);
    EXPECT_EQ(panel.height, front.height);
  } else {
    EXPECT_EQ(panel.width, display->film().panelWidth);
    EXPECT_EQ(panel.height, display->film().panelHeight);
  }
}

TEST(BarrierDisplay, TheViewersPictureIsTheFrontLayersWhicheverItIs) {
  // A mask panel of twice the image panel's resolution (the same size in mm): the viewer's
  // picture follows the layer in front.
  DisplaySpec s = smallBarrier();
  s.maskPanel.width = 2 * s.imagePanel.width, s.maskPanel.height = 2 * s.imagePanel.height;
  s.maskPanel.pitchMm = 0.5 * s.imagePanel.pitchMm;
  const PanelSize back = makeBarrierDisplay(designDisplay(s))->viewerPanel();
  EXPECT_EQ(back.width, s.imagePanel.width);
  EXPECT_EQ(back.height, s.imagePanel.height);
  s.order = LayerOrder::BarrierFront;
  const PanelSize front = makeBarrierDisplay(designDisplay(s))->viewerPanel();
  EXPECT_EQ(front.width, s.maskPanel.width);
  EXPECT_EQ(front.height, s.maskPanel.height);
}

TEST_P(DisplayContract, QuiltTilesShareTheDevicesQuiltOrAreThePanel) {
  const auto display = GetParam().make();
  const QuiltShape quilt = display->defaultQuilt();
  ASSERT_GE(quilt.columns, 1);
  ASSERT_GE(quilt.rows, 1);
  for (const QuiltShape layout : {quilt, QuiltShape{3, 2}}) {
    const PanelSize tile = display->quiltTile(layout.columns, layout.rows);
    if (const LenticularDesign* l = display->lenticularDesign()) {
      // The device's quilt shared out, whole pixels, nothing left over but the remainder.
      const QuiltFormat& q = l->calibration.quilt;
      EXPECT_LE(tile.width * layout.columns, q.width);
      EXPECT_GT((tile.width + 1) * layout.columns, q.width);
      EXPECT_LE(tile.height * layout.rows, q.height);
      EXPECT_GT((tile.height + 1) * layout.rows, q.height);
    } else {
      // A barrier's views are its panel's pictures, whatever the layout; one row of its views.
      EXPECT_EQ(tile.width, display->film().panelWidth);
      EXPECT_EQ(tile.height, display->film().panelHeight);
      EXPECT_EQ(quilt.columns, display->viewCount());
      EXPECT_EQ(quilt.rows, 1);
    }
  }
}

TEST_P(DisplayContract, ADepthScaledViewAnswersAsTheDisplay) {
  const std::shared_ptr<const DisplayModel> display = GetParam().make();
  const std::unique_ptr<DisplayModel> scaled = depthScaledView(*display, 0.5);
  EXPECT_EQ(scaled->viewerPanel().width, display->viewerPanel().width);
  EXPECT_EQ(scaled->viewerPanel().height, display->viewerPanel().height);
  EXPECT_EQ(scaled->diffuserSigmaMm(), display->diffuserSigmaMm());
  EXPECT_EQ(scaled->defaultQuilt().columns, display->defaultQuilt().columns);
  EXPECT_EQ(scaled->quiltTile(4, 2).width, display->quiltTile(4, 2).width);
  EXPECT_EQ(scaled->directMappingViews(), display->directMappingViews());
  EXPECT_EQ(scaled->deviceNote(), display->deviceNote());
  EXPECT_EQ(scaled->summaryClause(), display->summaryClause());
  EXPECT_EQ(scaled->denseViewCount(), display->denseViewCount());
  EXPECT_EQ(scaled->denseEye(1, 0.25, 1.1).x, display->denseEye(1, 0.25, 1.1).x);
  EXPECT_EQ(scaled->denseDesignEyes().size(), display->denseDesignEyes().size());
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
