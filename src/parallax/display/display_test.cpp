// Barrier design against G1-G4 (docs/display-geometry.md), checked by brute-force ray geometry
// where an independent check exists.
#include "parallax/display/display.h"

#include <gtest/gtest.h>

#include <cmath>

#include "parallax/core/error.h"
#include "parallax/core/random.h"

namespace parallax {
namespace {

TEST(DisplayDesign, DefaultMatchesTheWorkedNumbers) {
  const DisplayDesign d = designDisplay(defaultDisplaySpec());
  EXPECT_NEAR(d.screenPeriodMm, 2.4705, 1e-9);
  EXPECT_NEAR(d.slitPeriodMm, 2.48285, 1e-5);
  EXPECT_NEAR(d.slitPeriodPx, 9.045, 1e-3);
  EXPECT_NEAR(d.viewZoneWidthMm, 496.6, 0.1);
  EXPECT_NEAR(d.viewWidthMm, 55.2, 0.1);
  EXPECT_NEAR(d.depthOfFieldMm, 27.1, 0.05);
  EXPECT_DOUBLE_EQ(d.views, 9.0);
  EXPECT_EQ(d.imageLayerZ(), 0.0);
  EXPECT_EQ(d.maskLayerZ(), -3.0);
}

DisplaySpec spec(LayerOrder order, double gap, double distance, double views) {
  DisplaySpec s = defaultDisplaySpec();
  s.order = order;
  s.gapMm = gap;
  s.viewDistanceMm = distance;
  s.views = views;
  return s;
}

// G1 and G2 by brute force: from any eye inside the view zone, the line from the eye through
// aperture k (a point on the mask layer) crosses the image layer inside group k, whichever
// layer is in front; from eyes outside the zone it lands in a neighbouring group.
void checkEachApertureServesItsGroup(const DisplayDesign& d) {
  const double D = d.viewDistanceMm, zI = d.imageLayerZ(), zM = d.maskLayerZ();
  const auto groupOffset = [&](double eye, int k) {
    const double x = eye + (k * d.slitPeriodMm - eye) * (D - zI) / (D - zM);
    return std::abs(x - k * d.screenPeriodMm);
  };
  Rng rng(3);
  for (int trial = 0; trial < 2000; ++trial) {
    const double eye = (rng.uniform() - 0.5) * d.viewZoneWidthMm * 0.999;
    const int k = int(rng.next() % 200) - 100;
    EXPECT_LE(groupOffset(eye, k), 0.5 * d.screenPeriodMm + 1e-9) << "eye " << eye;
  }
  for (int trial = 0; trial < 200; ++trial) {
    const double eye = 0.5 * d.viewZoneWidthMm * (1.001 + rng.uniform());
    EXPECT_GT(groupOffset(eye, int(rng.next() % 200) - 100), 0.5 * d.screenPeriodMm);
  }
}

TEST(DisplayDesign, G1G2HoldInBothLayerOrders) {
  for (LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront})
    for (double gap : {1.0, 3.0, 8.0})
      for (double distance : {300.0, 600.0, 2000.0})
        for (double views : {3.0, 5.0, 9.0, 16.5}) {
          const DisplayDesign d = designDisplay(spec(order, gap, distance, views));
          const double rear = order == LayerOrder::BarrierBack ? d.slitPeriodMm : d.screenPeriodMm;
          const double front = order == LayerOrder::BarrierBack ? d.screenPeriodMm : d.slitPeriodMm;
          EXPECT_NEAR(rear / front, (distance + gap) / distance, 1e-12);  // G1
          EXPECT_NEAR(d.viewZoneWidthMm, rear * distance / gap, 1e-9);    // G2
          EXPECT_NEAR(d.views * d.viewWidthMm, d.viewZoneWidthMm, 1e-9);
          EXPECT_NEAR(d.depthOfFieldMm, gap * d.slitPeriodMm / d.spec.imagePanel.pitchMm,
                      1e-9);  // G4
          checkEachApertureServesItsGroup(d);
        }
}

TEST(DisplayDesign, G3ApertureSpanAndTheResolutionCount) {
  // Barrier-front with N groups exactly filling the screen: Sv = (Sx - Tx) D / (D + g), and
  // views x (Sv / Tv + 1) = Sx / dx, the whole panel (the paper's resolution count).
  DisplaySpec s = spec(LayerOrder::BarrierFront, 3.0, 600.0, 8.0);
  s.imagePanel.width = s.maskPanel.width = 1920;  // 240 groups of 8
  const DisplayDesign d = designDisplay(s);
  const double Sx = s.imagePanel.widthMm();
  EXPECT_NEAR(d.aperturesAcross, 240.0, 0.0);
  EXPECT_NEAR(d.apertureSpanMm, (Sx - d.screenPeriodMm) * 600.0 / 603.0, 1e-9);
  EXPECT_NEAR(d.views * (d.apertureSpanMm / d.slitPeriodMm + 1), Sx / s.imagePanel.pitchMm, 1e-6);
}

TEST(DisplayDesign, AcceptsWhatUsersKnow) {
  const DisplayDesign byViews = designDisplay(spec(LayerOrder::BarrierBack, 3, 600, 9));
  DisplaySpec byZone = spec(LayerOrder::BarrierBack, 3, 600, 9);
  byZone.views.reset();
  byZone.viewZoneWidthMm = byViews.viewZoneWidthMm;
  EXPECT_NEAR(designDisplay(byZone).screenPeriodPx, 9.0, 1e-9);
  DisplaySpec measured = spec(LayerOrder::BarrierBack, 3, 600, 9);
  measured.views.reset();
  measured.viewDistanceMm.reset();
  measured.screenPeriodPx = 9.0;
  measured.slitPeriodPx = byViews.slitPeriodPx;
  EXPECT_NEAR(designDisplay(measured).viewDistanceMm, 600.0, 1e-6);  // D = g / (Tr/Tf - 1)
}

void expectRefused(const DisplaySpec& s, const std::string& key,
                   const BarrierCameraSettings& camera = {}) {
  try {
    designDisplay(s, camera);
    ADD_FAILURE() << "accepted an impossible display; expected an error at " << key;
  } catch (const InputError& e) {
    EXPECT_EQ(e.path(), key) << e.what();
  }
}

TEST(DisplayDesign, RefusesImpossibleDisplays) {
  DisplaySpec s = defaultDisplaySpec();
  s.gapMm = 0;
  expectRefused(s, "/gap_mm");
  s = defaultDisplaySpec();
  s.viewDistanceMm = -5;
  expectRefused(s, "/view_distance_mm");
  s = defaultDisplaySpec();
  s.views = 1.5;
  expectRefused(s, "/views");
  s = defaultDisplaySpec();
  s.views.reset();
  s.viewDistanceMm.reset();
  s.screenPeriodPx = 9;
  s.slitPeriodPx = 8.9;  // barrier-back needs Tv > Tx
  expectRefused(s, "/slit_period_px");
  s.order = LayerOrder::BarrierFront;  // ... and barrier-front accepts it
  EXPECT_GT(designDisplay(s).viewDistanceMm, 0);
  s = defaultDisplaySpec();
  s.mask.kind = MaskKind::Pinholes;
  expectRefused(s, "/mask/vertical_period_px");
  s = defaultDisplaySpec();
  s.mask.dutyCycle = 0;
  expectRefused(s, "/mask/duty_cycle");
  BarrierCameraSettings camera;
  camera.virtualGapMm = -1;
  expectRefused(defaultDisplaySpec(), "/virtual/gap_mm", camera);
  camera = {};
  camera.subpixelRays = true;
  s = defaultDisplaySpec();
  s.imagePanel.subpixels = SubpixelOrder::None;
  expectRefused(s, "/subpixel_rays", camera);
  EXPECT_NO_THROW(designDisplay(s));  // the same panel, traced one ray per pixel
}

TEST(DisplayDesign, AdjacentViewDisparity) {
  const DisplayDesign d = designDisplay(defaultDisplaySpec());
  // A point at depth z seen from eyes S/N apart at D shifts on the display plane by
  // (S/N) z / (D - z): project from both eyes and compare.
  const double z = 50.0, X = 10.0, D = d.viewDistanceMm;
  const double e0 = 0.0, e1 = d.viewWidthMm;
  const auto onPlane = [&](double eye) { return eye + (X - eye) * D / (D - z); };
  EXPECT_NEAR(d.adjacentViewDisparityMm(z), std::abs(onPlane(e1) - onPlane(e0)), 1e-9);
  EXPECT_EQ(d.adjacentViewDisparityMm(0.0), 0.0);
}

}  // namespace
}  // namespace parallax
