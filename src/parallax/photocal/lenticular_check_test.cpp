// The seat check's model of what an eye takes in (lenticular_check.h) against hand-worked
// answers: the renderer's spot model, boxes of delta and W delta.
#include "parallax/photocal/lenticular_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "parallax/display/lenticular_presets.h"

namespace parallax::photocal {
namespace {

LenticularDesign portrait() {
  const std::optional<LenticularCalibration> c = lenticularPreset("portrait");
  EXPECT_TRUE(c.has_value());
  return designLenticular(*c);
}

TEST(SeatCheckModel, AmplitudeAndSpotAreInverses) {
  const LenticularDesign d = portrait();
  const double delta = subpixelViewWidth(d);
  // An ideal lens: the subpixel's own box, sinc(delta).
  EXPECT_NEAR(seenAmplitudeOfSpot(d, 0),
              std::sin(std::numbers::pi * delta) / (std::numbers::pi * delta), 1e-12);
  // A spot as wide as 1 / delta subpixels spans the whole period: nothing of the view is left.
  EXPECT_NEAR(seenAmplitudeOfSpot(d, 1 / delta), 0, 1e-9);
  for (const double spot : {0.5, 1.0, 3.0, 7.5})
    EXPECT_NEAR(spotOfSeenAmplitude(d, seenAmplitudeOfSpot(d, spot)), spot, 1e-6) << spot;
  EXPECT_EQ(spotOfSeenAmplitude(d, 1.0), 0.0);
}

TEST(SeatCheckModel, OtherViewsShareIsTheBoxesOverlap) {
  const LenticularDesign d = portrait();
  const double delta = subpixelViewWidth(d), view = 1.0 / d.quiltViews;
  ASSERT_LT(view, delta);  // a Portrait's subpixel spans 2.6 of its 48 views
  // An ideal lens: a box of delta, of which one view's width is the eye's own.
  EXPECT_NEAR(otherViewsShare(d, 0), 1 - view / delta, 1e-3);
  // A spot as wide as a subpixel: a triangle of half-width delta; beyond +-v/2 of it,
  // (1 - v / (2 delta))^2.
  EXPECT_NEAR(otherViewsShare(d, 1), std::pow(1 - view / (2 * delta), 2), 1e-3);
}

}  // namespace
}  // namespace parallax::photocal
