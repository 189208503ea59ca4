#include "parallax/camera/lenticular_camera.h"

#include <cmath>

#include "parallax/camera/display_camera.h"

namespace parallax {

LenticularCamera::LenticularCamera(const LenticularDesign& design,
                                   const DisplayPlacement& placement)
    : design_(design), worldFromDisplay_(worldFromDisplay(placement, displayWindow(design))) {}

Ray LenticularCamera::generateRay(const FilmSample& s) const {
  const int column = int(std::floor(s.x));
  const int x = column / 3, channel = channelOfColumn(column);
  // A subpixel is a third of a pixel wide: spread the column's samples over that third.
  const double filmX = x + 0.5 + (s.x - column - 0.5) / 3.0;
  const LenticularRay r = lenticularRay(design_, filmX, s.y, channel);
  const Vec3f origin{float(r.origin.x), float(r.origin.y), float(r.origin.z)};
  const Vec3f direction{float(r.direction.x), float(r.direction.y), float(r.direction.z)};
  return {worldFromDisplay_.point(origin), worldFromDisplay_.vector(direction)};
}

DisplayWindow displayWindow(const LenticularDesign& design) {
  return {design.widthMm, design.heightMm, {0, 0, design.viewDistanceMm}};
}

DisplayDesign lenticularWindowDesign(const LenticularDesign& d) {
  DisplayDesign window;
  Panel panel;
  panel.width = d.calibration.screenW;
  panel.height = d.calibration.screenH;
  panel.pitchMm = d.pixelPitchMm;
  window.spec.imagePanel = window.spec.maskPanel = panel;
  window.spec.source = d.calibration.source;
  window.spec.viewDistanceMm = d.viewDistanceMm;
  window.spec.viewZoneHeightMm = 0.0;  // the eye line of lenticularRay
  window.viewDistanceMm = d.viewDistanceMm;
  window.viewZoneWidthMm = d.viewZoneWidthMm;
  return window;
}

}  // namespace parallax
