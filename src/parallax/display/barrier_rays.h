// The display camera's geometry in display millimetres (docs/display-geometry.md, "The ray of
// one pair"): which aperture serves an image-layer sample, and the ray through both.
#pragma once

#include <cstdint>
#include <vector>

#include "parallax/core/math.h"
#include "parallax/display/display.h"
#include "parallax/display/mask.h"
#include "parallax/display/view_filter.h"

namespace parallax {

struct BarrierRay {
  Vec3d origin;             // on the viewer's side: at z = D' (or z = D when D' is infinite)
  Vec3d direction;          // toward the display, normalised to direction.z = -1
  Vec3d imagePoint;         // where the ray crosses the (virtual) image layer
  Vec3d aperturePoint;      // where it crosses the (virtual) mask layer
  int64_t aperture = 0;     // index of the serving aperture (column)
  int64_t apertureRow = 0;  // pinhole row (0 for slits)
};

class BarrierRayGenerator {
 public:
  // `filter`: how a pixel's sub-rays spread in angle (view_filter.h); a render setting, not
  // part of the display.
  explicit BarrierRayGenerator(const DisplayDesign& design, const ViewFilter& filter = {});

  // Film columns: the image layer's pixels, or three per pixel in subpixel mode.
  int filmWidth() const { return filmWidth_; }
  int filmHeight() const { return design_.spec.imagePanel.height; }
  bool subpixelMode() const { return subpixels_; }
  // Colour channel (0 R, 1 G, 2 B) that film column `column` carries in subpixel mode.
  int channelOfColumn(int column) const;

  // The ray for a sample at film position (x, y) (continuous film pixels, y down) and angular
  // sample (u, v) in [0, 1)^2. The pixel is assigned to an aperture by projecting apertures
  // from the view-zone centre onto the image layer, using the centre of the film column (so
  // every sample of a pixel uses the same aperture). u, v = 0.5 is the pixel's central ray
  // (through the aperture's centre line); u, v spread the ray over the filter's angular
  // window around it (docs/display-geometry.md, "Super-sampling"): with the filter's offset
  // f(u) in views, the ray crosses the virtual mask at
  //   x_M = a_c + s' ((x - x_c) + f(u) dx),   s' = (D' - z_M') / (D' - z_I')  (1 for D' = inf)
  // with a_c the aperture centre, x_c the pixel centre and dx the film column's width: the
  // line from the sample point to an eye f(u) view widths from the central ray's eye at D'.
  // The Period filter keeps the old cell instead: x_M = a_c + (u - 0.5) T' (a whole period).
  BarrierRay ray(double filmX, double filmY, double u, double v) const;

  // The view a film column serves: its place in its group, 0 .. round(views) - 1 counted in
  // the direction of increasing x on the image layer (3x the views in subpixel mode).
  int viewIndex(int column, int row) const;

  // The design eye position of a view: where the central rays of all its columns meet, on the
  // view line at z = D: x = e_c + delta (z_M - D) / (z_M - z_I), with delta the column's offset
  // from its group centre (docs/display-geometry.md).
  Vec3d viewPosition(int view) const;

  // Sixteen rays at once, origins and directions only (the render loop's packets). Vertical
  // slits, the common case, run as branch-free lane loops; other masks call ray() per lane.
  void rays16(const float filmX[16], const float filmY[16], const float u[16], const float v[16],
              double origin[3][16], double direction[3][16]) const;

  // The image-layer point (mm) of a film position.
  Vec3d imagePoint(double filmX, double filmY) const;

  const DisplayDesign& design() const { return design_; }
  const MaskGeometry& mask() const { return mask_; }
  const ViewFilter& filter() const { return filter_; }

 private:
  DisplayDesign design_;
  MaskGeometry mask_;
  ViewFilter filter_;
  ViewFilterWarp warp_;
  bool subpixels_;
  int filmWidth_;
  double zImage_, zMask_;                // physical layers
  double zImageVirtual_, zMaskVirtual_;  // the camera's layers (g')
  double eyeX_, eyeY_, distance_, virtualDistance_;
  double maskFromImage_;         // (D - zM) / (D - zI): projection scale from the eye
  double virtualMaskFromImage_;  // the same with g', D' (1 for D' infinite)
  double imageFromMask_;         // 1 / maskFromImage_
  double inverseVirtualGap_;     // 1 / (zM' - zI'), signed
  double inverseViewDepth_;      // 1 / (D' - zI'), 0 for D' infinite
  // Vertical slits: the left edge (u = 0) of each film column's virtual aperture cell, x in mm.
  std::vector<double> apertureCellLeft_;

  // The film sample actually traced: the pixel centre for the None filter.
  void snapToCentre(double& filmX, double& filmY, double& u, double& v) const;

  // Which aperture serves a film sample, and where its group and virtual aperture cell lie.
  struct Association {
    int64_t aperture = 0, apertureRow = 0;
    double groupX = 0, groupY = 0;  // group centre on the image layer (mm)
    double cellLeftX = 0;           // left edge of the virtual aperture cell (u = 0), mm
  };
  Association associate(double filmX, double filmY) const;
};

// The display's own rays, for what measures or plots a barrier's ray space itself (the
// light-field plot, sim/lightfield.h): the design's subpixel choice kept, its camera's virtual
// gap and distance (section 2.3) replaced by the physical g and D, so that a ray's aperturePoint
// is where it really crosses the mask. The display camera and everything that asks for views
// use the display model instead (display_model.h, makeBarrierDisplay).
BarrierRayGenerator physicalBarrierRays(const DisplayDesign& design, const ViewFilter& filter = {});

}  // namespace parallax
