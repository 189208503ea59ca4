// The camera of a slanted lenticular display: one exact ray per subpixel, in the direction its
// view fraction gives (display/lenticular.h, docs/lenticular.md).
#pragma once

#include "parallax/camera/camera.h"
#include "parallax/camera/display_camera.h"
#include "parallax/core/transform.h"
#include "parallax/display/display.h"
#include "parallax/display/lenticular.h"
#include "parallax/display/view_filter.h"
#include "parallax/scene/scene.h"

namespace parallax {

// The film has one column per subpixel: column 3x + c is channel c (0 R, 1 G, 2 B) of panel
// column x, wherever the calibration puts that subpixel. A film sample's position inside its
// column moves the ray's panel point across the subpixel's area; its aperture sample spreads the
// ray's view around the subpixel's own (the formula at the pixel's centre) by the filter, whose
// width is in the channel's view steps (channelViewStep: one pixel's worth of view fraction, the
// spacing at which the panel samples each channel's views, docs/lenticular.md "Prefilter").
// The column's centre casts exactly the published formula's ray.
class LenticularCamera final : public Camera {
 public:
  // The panel is the display's front layer: its width in mm (from DPI) maps onto
  // placement.width scene units (worldFromDisplay).
  LenticularCamera(const LenticularDesign& design, const DisplayPlacement& placement,
                   const ViewFilter& filter = {});

  int width() const override { return 3 * design_.calibration.screenW; }
  int height() const override { return design_.calibration.screenH; }
  Ray generateRay(const FilmSample& sample) const override;
  static int channelOfColumn(int column) { return column % 3; }

 private:
  LenticularDesign design_;
  Transform worldFromDisplay_;
  ViewFilterKind filterKind_;
  ViewFilterWarp warp_;  // offsets in view steps
};

// The lenticular panel's window, framed for the design viewer straight in front of it.
DisplayWindow displayWindow(const LenticularDesign& design);

// A stand-in two-layer design with the lenticular panel's size and the design viewer's distance
// and eye line, for WindowCamera: the ideal view through the panel's window from one eye.
DisplayDesign lenticularWindowDesign(const LenticularDesign& design);

}  // namespace parallax
