#include "parallax/display/barrier_rays.h"

#include "parallax/core/lane_kernel.h"

#include <algorithm>
#include <cmath>

namespace parallax {

BarrierRayGenerator::BarrierRayGenerator(const DisplayDesign& design, const ViewFilter& filter)
    : design_(design),
      mask_(design),
      filter_(filter),
      warp_(filter),
      subpixels_(design.camera.subpixelRays),
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
  // Vertical slits serve a film column through the same aperture at every height.
  if (design.spec.mask.kind == MaskKind::Slits) {
    apertureCellLeft_.resize(size_t(filmWidth_));
    for (int column = 0; column < filmWidth_; ++column)
      apertureCellLeft_[size_t(column)] = associate(column + 0.5, 0.5).cellLeftX;
  }
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

PARALLAX_LANE_KERNEL void BarrierRayGenerator::rays16(const float filmX[16], const float filmY[16],
                                                      const float u[16], const float v[16],
                                                      double origin[3][16],
                                                      double direction[3][16]) const {
  if (design_.spec.mask.kind != MaskKind::Slits || std::isinf(virtualDistance_) ||
      filter_.kind == ViewFilterKind::None) {
    for (int i = 0; i < 16; ++i) {
      const BarrierRay r = ray(filmX[i], filmY[i], u[i], v[i]);
      origin[0][i] = r.origin.x, origin[1][i] = r.origin.y, origin[2][i] = r.origin.z;
      direction[0][i] = r.direction.x, direction[1][i] = r.direction.y;
      direction[2][i] = r.direction.z;
    }
    return;
  }
  // ray() for vertical slits and a finite D', written out lane-wise, with the association
  // (which depends on the film column only) read from the column table.
  const Panel& p = design_.spec.imagePanel;
  const double columnWidth = p.pitchMm / (subpixels_ ? 3.0 : 1.0);
  const double left = -0.5 * p.widthMm(), top = 0.5 * p.heightMm();
  const double periodX = design_.screenPeriodMm * virtualMaskFromImage_;
  const double originZ = virtualDistance_, t = originZ - zImageVirtual_;
  // Members and outputs as locals: nothing can alias, so the lane loops vectorise.
  const double eyeY = eyeY_, inverseGap = inverseVirtualGap_, inverseDepth = inverseViewDepth_;
  const double pitch = p.pitchMm;
  const int lastColumn = filmWidth_ - 1;
  const double* cells = apertureCellLeft_.data();
  alignas(64) double fx[16], fy[16], fu[16], cell[16], o[3][16], d[2][16];
  alignas(64) int column[16];
  for (int i = 0; i < 16; ++i) {
    fx[i] = filmX[i], fy[i] = filmY[i];
    column[i] = std::min(std::max(int(filmX[i]), 0), lastColumn);  // film x >= 0: floor
  }
  // The aperture offset of each lane, relative to the cell's left edge (Period) or to the
  // aperture centre plus the sample's offset from its pixel centre (the view filters).
  const bool period = filter_.kind == ViewFilterKind::Period;
  const double sv = virtualMaskFromImage_;
  for (int i = 0; i < 16; ++i)
    fu[i] = period ? u[i] * periodX
                   : 0.5 * periodX + sv * ((fx[i] - column[i] - 0.5) + warp_(u[i])) * columnWidth;
  // The render loop's packets are one film column (a broadcast); a gather is slow here.
  bool oneColumn = true;
  for (int i = 1; i < 16; ++i) oneColumn &= column[i] == column[0];
  if (oneColumn) {
    for (int i = 0; i < 16; ++i) cell[i] = cells[column[0]];
  } else {
    for (int i = 0; i < 16; ++i) cell[i] = cells[column[i]];
  }
  for (int i = 0; i < 16; ++i) {
    const double sampleX = left + fx[i] * columnWidth;
    const double sampleY = top - fy[i] * pitch;
    const double apertureX = cell[i] + fu[i];
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

BarrierRayGenerator physicalBarrierRays(const DisplayDesign& design, const ViewFilter& filter) {
  BarrierCameraSettings physical;
  physical.subpixelRays = design.camera.subpixelRays;
  return BarrierRayGenerator(designDisplay(design.spec, physical), filter);
}

BarrierRayGenerator::Association BarrierRayGenerator::associate(double filmX, double filmY) const {
  Association a;
  // 1. Association, at the pixel's centre: the aperture nearest to the line from the
  //    view-zone centre through the pixel, where that line crosses the mask.
  const Vec3d centre = imagePoint(std::floor(filmX) + 0.5, std::floor(filmY) + 0.5);
  const double s = maskFromImage_;
  const double centreMaskY = eyeY_ + (centre.y - eyeY_) * s;
  a.aperture = mask_.nearestAperture(eyeX_ + (centre.x - eyeX_) * s, centreMaskY);
  a.apertureRow = mask_.nearestRow(centreMaskY);
  // 2. The group centre: that aperture, at the sample's height on the mask (slanted and
  //    wiggling slits move with y), projected back onto the image layer.
  const double maskY = eyeY_ + (imagePoint(filmX, filmY).y - eyeY_) * s;
  a.groupX = eyeX_ + (mask_.apertureCenterX(a.aperture, maskY) - eyeX_) * imageFromMask_;
  a.groupY = eyeY_ + (mask_.rowCenterY(a.apertureRow) - eyeY_) * imageFromMask_;
  // 3. The virtual aperture cell (section 2.3): the group centre projected toward the virtual
  //    view-zone centre onto the virtual mask plane, v'_k = e_c + (c_k - e_c) D'/(D' + g')
  //    for barrier-back; the cell spans one virtual aperture period around it.
  const double sv = virtualMaskFromImage_;
  a.cellLeftX = eyeX_ + (a.groupX - eyeX_) * sv - 0.5 * design_.screenPeriodMm * sv;
  return a;
}

void BarrierRayGenerator::snapToCentre(double& filmX, double& filmY, double& u, double& v) const {
  if (filter_.kind != ViewFilterKind::None) return;
  filmX = std::floor(filmX) + 0.5, filmY = std::floor(filmY) + 0.5;
  u = v = 0.5;
}

BarrierRay BarrierRayGenerator::ray(double filmX, double filmY, double u, double v) const {
  snapToCentre(filmX, filmY, u, v);
  BarrierRay r;
  const Association a = associate(filmX, filmY);
  r.aperture = a.aperture;
  r.apertureRow = a.apertureRow;
  const Vec3d sample = imagePoint(filmX, filmY);
  const Vec3d pixelCentre = imagePoint(std::floor(filmX) + 0.5, std::floor(filmY) + 0.5);
  const double sv = virtualMaskFromImage_;
  const bool period = filter_.kind == ViewFilterKind::Period;
  // Where the sample's ray crosses the virtual mask (the equation in barrier_rays.h).
  const double periodX = design_.screenPeriodMm * sv;
  const double columnWidth = design_.spec.imagePanel.pitchMm / (subpixels_ ? 3.0 : 1.0);
  const double apertureX = period ? a.cellLeftX + u * periodX
                                  : a.cellLeftX + 0.5 * periodX +
                                        sv * ((sample.x - pixelCentre.x) + warp_(u) * columnWidth);
  const double dz = zMaskVirtual_ - zImageVirtual_;
  const double slopeX = (apertureX - sample.x) * inverseVirtualGap_;
  double slopeY = 0.0;
  if (mask_.isPinholeGrid()) {
    // Pinholes select a view in y too: the same rule down the columns, with the pixel pitch
    // as one vertical view.
    const double periodY = mask_.verticalPeriodMm() * imageFromMask_ * sv;
    const double centreY = eyeY_ + (a.groupY - eyeY_) * sv;
    const double apertureY = period ? centreY + (v - 0.5) * periodY
                                    : centreY + sv * ((sample.y - pixelCentre.y) +
                                                      warp_(v) * design_.spec.imagePanel.pitchMm);
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
