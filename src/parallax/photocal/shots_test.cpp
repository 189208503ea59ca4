// The shots: markers where the ring says, inside the panel and apart; the barrier's bands and
// gratings where the estimator reads them; the lenticular interior lit by each subpixel's view.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "parallax/core/error.h"
#include "parallax/display/lenticular_presets.h"
#include "parallax/photocal/barrier_shot.h"
#include "parallax/photocal/lenticular_shot.h"
#include "parallax/vision/vision.h"

namespace parallax::photocal {
namespace {

TEST(MarkerRing, MarkersFitApartWithTheirQuietZones) {
  for (const PanelGrid panel :
       {PanelGrid{1920, 1080, 0.2745}, PanelGrid{1536, 2048, 0.078}, PanelGrid{640, 480, 0.3}}) {
    const MarkerRing ring = markerRing(panel, 0, 108);
    EXPECT_GE(ring.markers.size(), 8u);
    EXPECT_EQ(ring.markerPx % vision::kMarkerCells, 0);
    for (size_t i = 0; i < ring.markers.size(); ++i) {
      const auto& a = ring.markers[i];
      EXPECT_GE(a.x, ring.quietPx);
      EXPECT_GE(a.y, ring.quietPx);
      EXPECT_LE(a.x + ring.markerPx + ring.quietPx, panel.width);
      EXPECT_LE(a.y + ring.markerPx + ring.quietPx, panel.height);
      EXPECT_EQ(a.id, int(i));
      for (size_t j = 0; j < i; ++j) {
        const auto& b = ring.markers[j];
        const bool apart = std::abs(a.x - b.x) >= ring.markerPx + ring.quietPx ||
                           std::abs(a.y - b.y) >= ring.markerPx + ring.quietPx;
        EXPECT_TRUE(apart) << i << " and " << j;
      }
    }
  }
}

TEST(BarrierShot, GratingsWhereTheBandsSay) {
  const DisplaySpec display = defaultDisplaySpec();
  const BarrierShot shot = barrierShot(display);
  const BarrierShotPictures p = drawBarrierShot(shot);
  ASSERT_EQ(p.front.width(), display.imagePanel.width);
  ASSERT_EQ(p.rear.height(), display.maskPanel.height);
  for (int b = 0; b < shot.bands; ++b)
    for (int row = 0; row < BarrierShot::kBandPx; ++row) {
      const int y = shot.y0 + b * BarrierShot::kBandPx + row;
      const bool inFront = row >= BarrierShot::kFrontRows[0] && row < BarrierShot::kFrontRows[1];
      const bool inRear = row >= BarrierShot::kRearRows[0] && row < BarrierShot::kRearRows[1];
      for (int x = shot.x0; x < shot.x1; x += 37) {
        const double fromCentre = x + 0.5 - 0.5 * shot.front.width;
        const double down = y + 0.5 - 0.5 * shot.front.height;
        EXPECT_NEAR(p.front.at(x, y).x, inFront ? shotGratings(fromCentre, down) : 1.0, 1e-6);
        EXPECT_NEAR(p.rear.at(x, y).x, inRear ? shotGratings(fromCentre, down) : 1.0, 1e-6);
        // Where one layer shows its grating the other lets it through.
        EXPECT_FALSE(inFront && inRear);
      }
    }
  // The gratings peak together at the panel's centre and again 156 columns and 32 rows on.
  EXPECT_NEAR(shotGratings(0, 0), 1.0, 1e-12);
  EXPECT_NEAR(shotGratings(156, 32), 1.0, 1e-12);
  EXPECT_NEAR(shotGratings(6, 16), 0.5 + (-1 + std::cos(M_PI * 12 / 13) - 1) / 6, 1e-12);
}

TEST(BarrierShot, TooSmallADisplayIsRefused) {
  DisplaySpec display = defaultDisplaySpec();
  display.imagePanel.width = 200, display.imagePanel.height = 100;
  display.maskPanel = display.imagePanel;
  EXPECT_THROW(barrierShot(display), InputError);
}

TEST(LenticularShot, EachSubpixelShowsItsViewInQuadrature) {
  const LenticularDesign d = designLenticular(*lenticularPreset("portrait"));
  const LenticularShot shot = lenticularShot(d);
  const Image picture = drawLenticularShot(shot, d);
  for (int k = 0; k < 40; ++k) {
    const int x = shot.x0 + (k * 131) % (shot.x1 - shot.x0);
    const int y = shot.y0 + (k * 977) % (shot.y1 - shot.y0);
    const double r = viewFraction(d, x, y, 0), b = viewFraction(d, x, y, 2);
    EXPECT_NEAR(picture.at(x, y).x, 0.5 + 0.5 * std::cos(2 * std::numbers::pi * r), 1e-6);
    EXPECT_NEAR(picture.at(x, y).y, 0.5, 1e-6);
    EXPECT_NEAR(picture.at(x, y).z, 0.5 + 0.5 * std::sin(2 * std::numbers::pi * b), 1e-6);
  }
  // The ring is there, black and white.
  const auto& m = shot.ring.markers.front();
  const float corner = picture.at(m.x + 1, m.y + 1).x;  // the marker's black border
  EXPECT_EQ(corner, 0.0f);
  EXPECT_EQ(picture.at(m.x - 1, m.y - 1).x, 1.0f);
}

}  // namespace
}  // namespace parallax::photocal
