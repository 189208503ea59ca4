#include "parallax/sim/lenticular_sim.h"

#include <gtest/gtest.h>

#include <cmath>

#include "parallax/core/error.h"
#include "parallax/display/lenticular_test_support.h"

namespace parallax {
namespace {

constexpr double kPi = 3.14159265358979323846;

LenticularDesign smallDesign(bool flipImageX = false, double spot = 1,
                             LensBundles bundles = LensBundles::Converging) {
  LensOptics o;
  o.spotWidthSubpixels = spot;
  o.bundles = bundles;
  return withOptics(smallLenticularDesign(60, flipImageX), o);
}

// Each subpixel shows its own view fraction (in its own channel), so that what the eye sees
// tells which subpixel it sees.
Image viewRamp(const LenticularDesign& d) {
  Image panel(d.calibration.screenW, d.calibration.screenH);
  for (int y = 0; y < panel.height(); ++y)
    for (int x = 0; x < panel.width(); ++x)
      for (int ch = 0; ch < 3; ++ch) panel.at(x, y)[ch] = float(viewFraction(d, x, y, ch));
  return panel;
}

// The view an eye asks for at pixel x, from the geometry: parallel bundles, the horizontal
// angle from the pixel's centre to the eye; bundles converging at D, the angle at which the line
// from the pixel through the eye meets the design line; across the 40-degree cone, wrapped.
double eyeView(const LenticularDesign& d, const Vec3d& eye, int x, LensBundles bundles) {
  const double px = -0.5 * d.widthMm + (x + 0.5) * d.pixelPitchMm, D = d.viewDistanceMm;
  const double slope = (eye.x - px) / eye.z;
  const double theta =
      bundles == LensBundles::Parallel ? std::atan(slope) : std::atan((px + slope * D) / D);
  const double f = theta / (40 * kPi / 180) + 0.5;
  return f - std::floor(f);
}

// A pixel-wide spot sees one subpixel's worth of each colour everywhere: a panel of one colour
// looks that colour.
TEST(LenticularSim, PixelWideSpotShowsAUniformPanelUniform) {
  for (const LensBundles bundles : {LensBundles::Parallel, LensBundles::Converging}) {
    const LenticularDesign d = smallDesign(false, 3, bundles);
    const Image panel(180, 60, Vec3f{0.2f, 0.5f, 0.9f});
    const Vec3d eye{150, 40, 700};
    const Image view = simulateLenticularView(d, panel, eye);
    int checked = 0;
    for (int y = 0; y < 60; ++y)
      for (int x = 7; x < 173; ++x) {  // lenses cut by the panel's edge aside
        // Not where the spot reaches the lens's edge (views 0 and 1): the colours' order breaks
        // there, as the lens holds a fractional number of subpixels.
        const double f = eyeView(d, eye, x, bundles), reach = 2 / d.subpixelsPerLens;
        if (f < reach || f > 1 - reach) continue;
        const Vec3f p = view.at(x, y);
        EXPECT_NEAR(p.x, 0.2f, 1e-5f) << x << "," << y;
        EXPECT_NEAR(p.y, 0.5f, 1e-5f) << x << "," << y;
        EXPECT_NEAR(p.z, 0.9f, 1e-5f) << x << "," << y;
        ++checked;
      }
    EXPECT_GT(checked, 60 * 100);
  }
  // A narrower spot shows colour stripes that the eye mixes over a lens and a colour cycle of
  // rows (lenticularAtDisplayResolution): the panel's colour, to a few percent.
  const LenticularDesign d = smallDesign(false, 1);
  const Image panel(180, 60, Vec3f{0.2f, 0.5f, 0.9f});
  const Image seen =
      lenticularAtDisplayResolution(d, simulateLenticularView(d, panel, {0, 0, 900}));
  Vec3f mean;
  for (const Vec3f& p : seen.pixels()) mean = mean + p * (1.0f / float(seen.pixels().size()));
  EXPECT_NEAR(mean.x, 0.2f, 0.02f);
  EXPECT_NEAR(mean.y, 0.5f, 0.05f);
  EXPECT_NEAR(mean.z, 0.9f, 0.09f);
}

// An ideal lens: through the lens at each point the eye sees exactly one subpixel, the one whose
// span of views (delta wide around its view) holds the eye's view, in its own colour (three times
// as bright: it fills the lens); inside the cone and beyond it, where the next lens's views
// repeat, for either bundles.
TEST(LenticularSim, IdealLensSeesExactlyTheSubpixelOfTheEyesView) {
  for (const LensBundles bundles : {LensBundles::Parallel, LensBundles::Converging}) {
    const LenticularDesign d = smallDesign(false, 0, bundles);
    const Image panel = viewRamp(d);
    const double D = d.viewDistanceMm, halfCone = 20 * kPi / 180;
    const double delta = 1 / d.subpixelsPerLens;
    for (const double angle : {0.0, 0.4 * halfCone, -0.4 * halfCone, 1.6 * halfCone})
      for (const double distance : {0.8 * D, D}) {
        const Vec3d eye{distance * std::tan(angle), 25, distance};
        const Image view = simulateLenticularView(d, panel, eye);
        int checked = 0;
        for (int y = 5; y < 60; y += 11)
          for (int x = 10; x < 170; x += 13) {
            const double expected = eyeView(d, eye, x, bundles);
            if (expected < 0.1 || expected > 0.9) continue;  // the ramp's jump from 1 to 0
            int lit = 0;
            for (int ch = 0; ch < 3; ++ch) {
              const double seen = view.at(x, y)[ch] / 3.0;
              if (seen == 0) continue;
              ++lit;
              EXPECT_LE(std::fabs(seen - expected), 0.5 * delta + 1e-6)
                  << int(bundles) << " " << angle << " " << x << "," << y;
            }
            EXPECT_EQ(lit, 1) << x << "," << y;
            ++checked;
          }
        EXPECT_GT(checked, 20) << angle;
      }
  }
}

TEST(LenticularSim, MirroredPanelsAreShownTheRightWayRound) {
  const LenticularDesign d = smallDesign(true, 3);
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
