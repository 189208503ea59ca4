#include "parallax/sim/lenticular_sim.h"

#include <gtest/gtest.h>

#include <cmath>

#include "parallax/core/error.h"
#include "parallax/display/lenticular_test_support.h"

namespace parallax {
namespace {

constexpr double kPi = 3.14159265358979323846;

LenticularDesign smallDesign(bool flipImageX = false) {
  return smallLenticularDesign(60, flipImageX);
}

// Each subpixel shows its own view fraction (in its own channel): the eye should see the view
// fraction of its own direction, interpolated exactly since the picture is linear in the view.
Image viewRamp(const LenticularDesign& d) {
  Image panel(d.calibration.screenW, d.calibration.screenH);
  for (int y = 0; y < panel.height(); ++y)
    for (int x = 0; x < panel.width(); ++x)
      for (int ch = 0; ch < 3; ++ch) panel.at(x, y)[ch] = float(viewFraction(d, x, y, ch));
  return panel;
}

// The view an eye's direction asks for, from the geometry: the horizontal angle from the pixel's
// centre to the eye across the cone, wrapped.
double eyeView(const LenticularDesign& d, const Vec3d& eye, int x, int y) {
  const double px = -0.5 * d.widthMm + (x + 0.5) * d.pixelPitchMm;
  (void)y;
  const double theta = std::atan((eye.x - px) / eye.z);
  const double f = theta / (d.calibration.viewConeDegrees * kPi / 180) + 0.5;
  return f - std::floor(f);
}

TEST(LenticularSim, UniformPanelLooksUniform) {
  const LenticularDesign d = smallDesign();
  const Image panel(180, 60, Vec3f{0.2f, 0.5f, 0.9f});
  const Image view = simulateLenticularView(d, panel, {150, 40, 700});
  for (const Vec3f& p : view.pixels()) {
    EXPECT_NEAR(p.x, 0.2f, 1e-5f);
    EXPECT_NEAR(p.y, 0.5f, 1e-5f);
    EXPECT_NEAR(p.z, 0.9f, 1e-5f);
  }
}

TEST(LenticularSim, EyeSeesTheViewsOfItsDirection) {
  const LenticularDesign d = smallDesign();
  const Image panel = viewRamp(d);
  const double D = d.viewDistanceMm, halfCone = 20 * kPi / 180;
  // Inside the cone, and beyond it where the next lens's views repeat.
  for (const double angle : {0.0, 0.4 * halfCone, -0.4 * halfCone, 1.6 * halfCone}) {
    const Vec3d eye{D * std::tan(angle), 25, D};
    const Image view = simulateLenticularView(d, panel, eye);
    int checked = 0;
    for (int y = 5; y < 60; y += 11)
      for (int x = 10; x < 170; x += 13) {
        const double expected = eyeView(d, eye, x, y);
        if (expected < 0.2 || expected > 0.8) continue;  // the ramp's jump from 1 to 0
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(view.at(x, y)[ch], expected, 1e-5);
        ++checked;
      }
    EXPECT_GT(checked, 20) << angle;
  }
}

TEST(LenticularSim, MirroredPanelsAreShownTheRightWayRound) {
  const LenticularDesign d = smallDesign(true);
  Image panel(180, 60);
  for (int y = 0; y < 60; ++y)
    for (int x = 0; x < 180; ++x) panel.at(x, y) = Vec3f(float(x) / 180);
  const Image view = simulateLenticularView(d, panel, {0, 0, d.viewDistanceMm});
  const double lens = d.pixelsPerLens / 180;
  for (int x = 10; x < 170; x += 20) EXPECT_NEAR(view.at(x, 30).y, (179.0 - x) / 180, lens) << x;
}

TEST(LenticularSim, PanelOfTheWrongSizeNamesTheCalibration) {
  try {
    simulateLenticularView(smallDesign(), Image(100, 60), {0, 0, 500});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("small.json: /screenW"), std::string::npos);
  }
  EXPECT_THROW(simulateLenticularView(smallDesign(), Image(180, 60), {0, 0, -1}),
               std::invalid_argument);
}

}  // namespace
}  // namespace parallax
