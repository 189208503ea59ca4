#include "parallax/display/lenticular.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "parallax/core/error.h"

namespace parallax {
namespace {

constexpr double kPi = 3.14159265358979323846;

LenticularCalibration device(double pitch, double slope, double center, double cone, double dpi,
                             int w, int h, bool invView) {
  LenticularCalibration c;
  c.source = "test.json";
  c.pitch = pitch;
  c.slope = slope;
  c.center = center;
  c.viewConeDegrees = cone;
  c.dpi = dpi;
  c.screenW = w;
  c.screenH = h;
  c.invView = invView;
  return c;
}

// Device-like calibrations (invented values of the usual magnitudes, not real devices).
LenticularCalibration portraitLike() {
  return device(47.61, -6.21, 0.413, 40, 324, 1536, 2048, true);
}
LenticularCalibration landscapeLike() {
  LenticularCalibration c = device(40.3, -5.47, -0.22, 50, 283, 3840, 2160, false);
  c.flipSubpixels = true;
  return c;
}
LenticularCalibration mirroredLike() {
  LenticularCalibration c = device(49.9, 5.8, 0.05, 35, 338, 2560, 1600, true);
  c.flipImageX = true;
  return c;
}

// The published formula, transcribed step by step from the HoloPlay Unity SDK (2017): the set-up
// in Quilt.cs PassConfigToMaterial and the fragment shader HoloPlay/Lenticular.shader, including
// its padded fmod and its blend for invView. The fragment of pixel (x, y) runs at the pixel's
// centre, and Unity's uv has v = 0 at the bottom row.
double publishedView(const LenticularCalibration& c, int x, int y, int channel) {
  const double screenInches = double(c.screenW) / c.dpi;
  double newPitch = c.pitch * screenInches;
  newPitch *= std::cos(std::atan(1.0 / c.slope));
  double newTilt = double(c.screenH) / (double(c.screenW) * c.slope);
  newTilt *= c.flipImageX ? -1.0 : 1.0;
  double subp = 1.0 / (double(c.screenW) * 3.0);
  subp *= c.flipImageX ? -1.0 : 1.0;
  const int ri = c.flipSubpixels ? 2 : 0, bi = c.flipSubpixels ? 0 : 2;
  const double flipX = c.flipImageX ? 1.0 : 0.0, invView = c.invView ? 1.0 : 0.0;

  const double uvX = (x + 0.5) / c.screenW;
  const double uvY = ((c.screenH - 1 - y) + 0.5) / c.screenH;
  const double nuvX = (1.0 - flipX) * uvX + flipX * (1.0 - uvX);
  // The output's red takes rgb[ri], green rgb[1], blue rgb[bi]: the slot i of each channel.
  const int i = channel == 0 ? ri : (channel == 1 ? 1 : bi);
  double z = (nuvX + i * subp + uvY * newTilt) * newPitch - c.center;
  z = std::fmod(z + std::ceil(std::fabs(newPitch * newTilt)) + 1.0, 1.0);
  z = (1.0 - invView) * z + invView * (1.0 - z);
  return z;
}

// Distance on the circle of view fractions (view 1 is view 0).
double circular(double a, double b) {
  const double d = std::fabs(a - b);
  return std::min(d, 1.0 - d);
}

TEST(Lenticular, DesignDerivesFigures) {
  const LenticularDesign d = designLenticular(device(50, -5, 0.2, 40, 300, 1500, 2000, true));
  // cos(atan(1 / -5)) = 5 / sqrt(26); 1500 px at 300 DPI is 5 inches.
  EXPECT_NEAR(d.pitchPx, 50 * 5 * 5 / std::sqrt(26.0), 1e-9);
  EXPECT_NEAR(d.tilt, -4.0 / 15.0, 1e-12);
  EXPECT_NEAR(d.pixelPitchMm, 25.4 / 300, 1e-12);
  EXPECT_NEAR(d.widthMm, 127.0, 1e-9);
  EXPECT_NEAR(d.heightMm, 2000 * 25.4 / 300, 1e-9);
  EXPECT_NEAR(d.lensPitchMm, 0.508, 1e-12);
  // Along a row a lens is wider by 1 / cos(slant), slant = atan(1/5) from vertical.
  EXPECT_NEAR(d.lensSlantDegrees, std::atan(0.2) * 180 / kPi, 1e-12);
  EXPECT_NEAR(d.horizontalLensPitchMm, 0.508 * std::sqrt(26.0) / 5, 1e-9);
  EXPECT_NEAR(d.subpixelsPerLens, 3 * 1500 / d.pitchPx, 1e-9);
  EXPECT_NEAR(d.lenticuleCount, d.pitchPx * (1 + 4.0 / 15.0), 1e-9);
  // A 1 m zone across a 40 degree cone: 500 mm / tan(20 degrees).
  EXPECT_NEAR(d.viewDistanceMm, 500 / std::tan(20 * kPi / 180), 1e-9);
  EXPECT_NEAR(d.viewZoneWidthMm, 1000, 1e-9);
  EXPECT_NEAR(designLenticular(d.calibration, 600).viewDistanceMm, 600, 0);
}

TEST(Lenticular, HandComputedPixels) {
  // pitch 50, slope -5, center 0.2, 300 DPI, 1500x2000, invView: pitch_px = 1250/sqrt(26)
  // = 245.145169, tilt = -4/15. Bottom-left pixel (0, 1999): u = 1/3000, v = 1/4000, so red's
  // phase is (1/3000 - 1/15000) * 245.145169 - 0.2 = -0.134628, fract 0.865372, inverted
  // 0.134628; green and blue add 1/4500 of the width each (0.054477 of a lens).
  const LenticularDesign d = designLenticular(device(50, -5, 0.2, 40, 300, 1500, 2000, true));
  EXPECT_NEAR(viewFraction(d, 0, 1999, 0), 0.134628, 1e-6);
  EXPECT_NEAR(viewFraction(d, 0, 1999, 1), 0.080151, 1e-6);
  EXPECT_NEAR(viewFraction(d, 0, 1999, 2), 0.025675, 1e-6);
  // The centre pixel (750, 1000): u = 750.5/1500, v = 0.49975: phase 89.784620, inverted 0.215380.
  EXPECT_NEAR(viewFraction(d, 750, 1000, 0), 0.215380, 1e-6);
}

TEST(Lenticular, MatchesThePublishedFormula) {
  for (const LenticularCalibration& c : {portraitLike(), landscapeLike(), mirroredLike()}) {
    const LenticularDesign d = designLenticular(c);
    const int w = c.screenW, h = c.screenH;
    const int pixels[][2] = {{0, 0},     {w - 1, h - 1}, {w / 2, h / 2},    {123, 457},
                             {w - 7, 3}, {5, h - 2},     {w / 3, 2 * h / 3}};
    for (const auto& p : pixels)
      for (int channel = 0; channel < 3; ++channel)
        EXPECT_LT(
            circular(viewFraction(d, p[0], p[1], channel), publishedView(c, p[0], p[1], channel)),
            1e-9)
            << c.pitch << " pixel " << p[0] << "," << p[1] << " channel " << channel;
  }
}

TEST(Lenticular, ViewFractionsLieInTheUnitInterval) {
  for (const LenticularCalibration& c : {portraitLike(), landscapeLike(), mirroredLike()}) {
    const LenticularDesign d = designLenticular(c);
    for (int y = 0; y < c.screenH; y += 7)
      for (int x = 0; x < c.screenW; x += 3)
        for (int channel = 0; channel < 3; ++channel) {
          const double f = viewFraction(d, x, y, channel);
          ASSERT_GE(f, 0.0);
          ASSERT_LT(f, 1.0);
        }
  }
  // A phase of exactly an integer: view 0, not 1, even inverted.
  LenticularCalibration c = device(50, -5, 0.0, 40, 300, 1500, 2000, true);
  const LenticularDesign d = designLenticular(c);
  c.center = (0.5 / 1500 + (1 - 1000.5 / 2000) * d.tilt) * d.pitchPx;
  EXPECT_LT(viewFraction(designLenticular(c), 0, 1000, 0), 1.0);
}

TEST(Lenticular, SubpixelsOfAPixelDifferByAThirdOfAPixel) {
  for (const LenticularCalibration& c : {portraitLike(), landscapeLike(), mirroredLike()}) {
    const LenticularDesign d = designLenticular(c);
    // One slot to the right adds pitch_px / (3 W) to the phase; invView and the mirror each
    // reverse the sign, and BGR panels put red in the last slot.
    double step = d.pitchPx / (3.0 * c.screenW);
    if (c.invView != c.flipImageX) step = -step;
    const int first = c.flipSubpixels ? 2 : 0, last = 2 - first;
    for (int y = 0; y < c.screenH; y += 101)
      for (int x = 0; x < c.screenW; x += 37) {
        const double a = viewFraction(d, x, y, first), b = viewFraction(d, x, y, 1);
        const double e = viewFraction(d, x, y, last);
        EXPECT_LT(circular(b - a, step), 1e-9);
        EXPECT_LT(circular(e - b, step), 1e-9);
      }
  }
}

// The shader's formula written out independently (holoplay-core's interlacer): offsets in
// pixels over the screen size, added to u and v before tilt and pitch, 1 - frac; the cell by the
// pattern with rows counted from the bottom.
TEST(Lenticular, SubpixelCellsFollowTheShaderFormulaForEveryPattern) {
  // The two cells of a 16" Gen3 landscape panel (LKG-J): the same layout mirrored in y.
  const SubpixelCell up{{-0.31, 0.28, 0.0}, {0.25, 0.25, -0.25}};
  const SubpixelCell down{{-0.31, 0.28, 0.0}, {-0.25, -0.25, 0.25}};
  const SubpixelCell third{{0.1, -0.1, 0.3}, {0.0, 0.1, -0.1}};
  for (int mode = 0; mode < kCellPatternModes; ++mode) {
    LenticularCalibration c = portraitLike();
    c.cellPatternMode = mode;
    c.subpixelCells = {up, down, third};
    const LenticularDesign d = designLenticular(c);
    for (const auto& p : {std::array<int, 2>{10, 2047}, std::array<int, 2>{11, 2047},
                          std::array<int, 2>{10, 2046}, std::array<int, 2>{11, 2045},
                          std::array<int, 2>{400, 1000}, std::array<int, 2>{401, 1001}}) {
      const int x = p[0], yUp = c.screenH - 1 - p[1];
      const int expectedCell[kCellPatternModes] = {0, (x % 2) ^ (yUp % 2), x % 2,
                                                   (yUp + 2 * (x % 2)) % 4 % 3, yUp % 2};
      ASSERT_EQ(cellIndex(c, x, yUp), expectedCell[mode]) << "mode " << mode;
      const SubpixelCell& cell = c.subpixelCells[size_t(expectedCell[mode])];
      const double u = (x + 0.5) / c.screenW, v = (yUp + 0.5) / c.screenH;
      for (int ch = 0; ch < 3; ++ch) {
        double view = u + cell.offsetX[size_t(ch)] / c.screenW;
        view += (v + cell.offsetY[size_t(ch)] / c.screenH) * d.tilt;
        view = view * d.pitchPx - c.center;
        view = 1.0 - (view - std::floor(view));  // the shader's 1 - frac (invView)
        EXPECT_LT(circular(viewFraction(d, x, p[1], ch), view), 1e-9) << "mode " << mode;
      }
    }
  }
}

TEST(Lenticular, AngleMapsTheViewConeAcross) {
  const LenticularDesign d = designLenticular(portraitLike());
  const double half = 20 * kPi / 180;
  EXPECT_NEAR(viewAngle(d, 0.0), -half, 1e-12);
  EXPECT_NEAR(viewAngle(d, 0.5), 0.0, 1e-12);
  EXPECT_NEAR(viewAngle(d, 1.0), half, 1e-12);
  EXPECT_NEAR(viewFractionOfAngle(d, viewAngle(d, 0.3)), 0.3, 1e-12);
  EXPECT_NEAR(viewFractionOfAngle(d, 1.5 * half), 1.25, 1e-12);  // beyond the cone
}

// Parallel bundles: every subpixel of view f sends its light at the angle theta(f), wherever it
// is (the old direction).
TEST(Lenticular, ParallelBundlesLeaveInTheViewsDirection) {
  LensOptics parallel;
  parallel.bundles = LensBundles::Parallel;
  const LenticularDesign d = designLenticular(landscapeLike(), 0, parallel);
  const double D = d.viewDistanceMm;
  for (const auto& p : {std::array<double, 2>{0.5, 0.5}, std::array<double, 2>{1919.2, 1080.7}}) {
    for (int ch = 0; ch < 3; ++ch) {
      const LenticularRay r = lenticularRay(d, p[0], p[1], ch);
      EXPECT_DOUBLE_EQ(r.origin.z, D);
      EXPECT_DOUBLE_EQ(r.origin.y, 0.0);  // toward the viewer's eye line
      EXPECT_NEAR(r.origin.x + r.direction.x * D, r.panelPoint.x, 1e-9);
      EXPECT_NEAR(r.origin.y + r.direction.y * D, r.panelPoint.y, 1e-9);
      EXPECT_NEAR(std::atan2(r.origin.x - r.panelPoint.x, D), viewAngle(d, r.viewFraction), 1e-12);
      EXPECT_DOUBLE_EQ(r.viewFraction, viewFractionAt(d, p[0], p[1], ch));
    }
  }
}

// Converging bundles (the default): the light of view f, from anywhere on the panel, passes
// through one eye point, (C tan theta(f), y, C); so from that point every subpixel of view f is
// seen, and an eye nearer or farther sees different views at the panel's two edges.
TEST(Lenticular, ConvergingBundlesMeetAtTheirEyePoint) {
  const LenticularDesign d = designLenticular(landscapeLike());
  ASSERT_EQ(d.optics.bundles, LensBundles::Converging);
  const double C = d.optics.convergenceDistanceMm;
  EXPECT_DOUBLE_EQ(C, d.viewDistanceMm);
  for (const double f : {0.05, 0.3, 0.5, 0.77}) {
    const double meet = C * std::tan((f - 0.5) * d.calibration.viewConeDegrees * kPi / 180);
    for (const double filmX : {0.5, 700.2, 1919.2, 3839.5}) {
      const LenticularRay r = lenticularRay(d, filmX, 1080.5, 1, f);
      EXPECT_NEAR(r.origin.x, meet, 1e-9) << f << " " << filmX;  // z = D = C
      EXPECT_NEAR(r.origin.x + r.direction.x * C, r.panelPoint.x, 1e-9);
      EXPECT_NEAR(lensFractionSeen(d, r.panelPoint.x, {meet, 40, C}), f, 1e-12);
      EXPECT_NEAR(lensQuiltFraction(d, r.panelPoint.x, f), f, 1e-15);  // the camera at D
    }
    // At half the distance the two edges show views differing by the edges' angle apart.
    const Vec3d nearer{0.5 * meet, 0, 0.5 * C};
    const double left = lensFractionSeen(d, -0.5 * d.widthMm, nearer);
    const double right = lensFractionSeen(d, 0.5 * d.widthMm, nearer);
    EXPECT_GT(left - right, 0.05);
  }
  // Another convergence distance: the eye point moves there.
  LensOptics far;
  far.convergenceDistanceMm = 3 * d.viewDistanceMm;
  const LenticularDesign f = withOptics(d, far);
  EXPECT_NEAR(lensFractionSeen(f, -100, {3 * C * std::tan(0.1), 0, 3 * C}),
              lensFractionSeen(f, 100, {3 * C * std::tan(0.1), 0, 3 * C}), 1e-12);
  // Parallel bundles reach the design line elsewhere: the quilt camera there.
  LensOptics parallel;
  parallel.bundles = LensBundles::Parallel;
  const LenticularDesign p = withOptics(d, parallel);
  const double x = 0.4 * d.widthMm, D = d.viewDistanceMm;
  const double reach = x + D * std::tan(viewAngle(p, 0.6));
  EXPECT_NEAR(lensQuiltFraction(p, x, 0.6), viewFractionOfAngle(p, std::atan(reach / D)), 1e-12);
  EXPECT_GT(lensQuiltFraction(p, x, 0.6), 0.6);
}

// What an eye integrates: a subpixel spans delta = 1 / subpixelsPerLens of the views; the spot's
// weight is the box delta convolved with the box W delta over W delta, whose integral over the
// view difference is delta (the box's area) and whose peak is min(1, 1 / W).
TEST(Lenticular, SpotWeightIsTheSubpixelBoxSeenThroughTheSpot) {
  const LenticularDesign base = designLenticular(portraitLike());
  const double delta = subpixelViewWidth(base);
  EXPECT_NEAR(delta, 1 / base.subpixelsPerLens, 1e-15);
  for (const double spot : {0.0, 0.5, 1.0, 3.0, 7.5}) {
    LensOptics o;
    o.spotWidthSubpixels = spot;
    const LenticularDesign d = withOptics(base, o);
    const double half = lensSpotHalfSupport(d);
    EXPECT_NEAR(half, 0.5 * (1 + spot) * delta, 1e-15);
    // Numerical integral (midpoint rule) against the analytic area.
    const int n = 200000;
    double area = 0, peak = 0;
    for (int i = 0; i < n; ++i) {
      const double x = -1.5 * half + 3 * half * (i + 0.5) / n;
      const double w = lensSpotWeight(d, x);
      area += w * 3 * half / n;
      peak = std::max(peak, w);
      if (std::fabs(x) >= half) {
        EXPECT_EQ(w, 0.0) << spot << " " << x;
      }
    }
    EXPECT_NEAR(area, delta, 1e-4 * delta) << spot;
    EXPECT_NEAR(peak, spot > 1 ? 1 / spot : 1.0, 1e-3) << spot;
    // Subpixels tiling the lens's period (every delta) sum to 1 wherever the eye looks.
    for (const double eye : {0.0, 0.123, 0.37 * delta}) {
      double sum = 0;
      for (int k = -40; k <= 40; ++k) sum += lensSpotWeight(d, k * delta - eye);
      EXPECT_NEAR(sum, 1.0, 1e-12) << spot << " " << eye;
    }
  }
  // A pixel-wide spot sees each colour channel (every third subpixel) a third of the time.
  LensOptics pixel;
  pixel.spotWidthSubpixels = 3;
  const LenticularDesign d = withOptics(base, pixel);
  for (const double eye : {0.0, 0.2 * delta, 0.5 * delta, 1.7 * delta}) {
    double red = 0;
    for (int k = -12; k <= 12; ++k) red += lensSpotWeight(d, 3 * k * delta - eye);
    EXPECT_NEAR(red, 1.0 / 3, 1e-12) << eye;
  }
  EXPECT_EQ(lensOpticsProblem(pixel), "");
  pixel.spotWidthSubpixels = -1;
  EXPECT_NE(lensOpticsProblem(pixel), "");
  EXPECT_THROW(withOptics(base, pixel), std::invalid_argument);
}

TEST(Lenticular, SubpixelPointsSitOnTheirPixel) {
  const LenticularDesign d = designLenticular(portraitLike());
  const double px = d.pixelPitchMm;
  // Pixel (0, 0) is the top-left; its subpixels are a third of a pixel apart, centred on it.
  const Vec3d r = subpixelPointMm(d, 0.5, 0.5, 0), g = subpixelPointMm(d, 0.5, 0.5, 1);
  const Vec3d b = subpixelPointMm(d, 0.5, 0.5, 2);
  EXPECT_NEAR(g.x, -0.5 * d.widthMm + 0.5 * px, 1e-9);
  EXPECT_NEAR(g.y, 0.5 * d.heightMm - 0.5 * px, 1e-9);
  EXPECT_NEAR(g.x - r.x, px / 3, 1e-9);
  EXPECT_NEAR(b.x - g.x, px / 3, 1e-9);
  // Mirrored panels: the viewer sees column 0 on the right, its red subpixel rightmost.
  const LenticularDesign m = designLenticular(mirroredLike());
  EXPECT_NEAR(subpixelPointMm(m, 0.5, 0.5, 1).x, 0.5 * m.widthMm - 0.5 * m.pixelPitchMm, 1e-9);
  EXPECT_GT(subpixelPointMm(m, 0.5, 0.5, 0).x, subpixelPointMm(m, 0.5, 0.5, 2).x);
}

TEST(Lenticular, BadCalibrationsNameTheKey) {
  const auto message = [](LenticularCalibration c) {
    try {
      designLenticular(c);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  LenticularCalibration c = portraitLike();
  c.slope = 0;
  EXPECT_NE(message(c).find("test.json: /slope:"), std::string::npos) << message(c);
  c = portraitLike();
  c.viewConeDegrees = 0;
  EXPECT_NE(message(c).find("/viewCone"), std::string::npos);
  c = portraitLike();
  c.pitch = 5000;  // lenses narrower than a pixel
  EXPECT_NE(message(c).find("/pitch"), std::string::npos);
  c = portraitLike();
  c.cellPatternMode = 5;
  EXPECT_NE(message(c).find("/CellPatternMode"), std::string::npos);
  c = portraitLike();
  c.subpixelCells = {SubpixelCell{{0.0, 3.0, 0.0}, {0.0, 0.0, 0.0}}};  // 3 pixels away
  EXPECT_NE(message(c).find("/subpixelCells/0"), std::string::npos);
}

}  // namespace
}  // namespace parallax
