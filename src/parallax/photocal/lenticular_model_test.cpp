// The lens sheet's field against the design's own formula, and the calibration found back from
// a field.
#include "parallax/photocal/lenticular_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "parallax/display/lenticular_presets.h"

namespace parallax::photocal {
namespace {

double wrapHalf(double v) {
  return v - std::round(v);
}

TEST(LenticularModel, FieldIsTheFormulaAtEverySubpixel) {
  for (const char* name : {"portrait", "go", "16-gen3", "16-gen3-portrait"}) {
    const LenticularDesign d = designLenticular(*lenticularPreset(name));
    const PhaseField f = phaseFieldOf(d);
    // The field predicts the formula's raw phase at subpixels it was not fitted to: exactly on
    // stripes; on OLED cells each cell's subpixels sit a little off it, and it is their mean.
    const bool cells = !d.calibration.subpixelCells.empty();
    double sum = 0;
    int count = 0;
    for (int k = 0; k < 50; ++k) {
      const int x = (k * 7919) % d.calibration.screenW, y = (k * 104729) % d.calibration.screenH;
      for (int dy = 0; dy < 4; ++dy)
        for (int dx = 0; dx < 2; ++dx)
          for (int c = 0; c < 3; ++c) {
            const int px = std::min(x + dx, d.calibration.screenW - 1);
            const int py = std::min(y + dy, d.calibration.screenH - 1);
            const Vec3d p = subpixelPointMm(d, px + 0.5, py + 0.5, c);
            const double raw = 1.0 - viewFraction(d, px, py, c);
            const double off = wrapHalf(raw - (f.gx * p.x + f.gy * p.y + f.r0));
            EXPECT_NEAR(off, 0, cells ? 0.05 : 1e-6)
                << name << " at " << px << "," << py << " channel " << c;
            sum += off;
            ++count;
          }
    }
    EXPECT_NEAR(sum / count, 0, cells ? 2e-3 : 1e-6) << name;
    // Its across period is the pitch in pixels over the width (pitch_px lenses across it).
    EXPECT_NEAR(std::abs(f.gx) * d.widthMm, d.pitchPx, 1e-9 * d.pitchPx) << name;
  }
}

TEST(LenticularModel, CalibrationFromItsOwnFieldIsItself) {
  for (const char* name : {"portrait", "go", "32-gen3"}) {
    const LenticularCalibration c = *lenticularPreset(name);
    const LenticularDesign d = designLenticular(c);
    const LenticularCalibration back = calibrationWithField(c, phaseFieldOf(d), d.viewDistanceMm);
    EXPECT_NEAR(back.pitch, c.pitch, 1e-9 * c.pitch) << name;
    EXPECT_NEAR(back.slope, c.slope, 1e-9 * std::abs(c.slope)) << name;
    EXPECT_NEAR(wrapHalf(back.center - c.center), 0, 1e-9) << name;
  }
}

TEST(LenticularModel, ChangedFieldGivesTheCalibrationThatHasIt) {
  const LenticularCalibration c = *lenticularPreset("portrait");
  const LenticularDesign d = designLenticular(c);
  PhaseField target = phaseFieldOf(d);
  target.gx *= 1.004, target.gy *= 0.99, target.r0 = std::fmod(target.r0 + 0.3, 1.0);
  const LenticularCalibration moved = calibrationWithField(c, target, d.viewDistanceMm);
  const PhaseField seen = phaseFieldOf(designLenticular(moved, d.viewDistanceMm));
  EXPECT_NEAR(seen.gx, target.gx, 1e-9 * std::abs(target.gx));
  EXPECT_NEAR(seen.gy, target.gy, 1e-9 * std::abs(target.gy));
  EXPECT_NEAR(wrapHalf(seen.r0 - target.r0), 0, 1e-9);
}

// A sheet's field: the across period on the pixels is the lens pitch magnified by (D + g) / D
// (lenses seen from the design distance), and the phase moves by a period with the sheet.
TEST(LenticularModel, SheetFieldScalesThePitchToTheDesignDistance) {
  const LensSheet sheet{0.5, 8.0, 0.1, 1.2};
  const PhaseField f = fieldOfSheet(sheet, true, 600);
  const double period = 1 / std::hypot(f.gx, f.gy);
  EXPECT_NEAR(period, 0.5 * 601.2 / 600, 1e-12);
  EXPECT_NEAR(std::atan2(-f.gy, f.gx) * 180 / M_PI, 8.0, 1e-9);
  LensSheet moved = sheet;
  moved.phaseMm += 0.5;
  EXPECT_NEAR(wrapHalf(fieldOfSheet(moved, true, 600).r0 - f.r0), 0, 1e-12);
  moved.phaseMm = sheet.phaseMm + 0.125;
  EXPECT_NEAR(wrapHalf(fieldOfSheet(moved, true, 600).r0 - f.r0), -0.25, 1e-12);
  // Without the lens's inversion the phase runs the other way.
  EXPECT_NEAR(fieldOfSheet(sheet, false, 600).gx, -f.gx, 1e-15);
}

}  // namespace
}  // namespace parallax::photocal
