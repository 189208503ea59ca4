// The mask raster: open area equals the duty cycle for every mask type, and the slit period
// of a row is the designed one (found by an independent Fourier analysis of the raster).
#include "parallax/display/mask.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numeric>

namespace parallax {
namespace {

DisplayDesign designWith(MaskKind kind, double duty = 1.0 / 9.0) {
  DisplaySpec s = defaultDisplaySpec();
  s.maskPanel.width = 480;
  s.maskPanel.height = 120;
  s.imagePanel.width = 480;
  s.imagePanel.height = 120;
  s.mask.kind = kind;
  s.mask.dutyCycle = duty;
  s.mask.slantDegrees = 18.43;
  s.mask.wiggleAmplitudeMm = 0.6;
  s.mask.wiggleWavelengthMm = 7.0;
  s.mask.jitterAmplitude = 0.2;
  s.mask.verticalPeriodPx = 9.045;
  return designDisplay(s);
}

double meanOf(const std::vector<float>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

// The period (in pixels) of the strongest spectral peak of a row, found by scanning the
// discrete-time Fourier transform finely between 3 and 40 pixels.
double dominantPeriod(const std::vector<float>& raster, int width, int row) {
  const double mean =
      std::accumulate(raster.begin() + row * width, raster.begin() + (row + 1) * width, 0.0) /
      width;
  double bestPeriod = 0, bestPower = -1;
  for (double period = 3.0; period <= 40.0; period += 0.0005) {
    std::complex<double> sum = 0;
    for (int x = 0; x < width; ++x)
      sum += (raster[size_t(row * width + x)] - mean) *
             std::polar(1.0, -2.0 * 3.14159265358979 * x / period);
    if (std::norm(sum) > bestPower) bestPower = std::norm(sum), bestPeriod = period;
  }
  return bestPeriod;
}

TEST(Mask, MeanTransmittanceIsTheDutyCycle) {
  for (MaskKind kind : {MaskKind::Slits, MaskKind::Slanted, MaskKind::Wiggling, MaskKind::Jittered,
                        MaskKind::Pinholes})
    for (double duty : {1.0 / 9.0, 0.25, 0.5}) {
      const DisplayDesign d = designWith(kind, duty);
      const std::vector<float> raster = MaskGeometry(d).rasterize();
      // Partial periods at the panel's edges allow a deviation of about one period's worth.
      const double edge = 2.0 * d.slitPeriodPx / d.spec.maskPanel.width +
                          (kind == MaskKind::Pinholes ? 2.0 * 9.045 / 120 : 0.0);
      EXPECT_NEAR(meanOf(raster), duty, edge * duty + 1e-3) << int(kind) << " duty " << duty;
      for (float c : raster) {
        ASSERT_GE(c, 0.0f);
        ASSERT_LE(c, 1.0f + 1e-6f);
      }
    }
}

TEST(Mask, RowPeriodIsTheSlitPeriod) {
  for (MaskKind kind : {MaskKind::Slits, MaskKind::Slanted, MaskKind::Wiggling}) {
    const DisplayDesign d = designWith(kind);
    const std::vector<float> raster = MaskGeometry(d).rasterize();
    EXPECT_NEAR(dominantPeriod(raster, 480, 60), d.slitPeriodPx, 0.01) << int(kind);
  }
}

TEST(Mask, FractionalPeriodIsAntiAliasedNotRounded) {
  // 9.045 px slits at duty 1/9 are 1.005 px wide: no pixel is fully open, and each period
  // holds exactly one aperture's worth of light.
  const DisplayDesign d = designWith(MaskKind::Slits);
  const std::vector<float> raster = MaskGeometry(d).rasterize();
  int partial = 0;
  for (int x = 0; x < 480; ++x) partial += raster[size_t(x)] > 0.0f && raster[size_t(x)] < 1.0f;
  EXPECT_GT(partial, 40);
}

TEST(Mask, SlantedSlitsMoveWithHeight) {
  const MaskGeometry m(designWith(MaskKind::Slanted));
  EXPECT_NEAR(m.apertureCenterX(3, 10.0) - m.apertureCenterX(3, 0.0),
              10.0 * std::tan(18.43 * 3.14159265358979 / 180.0), 1e-9);
  EXPECT_EQ(m.nearestAperture(m.apertureCenterX(5, 7.0) + 0.3, 7.0), 5);
}

TEST(Mask, JitteredSlitsStayInOrderAndAreFoundAgain) {
  const DisplayDesign d = designWith(MaskKind::Jittered);
  const MaskGeometry m(d);
  for (int64_t k = -50; k < 50; ++k) {
    EXPECT_LT(m.apertureCenterX(k, 0), m.apertureCenterX(k + 1, 0));
    EXPECT_LE(std::abs(m.apertureCenterX(k, 0) - d.apertureOriginMm - double(k) * m.periodMm()),
              0.2 * m.periodMm() + 1e-12);
    EXPECT_EQ(m.nearestAperture(m.apertureCenterX(k, 0) + 0.1 * m.periodMm(), 0), k);
  }
}

}  // namespace
}  // namespace parallax

namespace parallax {
namespace {

TEST(Mask, PanelOffsetMovesTheRasterButNotTheApertures) {
  DisplaySpec s = defaultDisplaySpec();
  s.maskPanel.width = s.imagePanel.width = 240;
  s.maskPanel.height = s.imagePanel.height = 4;
  const DisplayDesign plain = designDisplay(s);
  s.mask.panelOffsetPx = 3.0;
  const DisplayDesign shifted = designDisplay(s);
  const MaskGeometry a(plain), b(shifted);
  // The apertures the camera traces through stay where they were...
  EXPECT_EQ(a.apertureCenterX(5, 0.0), b.apertureCenterX(5, 0.0));
  // ...and the drawn pattern moves by exactly three mask pixels.
  const std::vector<float> ra = a.rasterize(), rb = b.rasterize();
  for (int x = 0; x + 3 < 240; ++x) EXPECT_NEAR(rb[size_t(x + 3)], ra[size_t(x)], 1e-6f) << x;
}

}  // namespace
}  // namespace parallax
