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
// repeat, for either bundles. A pixel that a lens's edge crosses shows the two lenses' subpixels,
// each weighted by the part of the pixel its lens covers (the weights read from a white panel).
TEST(LenticularSim, IdealLensSeesExactlyTheSubpixelOfTheEyesView) {
  for (const LensBundles bundles : {LensBundles::Parallel, LensBundles::Converging}) {
    const LenticularDesign d = smallDesign(false, 0, bundles);
    const Image panel = viewRamp(d), white(180, 60, Vec3f(1.0f));
    const double D = d.viewDistanceMm, halfCone = 20 * kPi / 180;
    const double delta = 1 / d.subpixelsPerLens;
    int crossed = 0;
    for (const double angle : {0.0, 0.4 * halfCone, -0.4 * halfCone, 1.6 * halfCone})
      for (const double distance : {0.8 * D, D}) {
        const Vec3d eye{distance * std::tan(angle), 25, distance};
        const Image view = simulateLenticularView(d, panel, eye);
        const Image weights = simulateLenticularView(d, white, eye);
        int checked = 0;
        for (int y = 5; y < 60; y += 11)
          for (int x = 10; x < 170; x += 13) {
            const double expected = eyeView(d, eye, x, bundles);
            if (expected < 0.1 || expected > 0.9) continue;  // the ramp's jump from 1 to 0
            // Whether a lens's edge (where the views under it wrap) crosses the pixel: the views
            // at its left and right edges, from its green subpixel's (at its centre) and the
            // step from pixel to pixel.
            const double green = viewFraction(d, x, y, 1);
            const double step = green - viewFraction(d, x - 1, y, 1);
            const double wrappedStep = step - std::round(step);
            const bool edge =
                std::floor(green - 0.5 * wrappedStep) != std::floor(green + 0.5 * wrappedStep);
            // Where it does, each part is seen from its own middle, where the eye's view is up
            // to 4e-4 off the pixel centre's at these eyes.
            const double tolerance = 0.5 * delta + (edge ? 1e-3 : 1e-6);
            int lit = 0;
            double total = 0;
            for (int ch = 0; ch < 3; ++ch) {
              const double weight = weights.at(x, y)[ch] / 3.0;
              if (weight == 0) continue;
              ++lit;
              total += weight;
              const double seen = view.at(x, y)[ch] / weights.at(x, y)[ch];
              EXPECT_LE(std::fabs(seen - expected), tolerance)
                  << int(bundles) << " " << angle << " " << x << "," << y;
            }
            EXPECT_NEAR(total, 1.0, 1e-5) << x << "," << y;
            EXPECT_GE(lit, 1) << x << "," << y;
            EXPECT_LE(lit, edge ? 2 : 1) << x << "," << y;
            crossed += edge;
            ++checked;
          }
        EXPECT_GT(checked, 20) << angle;
      }
    EXPECT_GT(crossed, 10);
  }
}

// Every lens counts by its width. An eye at the cone's centre sees through every lens the
// subpixel around view 1/2; which colour that is goes with where the lens sits against the
// pixels, and across a row and down the slant the lenses sit everywhere alike, so each colour is
// seen through a third of the panel, at views whose mean is the eye's. On a Portrait-like panel
// (6.29 pixels a lens) a sample at each pixel's centre alone counted a lens centred on a pixel's
// green stripe 6.88 times on average and one centred on red or blue 6 times: under an ideal lens
// green came out 9 % too bright, red and blue 5 % too dark, and a ramp of views read in red
// against green, R / (R + G), gave 0.466 for 0.5 on a whole Portrait (0.471 here; 0.477 with a
// 1-subpixel spot; 0.501 with a pixel-wide one, every colour under every lens). The tolerances
// are the lenses' 119 phases against the pixels here (17 lenses in 107 pixels, rows 1/7 pixel
// apart), which an ideal lens shows one by one: a colour's share is 39 or 40 of 119.
TEST(LenticularSim, EachLensCountsByItsWidthSoEveryColourShowsTheEyesView) {
  LenticularCalibration c;  // lkg:portrait's optics on a strip 384 pixels wide, 16 colour cycles
  c.source = "portrait-strip.json";
  c.pitch = 52;
  c.slope = -7;
  c.center = 0.5;
  c.viewConeDegrees = 40;
  c.dpi = 324;
  c.screenW = 384;
  c.screenH = 112;
  c.invView = true;
  const LenticularDesign portrait = designLenticular(c);
  // R: each subpixel's own view; G: one minus it (as a red-to-green ramp of views interlaced).
  Image white(384, 112, Vec3f(1.0f)), ramp(384, 112);
  for (int y = 0; y < 112; ++y)
    for (int x = 0; x < 384; ++x)
      ramp.at(x, y) = {float(viewFraction(portrait, x, y, 0)),
                       float(1 - viewFraction(portrait, x, y, 1)), 0.0f};
  for (const double spot : {0.0, 1.0, 3.0})
    for (const double t : {0.5, 0.3, 0.62}) {
      LensOptics o;
      o.spotWidthSubpixels = spot;
      const LenticularDesign d = withOptics(portrait, o);
      const Vec3d eye = lensEyeOnDesignLine(d, t);
      const Image seenWhite = simulateLenticularView(d, white, eye);
      const Image seenRamp = simulateLenticularView(d, ramp, eye);
      // Over whole periods of the lenses against the pixels (17 lenses are 107.0 pixels: 6.29412
      // a lens), down whole colour cycles, the lenses cut by the panel's edges aside.
      double white3[3] = {0, 0, 0}, red = 0, green = 0;
      for (int y = 0; y < 112; ++y)
        for (int x = 31; x < 31 + 3 * 107; ++x) {
          for (int ch = 0; ch < 3; ++ch) white3[ch] += seenWhite.at(x, y)[ch] / (112.0 * 321);
          red += seenRamp.at(x, y).x;
          green += seenRamp.at(x, y).y;
        }
      for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(white3[ch], 1.0, 0.02) << spot << " " << t;
      EXPECT_NEAR(red / (red + green), t, 0.008) << spot << " " << t;
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
