#include "parallax/display/lenticular.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "parallax/core/error.h"

namespace parallax {

namespace {

constexpr double kMmPerInch = 25.4;

std::string shortNumber(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

double radians(double degrees) {
  return degrees * kPiD / 180.0;
}

// The subpixel's offset from its pixel's reference point, in screen fractions (x right, y up),
// as the calibration describes it: stripes at slot / (3 W) (slot 2 - channel for BGR, the
// shaders' ri/bi swap), or the cell's offsets (pixels, over W and H). Pixel row `row` counts
// from the bottom, as the shaders' cell pattern does.
void subpixelOffset(const LenticularDesign& d, int column, int row, int channel, double& dx,
                    double& dy) {
  const LenticularCalibration& c = d.calibration;
  if (c.subpixelCells.empty()) {
    const int slot = c.flipSubpixels ? 2 - channel : channel;
    dx = slot / (3.0 * c.screenW);
    dy = 0;
    return;
  }
  const SubpixelCell& s = c.subpixelCells[size_t(cellIndex(c, column, row))];
  dx = s.offsetX[size_t(channel)] / c.screenW;
  dy = s.offsetY[size_t(channel)] / c.screenH;
}

// Framebuffer position to the shaders' screen coordinates: u right, v up, both in [0, 1].
void screenUv(const LenticularDesign& d, double filmX, double filmY, double& u, double& v) {
  u = filmX / d.calibration.screenW;
  v = 1.0 - filmY / d.calibration.screenH;
}

}  // namespace

int cellIndex(const LenticularCalibration& c, int x, int yUp) {
  if (c.subpixelCells.empty()) return 0;
  int cell = 0;
  switch (c.cellPatternMode) {
    case 1:
      cell = (x + yUp) & 1;
      break;
    case 2:
      cell = x & 1;
      break;
    case 3:
      cell = (yUp + 2 * (x & 1)) & 3;
      break;
    case 4:
      cell = yUp & 1;
      break;
    default:
      cell = 0;
  }
  return cell % int(c.subpixelCells.size());
}

bool parseLensBundles(const std::string& text, LensBundles& bundles) {
  for (const LensBundles b : {LensBundles::Parallel, LensBundles::Converging})
    if (text == lensBundlesName(b)) {
      bundles = b;
      return true;
    }
  return false;
}

const char* lensBundlesName(LensBundles bundles) {
  return bundles == LensBundles::Parallel ? "parallel" : "converging";
}

std::string lensOpticsProblem(const LensOptics& o) {
  if (!(o.spotWidthSubpixels >= 0 && o.spotWidthSubpixels <= kMaxLensSpotSubpixels))
    return "the focal spot must be from 0 to " + shortNumber(kMaxLensSpotSubpixels) +
           " subpixels wide (got " + shortNumber(o.spotWidthSubpixels) + ")";
  if (!(o.convergenceDistanceMm >= 0 && o.convergenceDistanceMm <= 1e6))
    return "the convergence distance must be from 0 (the view distance) to 1e6 mm (got " +
           shortNumber(o.convergenceDistanceMm) + ")";
  return "";
}

LenticularDesign withOptics(const LenticularDesign& design, LensOptics optics) {
  const std::string problem = lensOpticsProblem(optics);
  if (!problem.empty()) throw std::invalid_argument(problem);
  if (!(optics.convergenceDistanceMm > 0)) optics.convergenceDistanceMm = design.viewDistanceMm;
  LenticularDesign d = design;
  d.optics = optics;
  return d;
}

LenticularDesign designLenticular(const LenticularCalibration& c, double viewDistanceMm,
                                  const LensOptics& optics) {
  const auto fail = [&c](const char* key, const std::string& message) {
    return InputError(c.source, key, message);
  };
  if (!(c.pitch > 0)) throw fail("/pitch", "must be a positive number of lenses per inch");
  if (!(c.dpi > 0)) throw fail("/DPI", "must be positive");
  if (!std::isfinite(c.slope) || c.slope == 0)
    throw fail("/slope", "must not be 0 (the lenses would be horizontal)");
  if (!std::isfinite(c.center)) throw fail("/center", "must be a finite number");
  if (!(c.viewConeDegrees > 0 && c.viewConeDegrees < 180))
    throw fail("/viewCone", "must be between 0 and 180 degrees");
  if (c.screenW < 1 || c.screenH < 1) throw fail("/screenW", "the screen must have pixels");
  // Physically sensible ranges, so that no nonsense reaches the rays (lenticular.h).
  const auto range = [&fail](const char* key, double v, double lowest, double highest,
                             const char* unit) {
    if (!(v >= lowest && v <= highest))
      throw fail(key, "must be from " + shortNumber(lowest) + " to " + shortNumber(highest) + " " +
                          unit + " (got " + shortNumber(v) + ")");
  };
  range("/pitch", c.pitch, 0.1, 1e4, "lenses per inch");
  range("/DPI", c.dpi, 10, 1e5, "pixels per inch");
  range("/slope", std::fabs(c.slope), 1e-3, 1e4, "(absolute value)");
  range("/center", c.center, -1e6, 1e6, "");
  range("/viewCone", c.viewConeDegrees, 1, 179, "degrees");
  if (c.screenW > 65536 || c.screenH > 65536)
    throw fail("/screenW", "the screen must be at most 65536 pixels a side");
  for (size_t i = 0; i < c.subpixelCells.size(); ++i)
    for (size_t ch = 0; ch < 3; ++ch)
      for (const double v : {c.subpixelCells[i].offsetX[ch], c.subpixelCells[i].offsetY[ch]})
        if (!(std::fabs(v) <= 2))
          throw InputError(c.source, "/subpixelCells/" + std::to_string(i),
                           "subpixel offsets must be from -2 to 2 pixels");
  if (c.cellPatternMode < 0 || c.cellPatternMode >= kCellPatternModes)
    throw fail("/CellPatternMode", "expected a cell pattern from 0 to 4");

  LenticularDesign d;
  d.calibration = c;
  d.pixelPitchMm = kMmPerInch / c.dpi;
  d.widthMm = c.screenW * d.pixelPitchMm;
  d.heightMm = c.screenH * d.pixelPitchMm;
  // pitch is measured across the slanted lenses; along x a lens is 1 / cos(slant) wider.
  d.pitchPx = c.pitch * (c.screenW / c.dpi) * std::cos(std::atan(1.0 / c.slope));
  d.tilt = c.screenH / (double(c.screenW) * c.slope) * (c.flipImageX ? -1.0 : 1.0);
  d.lensSlantDegrees = std::atan(1.0 / std::fabs(c.slope)) * 180.0 / kPiD;
  d.lensPitchMm = kMmPerInch / c.pitch;
  d.horizontalLensPitchMm = d.widthMm / d.pitchPx;
  d.pixelsPerLens = c.screenW / d.pitchPx;
  d.subpixelsPerLens = 3.0 * d.pixelsPerLens;
  if (!(d.pixelsPerLens > 1))
    throw fail("/pitch", "the lenses are narrower than a pixel (" + std::to_string(d.pitchPx) +
                             " lenses across " + std::to_string(c.screenW) + " pixels)");
  d.lenticuleCount = d.pitchPx * (1.0 + std::fabs(d.tilt));
  const double halfCone = 0.5 * radians(c.viewConeDegrees);
  d.viewDistanceMm =
      viewDistanceMm > 0 ? viewDistanceMm : 0.5 * kLenticularZoneWidthMm / std::tan(halfCone);
  d.viewZoneWidthMm = 2.0 * d.viewDistanceMm * std::tan(halfCone);
  d.quiltViews = std::max(1, c.quilt.views());
  return withOptics(d, optics);
}

double viewFractionAt(const LenticularDesign& d, double filmX, double filmY, int channel) {
  const LenticularCalibration& c = d.calibration;
  double u, v, dx, dy;
  screenUv(d, filmX, filmY, u, v);
  subpixelOffset(d, int(std::floor(filmX)), c.screenH - 1 - int(std::floor(filmY)), channel, dx,
                 dy);
  // flipImageX mirrors u and reverses the subpixel step (tilt is already negated in the design),
  // as the HoloPlay SDK does: the formula then runs in the viewer's frame.
  if (c.flipImageX) u = 1.0 - u, dx = -dx;
  const double phase = (u + dx + (v + dy) * d.tilt) * d.pitchPx - c.center;
  double f = phase - std::floor(phase);
  if (c.invView) f = 1.0 - f;
  // Rounding can land on 1 (a phase just below an integer); view 1 is view 0 of the next lens.
  return f >= 1.0 ? f - 1.0 : f;
}

double viewFraction(const LenticularDesign& d, int x, int y, int channel) {
  return viewFractionAt(d, x + 0.5, y + 0.5, channel);
}

Vec3d subpixelPointMm(const LenticularDesign& d, double filmX, double filmY, int channel) {
  const LenticularCalibration& c = d.calibration;
  const int column = int(std::floor(filmX)), row = c.screenH - 1 - int(std::floor(filmY));
  double u, v, dx, dy, meanX = 0;
  screenUv(d, filmX, filmY, u, v);
  for (int k = 0; k < 3; ++k) {
    subpixelOffset(d, column, row, k, dx, dy);
    meanX += dx / 3.0;
  }
  subpixelOffset(d, column, row, channel, dx, dy);
  u += dx - meanX;
  v += dy;
  if (c.flipImageX) u = 1.0 - u;
  if (c.flipImageY) v = 1.0 - v;
  return {(u - 0.5) * d.widthMm, (v - 0.5) * d.heightMm, 0.0};
}

double viewAngle(const LenticularDesign& d, double fraction) {
  return (fraction - 0.5) * radians(d.calibration.viewConeDegrees);
}

double viewFractionOfAngle(const LenticularDesign& d, double angle) {
  return angle / radians(d.calibration.viewConeDegrees) + 0.5;
}

double lensSlope(const LenticularDesign& d, double panelX, double fraction) {
  const double t = std::tan(viewAngle(d, fraction));
  if (d.optics.bundles == LensBundles::Parallel) return t;
  const double C = d.optics.convergenceDistanceMm;
  return (C * t - panelX) / C;
}

double lensFractionSeen(const LenticularDesign& d, double panelX, const Vec3d& eye) {
  const double slope = (eye.x - panelX) / eye.z;
  if (d.optics.bundles == LensBundles::Parallel) return viewFractionOfAngle(d, std::atan(slope));
  const double C = d.optics.convergenceDistanceMm;
  return viewFractionOfAngle(d, std::atan((panelX + slope * C) / C));
}

double lensQuiltFraction(const LenticularDesign& d, double panelX, double fraction) {
  // Converging at D: the subpixel's light reaches the design line at view f's own camera.
  if (d.optics.bundles == LensBundles::Converging &&
      d.optics.convergenceDistanceMm == d.viewDistanceMm)
    return fraction;
  const double D = d.viewDistanceMm;
  return viewFractionOfAngle(d, std::atan((panelX + lensSlope(d, panelX, fraction) * D) / D));
}

Vec3d lensEyeOnDesignLine(const LenticularDesign& d, double t) {
  return {d.viewDistanceMm * std::tan(viewAngle(d, t)), 0.0, d.viewDistanceMm};
}

double subpixelViewWidth(const LenticularDesign& d) {
  return 1.0 / d.subpixelsPerLens;
}

double lensSpotHalfSupport(const LenticularDesign& d) {
  return 0.5 * (1.0 + d.optics.spotWidthSubpixels) * subpixelViewWidth(d);
}

double lensSpotWeight(const LenticularDesign& d, double low, double high) {
  const double spot = d.optics.spotWidthSubpixels * subpixelViewWidth(d);
  // An ideal lens: the (part of a) subpixel whose half-open span holds the eye's view, so that
  // of two neighbours exactly one is seen.
  if (!(spot > 0)) return low <= 0 && 0 < high ? 1.0 : 0.0;
  const double overlap = std::min(high, 0.5 * spot) - std::max(low, -0.5 * spot);
  return std::max(0.0, overlap) / spot;
}

double lensSpotWeight(const LenticularDesign& d, double difference) {
  const double half = 0.5 * subpixelViewWidth(d);
  return lensSpotWeight(d, difference - half, difference + half);
}

LenticularRay lenticularRay(const LenticularDesign& d, double filmX, double filmY, int channel) {
  return lenticularRay(d, filmX, filmY, channel, viewFractionAt(d, filmX, filmY, channel));
}

LenticularRay lenticularRay(const LenticularDesign& d, double filmX, double filmY, int channel,
                            double viewFraction) {
  LenticularRay r;
  r.viewFraction = viewFraction;
  r.panelPoint = subpixelPointMm(d, filmX, filmY, channel);
  const double D = d.viewDistanceMm;
  r.origin = {r.panelPoint.x + D * lensSlope(d, r.panelPoint.x, r.viewFraction), 0.0, D};
  r.direction = {(r.panelPoint.x - r.origin.x) / D, (r.panelPoint.y - r.origin.y) / D, -1.0};
  return r;
}

}  // namespace parallax
