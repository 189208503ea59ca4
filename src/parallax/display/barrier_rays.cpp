#include "parallax/display/barrier_rays.h"

#include <algorithm>
#include <cmath>

namespace parallax {

BarrierRayGenerator::BarrierRayGenerator(const DisplayDesign& design)
    : design_(design),
      mask_(design),
      subpixels_(design.spec.subpixelRays),
      filmWidth_(design.spec.imagePanel.width * (subpixels_ ? 3 : 1)),
      zImage_(design.imageLayerZ()),
      zMask_(design.maskLayerZ()),
      eyeX_(design.spec.viewZoneCenterXMm),
      eyeY_(design.spec.viewZoneHeightMm),
      distance_(design.viewDistanceMm),
      virtualDistance_(design.virtualDistanceMm) {
  const bool imageInFront = design.spec.order == LayerOrder::BarrierBack;
  zImageVirtual_ = imageInFront ? 0.0 : -design.virtualGapMm;
  zMaskVirtual_ = imageInFront ? -design.virtualGapMm : 0.0;
  maskFromImage_ = (distance_ - zMask_) / (distance_ - zImage_);
  imageFromMask_ = 1.0 / maskFromImage_;
  inverseVirtualGap_ = 1.0 / (zMaskVirtual_ - zImageVirtual_);
  inverseViewDepth_ = 1.0 / (virtualDistance_ - zImageVirtual_);
  virtualMaskFromImage_ = std::isinf(virtualDistance_) ? 1.0
                                                       : (virtualDistance_ - zMaskVirtual_) /
                                                             (virtualDistance_ - zImageVirtual_);
}

int BarrierRayGenerator::channelOfColumn(int column) const {
  const int c = column % 3;
  return design_.spec.imagePanel.subpixels == SubpixelOrder::BGR ? 2 - c : c;
}

Vec3d BarrierRayGenerator::imagePoint(double filmX, double filmY) const {
  const Panel& p = design_.spec.imagePanel;
  const double columnWidth = p.pitchMm / (subpixels_ ? 3.0 : 1.0);
  return {-0.5 * p.widthMm() + filmX * columnWidth, 0.5 * p.heightMm() - filmY * p.pitchMm,
          zImage_};
}

int BarrierRayGenerator::viewIndex(int column, int row) const {
  const Vec3d centre = imagePoint(column + 0.5, row + 0.5);
  const double s = maskFromImage_;
  const double maskY = eyeY_ + (centre.y - eyeY_) * s;
  const int64_t k = mask_.nearestAperture(eyeX_ + (centre.x - eyeX_) * s, maskY);
  const double groupX = eyeX_ + (mask_.apertureCenterX(k, maskY) - eyeX_) * imageFromMask_;
  const double columnWidth = design_.spec.imagePanel.pitchMm / (subpixels_ ? 3.0 : 1.0);
  const double columnsPerGroup = design_.screenPeriodMm / columnWidth;
  // Offset from the group's left edge, in columns.
  const double offset = (centre.x - groupX) / columnWidth + 0.5 * columnsPerGroup;
  const int views = std::max(1, int(std::lround(columnsPerGroup)));
  return std::clamp(int(std::floor(offset)), 0, views - 1);
}

Vec3d BarrierRayGenerator::viewPosition(int view) const {
  const double columnWidth = design_.spec.imagePanel.pitchMm / (subpixels_ ? 3.0 : 1.0);
  const double columnsPerGroup = design_.screenPeriodMm / columnWidth;
  const double offset = (view + 0.5 - 0.5 * columnsPerGroup) * columnWidth;
  return {eyeX_ + offset * (zMask_ - distance_) / (zMask_ - zImage_), eyeY_, distance_};
}

void BarrierRayGenerator::rays16(const float filmX[16], const float filmY[16], const float u[16],
                                 const float v[16], double origin[3][16],
                                 double direction[3][16]) const {
  if (design_.spec.mask.kind != MaskKind::Slits || std::isinf(virtualDistance_)) {
    for (int i = 0; i < 16; ++i) {
      const BarrierRay r = ray(filmX[i], filmY[i], u[i], v[i]);
      origin[0][i] = r.origin.x, origin[1][i] = r.origin.y, origin[2][i] = r.origin.z;
      direction[0][i] = r.direction.x, direction[1][i] = r.direction.y;
      direction[2][i] = r.direction.z;
    }
    return;
  }
  // ray() for vertical slits and a finite D', written out lane-wise: the same steps 1-3.
  const Panel& p = design_.spec.imagePanel;
  const double columnWidth = p.pitchMm / (subpixels_ ? 3.0 : 1.0);
  const double left = -0.5 * p.widthMm(), top = 0.5 * p.heightMm();
  const double apertureBase = mask_.apertureCenterX(0, 0.0), period = mask_.periodMm();
  const double inversePeriod = 1.0 / period, s = maskFromImage_, sv = virtualMaskFromImage_;
  const double periodX = design_.screenPeriodMm * sv;
  const double originZ = virtualDistance_, t = originZ - zImageVirtual_;
  // Members and outputs as locals: nothing can alias, so the lane loop vectorises.
  const double eyeX = eyeX_, eyeY = eyeY_, imageFromMask = imageFromMask_;
  const double inverseGap = inverseVirtualGap_, inverseDepth = inverseViewDepth_;
  const double pitch = p.pitchMm;
  alignas(64) double fx[16], fy[16], fu[16], o[3][16], d[2][16];
  for (int i = 0; i < 16; ++i) fx[i] = filmX[i], fy[i] = filmY[i], fu[i] = u[i];
  for (int i = 0; i < 16; ++i) {
    const double centreX = left + (std::floor(fx[i]) + 0.5) * columnWidth;
    const double sampleX = left + fx[i] * columnWidth;
    const double sampleY = top - fy[i] * pitch;
    const double k = std::floor((eyeX + (centreX - eyeX) * s - apertureBase) * inversePeriod + 0.5);
    const double groupX = eyeX + (apertureBase + k * period - eyeX) * imageFromMask;
    const double apertureX = eyeX + (groupX - eyeX) * sv + (fu[i] - 0.5) * periodX;
    const double slopeX = (apertureX - sampleX) * inverseGap;
    const double slopeY = (eyeY - sampleY) * inverseDepth;
    o[0][i] = sampleX + slopeX * t;
    o[1][i] = sampleY + slopeY * t;
    d[0][i] = -slopeX, d[1][i] = -slopeY;
  }
  for (int i = 0; i < 16; ++i) {
    origin[0][i] = o[0][i], origin[1][i] = o[1][i], origin[2][i] = originZ;
    direction[0][i] = d[0][i], direction[1][i] = d[1][i], direction[2][i] = -1.0;
  }
  (void)v;
}

BarrierRay BarrierRayGenerator::ray(double filmX, double filmY, double u, double v) const {
  BarrierRay r;
  // 1. Association, at the pixel's centre: the aperture nearest to the line from the
  //    view-zone centre through the pixel, where that line crosses the mask.
  const Vec3d centre = imagePoint(std::floor(filmX) + 0.5, std::floor(filmY) + 0.5);
  const Vec3d sample = imagePoint(filmX, filmY);
  const double s = maskFromImage_;
  const double centreMaskY = eyeY_ + (centre.y - eyeY_) * s;
  r.aperture = mask_.nearestAperture(eyeX_ + (centre.x - eyeX_) * s, centreMaskY);
  r.apertureRow = mask_.nearestRow(centreMaskY);
  // 2. The group centre: that aperture, at the sample's height on the mask (slanted and
  //    wiggling slits move with y), projected back onto the image layer.
  const double maskY = eyeY_ + (sample.y - eyeY_) * s;
  const double groupX = eyeX_ + (mask_.apertureCenterX(r.aperture, maskY) - eyeX_) * imageFromMask_;
  const double groupY = eyeY_ + (mask_.rowCenterY(r.apertureRow) - eyeY_) * imageFromMask_;
  // 3. The virtual aperture (section 2.3): the group centre projected toward the virtual
  //    view-zone centre onto the virtual mask plane, v'_k = e_c + (c_k - e_c) D'/(D' + g')
  //    for barrier-back, and jittered across one virtual aperture period.
  const double sv = virtualMaskFromImage_;
  const double periodX = design_.screenPeriodMm * sv;
  const double apertureX = eyeX_ + (groupX - eyeX_) * sv + (u - 0.5) * periodX;
  const double dz = zMaskVirtual_ - zImageVirtual_;
  const double slopeX = (apertureX - sample.x) * inverseVirtualGap_;
  double slopeY = 0.0;
  if (mask_.isPinholeGrid()) {
    const double periodY = mask_.verticalPeriodMm() * imageFromMask_ * sv;
    const double apertureY = eyeY_ + (groupY - eyeY_) * sv + (v - 0.5) * periodY;
    slopeY = (apertureY - sample.y) * inverseVirtualGap_;
  } else if (!std::isinf(virtualDistance_)) {
    // One-axis perspective: every ray meets the view line y = y_e at z = D' (section 2.2).
    slopeY = (eyeY_ - sample.y) * inverseViewDepth_;
  }
  r.imagePoint = {sample.x, sample.y, zImageVirtual_};
  r.aperturePoint = {sample.x + slopeX * dz, sample.y + slopeY * dz, zMaskVirtual_};
  const double originZ = std::isinf(virtualDistance_) ? distance_ : virtualDistance_;
  const double t = originZ - zImageVirtual_;
  r.origin = {sample.x + slopeX * t, sample.y + slopeY * t, originZ};
  r.direction = {-slopeX, -slopeY, -1.0};
  return r;
}

}  // namespace parallax
