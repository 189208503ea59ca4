#include "parallax/display/mask.h"

#include <algorithm>
#include <cmath>

#include "parallax/core/random.h"

namespace parallax {

MaskGeometry::MaskGeometry(const DisplayDesign& design)
    : kind_(design.spec.mask.kind),
      period_(design.slitPeriodMm),
      verticalPeriod_(0.0),
      apertureWidth_(0.0),
      apertureHeight_(0.0),
      phaseMm_(design.apertureOriginMm + design.spec.mask.phasePx * design.spec.maskPanel.pitchMm),
      slope_(0.0),
      wiggleAmplitude_(0.0),
      wiggleWavenumber_(0.0),
      jitter_(0.0),
      seed_(design.spec.mask.jitterSeed),
      width_(design.spec.maskPanel.width),
      height_(design.spec.maskPanel.height),
      pitch_(design.spec.maskPanel.pitchMm) {
  const MaskSpec& m = design.spec.mask;
  // The duty cycle is the open fraction of the area for every mask: slits are duty * Tv wide;
  // square-ish pinholes take sqrt(duty) of each period.
  if (kind_ == MaskKind::Pinholes) {
    verticalPeriod_ = m.verticalPeriodPx * pitch_;
    apertureWidth_ = std::sqrt(m.dutyCycle) * period_;
    apertureHeight_ = std::sqrt(m.dutyCycle) * verticalPeriod_;
  } else {
    apertureWidth_ = m.dutyCycle * period_;
  }
  if (kind_ == MaskKind::Slanted) slope_ = std::tan(m.slantDegrees * 3.14159265358979 / 180.0);
  if (kind_ == MaskKind::Wiggling) {
    wiggleAmplitude_ = m.wiggleAmplitudeMm;
    wiggleWavenumber_ = 2.0 * 3.14159265358979 / m.wiggleWavelengthMm;
  }
  if (kind_ == MaskKind::Jittered) jitter_ = m.jitterAmplitude * period_;
  inversePeriod_ = 1.0 / period_;
  drawOffsetMm_ = m.panelOffsetPx * pitch_;
}

double MaskGeometry::apertureCenterX(int64_t k, double y) const {
  double x = double(k) * period_ + phaseMm_;
  switch (kind_) {
    case MaskKind::Slanted:
      x += slope_ * y;
      break;
    case MaskKind::Wiggling:
      x += wiggleAmplitude_ * std::sin(wiggleWavenumber_ * y);
      break;
    case MaskKind::Jittered: {
      // A fixed random offset per slit in [-jitter, jitter), from the slit index and seed.
      Rng rng(mix64(uint64_t(k) ^ mix64(seed_)));
      x += jitter_ * (2.0 * double(rng.uniform()) - 1.0);
      break;
    }
    default:
      break;
  }
  return x;
}

int64_t MaskGeometry::nearestAperture(double x, double y) const {
  const double base = kind_ == MaskKind::Jittered ? phaseMm_ : apertureCenterX(0, y);
  int64_t k = int64_t(std::llround((x - base) * inversePeriod_));
  if (kind_ != MaskKind::Jittered) return k;
  // Jittered slits move by less than half a period: the nearest is among k - 1 .. k + 1.
  int64_t best = k;
  double bestDistance = std::abs(x - apertureCenterX(k, y));
  for (int64_t c : {k - 1, k + 1}) {
    const double distance = std::abs(x - apertureCenterX(c, y));
    if (distance < bestDistance) best = c, bestDistance = distance;
  }
  return best;
}

double MaskGeometry::rowCenterY(int64_t j) const {
  return kind_ == MaskKind::Pinholes ? double(j) * verticalPeriod_ : 0.0;
}

int64_t MaskGeometry::nearestRow(double y) const {
  return kind_ == MaskKind::Pinholes ? int64_t(std::llround(y / verticalPeriod_)) : 0;
}

double MaskGeometry::xOverlap(double a, double b, double y) const {
  // The raster is drawn shifted by the panel offset: pixel [a, b] covers [a, b] - offset of
  // the aperture pattern.
  a -= drawOffsetMm_, b -= drawOffsetMm_;
  const double half = 0.5 * apertureWidth_;
  double open = 0.0;
  for (int64_t k = nearestAperture(a, y) - 1, last = nearestAperture(b, y) + 1; k <= last; ++k) {
    const double c = apertureCenterX(k, y);
    open += std::max(0.0, std::min(b, c + half) - std::max(a, c - half));
  }
  return open;
}

std::vector<float> MaskGeometry::rasterize() const {
  std::vector<float> coverage(size_t(width_) * size_t(height_));
  const double left = -0.5 * width_ * pitch_, top = 0.5 * height_ * pitch_;
  // Masks whose slits bend with y are integrated over sub-rows; the others are separable.
  const bool bends = kind_ == MaskKind::Slanted || kind_ == MaskKind::Wiggling;
  const int subRows = bends ? 16 : 1;
  std::vector<float> row(static_cast<size_t>(width_));
  for (int py = 0; py < height_; ++py) {
    const double y0 = top - (py + 1) * pitch_, y1 = top - py * pitch_;
    if (py == 0 || bends) {
      for (int px = 0; px < width_; ++px) {
        const double a = left + px * pitch_, b = a + pitch_;
        double open = 0.0;
        for (int s = 0; s < subRows; ++s) open += xOverlap(a, b, y0 + (s + 0.5) * pitch_ / subRows);
        row[size_t(px)] = float(open / (subRows * pitch_));
      }
    }
    double yCoverage = 1.0;
    if (kind_ == MaskKind::Pinholes) {
      yCoverage = 0.0;
      const double half = 0.5 * apertureHeight_;
      for (int64_t j = nearestRow(y0) - 1; j <= nearestRow(y1) + 1; ++j) {
        const double c = rowCenterY(j);
        yCoverage += std::max(0.0, std::min(y1, c + half) - std::max(y0, c - half));
      }
      yCoverage /= pitch_;
    }
    for (int px = 0; px < width_; ++px)
      coverage[size_t(py) * size_t(width_) + size_t(px)] = float(row[size_t(px)] * yCoverage);
  }
  return coverage;
}

}  // namespace parallax
