#include "parallax/photocal/lenticular_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "parallax/core/error.h"

namespace parallax::photocal {

namespace {

double wrapHalf(double v) {
  return v - std::round(v);
}

// The raw phase of one subpixel from the design's own formula: 1 - view with invView.
double rawPhase(const LenticularDesign& d, int x, int y, int channel) {
  const double f = viewFraction(d, x, y, channel);
  return d.calibration.invView ? 1.0 - f : f;
}

}  // namespace

PhaseField phaseFieldOf(const LenticularDesign& d) {
  const LenticularCalibration& c = d.calibration;
  // The formula's gradient, up to the signs the flips give: tried all four, the one that leaves
  // no residual is the design's.
  const double gx = d.pitchPx / d.widthMm, gy = d.pitchPx * d.tilt / d.heightMm;
  PhaseField best;
  double bestError = 1e9;
  for (int sx = -1; sx <= 1; sx += 2)
    for (int sy = -1; sy <= 1; sy += 2) {
      PhaseField f{sx * gx, sy * gy, 0};
      // r0: the circular mean of what is left, over subpixels across the panel.
      double cs = 0, sn = 0;
      std::vector<double> left;
      // Every kind of subpixel cell alike (cellIndex repeats within 2 columns and 4 rows): a
      // panel with cells has a field only on average, each cell's subpixels a little off it.
      for (int j = 0; j < 7; ++j)
        for (int i = 0; i < 7; ++i)
          for (int cell = 0; cell < 8; ++cell)
            for (int ch = 0; ch < 3; ++ch) {
              const int x = std::min(c.screenW - 1, (c.screenW - 2) * i / 6 + cell % 2);
              const int y = std::min(c.screenH - 1, (c.screenH - 4) * j / 6 + cell / 2);
              const Vec3d p = subpixelPointMm(d, x + 0.5, y + 0.5, ch);
              const double r = rawPhase(d, x, y, ch) - f.gx * p.x - f.gy * p.y;
              left.push_back(r);
              cs += std::cos(2 * std::numbers::pi * r);
              sn += std::sin(2 * std::numbers::pi * r);
            }
      f.r0 = std::atan2(sn, cs) / (2 * std::numbers::pi);
      f.r0 -= std::floor(f.r0);
      double error = 0;
      for (double r : left) error += std::abs(wrapHalf(r - f.r0));
      if (error < bestError) bestError = error, best = f;
    }
  return best;
}

double sheetGapOfViewCone(const LenticularDesign& d) {
  return d.horizontalLensPitchMm /
         (2 * std::tan(d.calibration.viewConeDegrees * std::numbers::pi / 360));
}

PhaseField fieldOfSheet(const LensSheet& sheet, bool invView, double D) {
  const double s = invView ? 1.0 : -1.0;
  const double slant = sheet.slantDegrees * std::numbers::pi / 180;
  const double pD = sheet.pitchMm * (D + sheet.gapMm) / D;
  PhaseField f{s * std::cos(slant) / pD, -s * std::sin(slant) / pD,
               0.5 - s * sheet.phaseMm / sheet.pitchMm};
  f.r0 -= std::floor(f.r0);
  return f;
}

LenticularCalibration calibrationWithField(const LenticularCalibration& nominal,
                                           const PhaseField& target, double D) {
  const LenticularDesign n = designLenticular(nominal, D);
  // pitch_px = |gx| width, tilt = |gy| height / pitch_px with the sign that the design then
  // confirms; slope = screenH / (screenW tilt); pitch from pitch_px as the design derives it,
  // pitch_px = pitch (screenW / DPI) cos(atan(1 / slope)).
  const double pitchPx = std::abs(target.gx) * n.widthMm;
  const double tiltMagnitude = std::abs(target.gy) * n.heightMm / pitchPx;
  LenticularCalibration best = nominal;
  double bestError = 1e9;
  for (int sign = -1; sign <= 1; sign += 2) {
    LenticularCalibration c = nominal;
    const double tilt = sign * tiltMagnitude;
    if (tilt == 0) continue;
    c.slope = double(c.screenH) / (double(c.screenW) * tilt);
    c.pitch = pitchPx / ((double(c.screenW) / c.dpi) * std::cos(std::atan(1 / c.slope)));
    c.center = nominal.center;
    const PhaseField f = phaseFieldOf(designLenticular(c, D));
    const double error = std::abs(f.gx - target.gx) + std::abs(f.gy - target.gy);
    if (error < bestError) {
      bestError = error;
      // r = ... - center: moving center by dc moves r0 by -dc.
      c.center = nominal.center + wrapHalf(f.r0 - target.r0 + (c.center - nominal.center));
      best = c;
    }
  }
  const PhaseField check = phaseFieldOf(designLenticular(best, D));
  if (!(std::abs(check.gx - target.gx) + std::abs(check.gy - target.gy) <
            1e-9 * std::abs(target.gx) + 1e-12 &&
        std::abs(wrapHalf(check.r0 - target.r0)) < 1e-6))
    throw InputError(nominal.source, "",
                     "no pitch, slope and center give the measured lens sheet (a flipped panel?)");
  return best;
}

}  // namespace parallax::photocal
