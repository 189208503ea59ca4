#include "parallax/camera/lenticular_camera.h"

#include <cmath>

#include "parallax/camera/display_camera.h"

namespace parallax {

LenticularCamera::LenticularCamera(const LenticularDesign& design,
                                   const DisplayPlacement& placement, const ViewFilter& filter)
    : design_(design),
      worldFromDisplay_(worldFromDisplay(placement, displayWindow(design))),
      filterKind_(filter.kind),
      warp_(filter) {}

Ray LenticularCamera::generateRay(const FilmSample& s) const {
  const int column = int(std::floor(s.x));
  const int x = column / 3, channel = channelOfColumn(column);
  const double rowCentre = std::floor(s.y) + 0.5;
  // The subpixel's own view: the published formula at its pixel's centre.
  const double ownView = viewFractionAt(design_, x + 0.5, rowCentre, channel);
  LenticularRay r;
  if (filterKind_ == ViewFilterKind::None) {
    r = lenticularRay(design_, x + 0.5, rowCentre, channel, ownView);  // the central ray
  } else {
    // A subpixel is a third of a pixel wide: spread the column's samples over that third.
    const double filmX = x + 0.5 + (s.x - column - 0.5) / 3.0;
    // Period: anywhere in the lens's cone (the old cell's analogue, for comparison); the
    // others: the filter's offset in channel view steps around the subpixel's own view.
    const double view = filterKind_ == ViewFilterKind::Period
                            ? ownView + (s.apertureU - 0.5)
                            : ownView + warp_(s.apertureU) * channelViewStep(design_);
    r = lenticularRay(design_, filmX, s.y, channel, view);
  }
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
