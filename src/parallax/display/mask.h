// The barrier on the mask layer: where its apertures are, and its raster image. Positions are
// in display millimetres with the mask panel centred on the z axis; aperture 0 sits at
// DisplayDesign::apertureOriginMm plus the phase.
#pragma once

#include <cstdint>
#include <vector>

#include "parallax/display/display.h"

namespace parallax {

class MaskGeometry {
 public:
  explicit MaskGeometry(const DisplayDesign& design);

  // Centre x of slit (or pinhole column) k at height y on the mask layer. Slanted, wiggling
  // and jittered masks move it with y or with k (the paper's section 4.3).
  double apertureCenterX(int64_t k, double yMm) const;
  // The slit whose centre is nearest to x at height y.
  int64_t nearestAperture(double xMm, double yMm) const;
  // Pinholes: centre y of row j, and the row nearest y. Slits: a single row at y.
  double rowCenterY(int64_t j) const;
  int64_t nearestRow(double yMm) const;
  bool isPinholeGrid() const { return kind_ == MaskKind::Pinholes; }

  double periodMm() const { return period_; }
  double verticalPeriodMm() const { return verticalPeriod_; }
  double apertureWidthMm() const { return apertureWidth_; }
  double apertureHeightMm() const { return apertureHeight_; }

  // Each mask pixel's open fraction by area (row-major, row 0 at the top, values in [0, 1]):
  // anti-aliased as the paper's section 3.1 does for fractional slit periods.
  std::vector<float> rasterize() const;

 private:
  double xOverlap(double a, double b, double y) const;  // open length of [a, b] at height y

  MaskKind kind_;
  double drawOffsetMm_ = 0;  // MaskSpec::panelOffsetPx: moves the raster only
  double period_, inversePeriod_ = 0, verticalPeriod_, apertureWidth_, apertureHeight_, phaseMm_;
  double slope_, wiggleAmplitude_, wiggleWavenumber_, jitter_;
  uint64_t seed_;
  int width_, height_;
  double pitch_;
};

}  // namespace parallax
