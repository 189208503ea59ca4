// The lens's depth of field and the depth-scaled camera (display/depth_scaled_display.h): the
// figure against a hand computation from a Portrait's calibration, a point at that depth seen
// through ideal lenses spread over one lens (a brute-force ray computation over the panel's
// subpixels, not the formula), and the scaled camera showing a point at z at k z.
#include "parallax/display/depth_scaled_display.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "parallax/display/lenticular_presets.h"

namespace parallax {
namespace {

constexpr double kPi = 3.14159265358979323846;

LenticularDesign preset(const char* name) {
  return designLenticular(*lenticularPreset(name));
}

TEST(LensDepthOfField, PortraitMatchesAHandComputation) {
  // lkg:portrait: 52 lenses per inch across the lenses, slope -7, 324 DPI, a 40 degree cone.
  // Along a row a lens is 1/cos(atan(1/7)) = sqrt(50)/7 wider: p_h = 25.4/52 * sqrt(50)/7 mm;
  // a subpixel is a third of 25.4/324 mm, so S = 3 p_h 324 / 25.4 subpixels lie under a lens;
  // a one-subpixel window spans (p_h / S) / F in tan(theta), F = p_h / (2 tan 20 deg), and at
  // depth z spreads over one lens when |z| = S p_h / (2 tan 20 deg).
  const double ph = 25.4 / 52 * std::sqrt(50.0) / 7;  // 0.49342 mm
  const double s = 3 * ph * 324 / 25.4;               // 18.882
  const double byHand = s * ph / (2 * std::tan(20 * kPi / 180));
  EXPECT_NEAR(byHand, 12.799, 0.001);
  const LenticularDesign portrait = preset("portrait");
  EXPECT_NEAR(lensDepthOfFieldMm(portrait), byHand, 1e-9);
  // N lenses, a wider window: linear in N, inverse in the window, which is the lens optics'
  // spot where that is wider than a subpixel (the ideal lens's window is one subpixel too).
  LensOptics wideSpot = portrait.optics;
  wideSpot.spotWidthSubpixels = 2;
  EXPECT_NEAR(lensDepthOfFieldMm(withOptics(portrait, wideSpot), 3), 1.5 * byHand, 1e-9);
  LensOptics ideal = portrait.optics;
  ideal.spotWidthSubpixels = 0;
  EXPECT_NEAR(lensDepthOfFieldMm(withOptics(portrait, ideal)), byHand, 1e-9);
  // The 16" Gen3: 44.72 lenses per inch, slope -6.9, 283 DPI, 50 degrees.
  const double ph16 = 25.4 / 44.72 / std::cos(std::atan(1 / 6.9));
  const double s16 = 3 * ph16 * 283 / 25.4;
  EXPECT_NEAR(lensDepthOfFieldMm(preset("16-gen3")), s16 * ph16 / (2 * std::tan(25 * kPi / 180)),
              1e-9);
}

// Brute force: every subpixel of a band of columns on every row of the panel, with the ray the
// direct route traces for it (lenticularRay at its centre, its own view). An ideal lens shows an
// eye the subpixels whose view lies within half a subpixel's worth of view (1 / (2 S)) of the
// view whose light from that place reaches the eye under the display's optics (lensFractionSeen:
// bundles converging at D by default); of those, the ones whose ray passes through a small point P
// at depth z show P. The panel positions that show P are P's image; its width, in lenses along a
// row.
double imageWidthInLenses(const LenticularDesign& d, double z, const Vec3d& eye) {
  const double halfWindow = 0.5 / d.subpixelsPerLens;
  // P on the line from the eye through the panel's centre.
  const double pointX = eye.x * z / eye.z, tolerance = 0.004;
  const int w = d.calibration.screenW;
  double lo = 1e300, hi = -1e300;
  for (int y = 0; y < d.calibration.screenH; ++y)
    for (int x = w / 2 - 60; x < w / 2 + 60; ++x)
      for (int c = 0; c < 3; ++c) {
        const LenticularRay r = lenticularRay(d, x + 0.5, y + 0.5, c);
        const Vec3d p = r.panelPoint;
        const double eyeView = lensFractionSeen(d, p.x, eye);
        double off = r.viewFraction - eyeView;
        off -= std::round(off);
        if (std::abs(off) > halfWindow) continue;
        // The ray from the panel point toward its origin (z = D) crosses z at:
        const double hit = p.x + (r.origin.x - p.x) * z / r.origin.z;
        if (std::abs(hit - pointX) > tolerance) continue;
        lo = std::min(lo, p.x), hi = std::max(hi, p.x);
      }
  // Each showing subpixel covers its own width (a lens pitch over S) of the image, so the image
  // spans from the first one's left edge to the last one's right edge.
  return (hi - lo) / d.horizontalLensPitchMm + 1.0 / d.subpixelsPerLens;
}

TEST(LensDepthOfField, APointAtTheLimitSpreadsOverOneLens) {
  const LenticularDesign d = preset("portrait");
  const double z = lensDepthOfFieldMm(d);
  for (const Vec3d eye : {Vec3d{0, 0, d.viewDistanceMm}, Vec3d{200, 0, d.viewDistanceMm}}) {
    for (const double depth : {z, -z}) {
      const double width = imageWidthInLenses(d, depth, eye);
      std::printf("eye x %+.0f mm, z %+.2f mm: the point's image spans %.3f lenses\n", eye.x, depth,
                  width);
      // One lens: the window's angle is the model's (f - 1/2) cone, 0.96 of the lens's
      // 2 tan(cone / 2) at the centre, and seen from D the panel magnifies depth by D / (D - z).
      EXPECT_GT(width, 0.85) << "z " << depth << " eye x " << eye.x;
      EXPECT_LT(width, 1.1) << "z " << depth << " eye x " << eye.x;
    }
    // Twice as deep, twice as wide; in the panel's plane, a point (no spread).
    EXPECT_NEAR(imageWidthInLenses(d, 2 * z, eye), 2 * imageWidthInLenses(d, z, eye), 0.2);
    EXPECT_LT(imageWidthInLenses(d, 0.05 * z, eye), 0.15);
  }
}

// A display whose rays all leave the panel toward one eye line, to see the scaling alone.
TEST(DepthScaledDisplay, KeepsThePanelPointAndScalesTheHorizontalSlope) {
  const LenticularDesign d = preset("portrait");
  const std::unique_ptr<DisplayModel> plain = makeLenticularDisplay(d);
  const std::unique_ptr<DisplayModel> scaled = scaleDisplayedDepth(makeLenticularDisplay(d), 0.25);
  for (const double fx : {10.5, 2000.5, 4500.5})
    for (const double fy : {3.5, 1000.5}) {
      const DisplayRay a = plain->ray(fx, fy, 0.5, 0.5), b = scaled->ray(fx, fy, 0.5, 0.5);
      const double ta = a.origin.z / -a.direction.z, tb = b.origin.z / -b.direction.z;
      EXPECT_NEAR(a.origin.x + ta * a.direction.x, b.origin.x + tb * b.direction.x, 1e-9);
      EXPECT_NEAR(a.origin.y + ta * a.direction.y, b.origin.y + tb * b.direction.y, 1e-9);
      EXPECT_NEAR(b.direction.x / b.direction.z, 0.25 * a.direction.x / a.direction.z, 1e-12);
      EXPECT_NEAR(b.direction.y / b.direction.z, a.direction.y / a.direction.z, 1e-12);
    }
  EXPECT_EQ(scaled->lenticularDesign(), scaled->lenticularDesign());
  EXPECT_EQ(scaled->kind(), DisplayKind::Lenticular);
  EXPECT_EQ(scaleDisplayedDepth(makeLenticularDisplay(d), 1.0)->intendedEye({1, 2, 3}).z, 3.0);
  EXPECT_THROW(scaleDisplayedDepth(makeLenticularDisplay(d), 0.0), std::invalid_argument);
  EXPECT_THROW(depthScaledView(*plain, 1.5), std::invalid_argument);
}

// The camera's ray of each film sample against the panel's own: the eye a physical ray reaches
// at some distance sees, through that panel point, the camera's ray, which must pass through
// intendedEye of that eye (the reference's camera looks from there); and the camera's ray meets
// depth z where the physical ray meets depth k z (the point the camera sees at z is shown at
// k z, its x kept).
TEST(DepthScaledDisplay, ItsRaysPassThroughTheIntendedEyeAndShowZAtKZ) {
  const LenticularDesign d = preset("portrait");
  const double k = 0.3;
  const std::unique_ptr<DisplayModel> plain = makeLenticularDisplay(d);
  const std::unique_ptr<DisplayModel> scaled = scaleDisplayedDepth(makeLenticularDisplay(d), k);
  const auto xAt = [](const DisplayRay& r, double z) {
    return r.origin.x + r.direction.x * (z - r.origin.z) / r.direction.z;
  };
  for (const double fx : {10.5, 2300.5, 4600.5})
    for (const double fy : {3.5, 1500.5})
      for (const double u : {0.1, 0.5, 0.9}) {
        const DisplayRay physical = plain->ray(fx, fy, u, 0.5),
                         camera = scaled->ray(fx, fy, u, 0.5);
        for (const double eyeZ : {700.0, 1374.0}) {
          const Vec3d eye{xAt(physical, eyeZ), 0, eyeZ};
          const Vec3d seen = scaled->intendedEye(eye);
          EXPECT_NEAR(seen.z, eyeZ / k, 1e-9);
          EXPECT_NEAR(xAt(camera, seen.z), seen.x, 1e-6);
        }
        for (const double z : {-60.0, 40.0})
          EXPECT_NEAR(xAt(camera, z), xAt(physical, k * z), 1e-9);
      }
}

}  // namespace
}  // namespace parallax
