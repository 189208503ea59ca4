// Depth of field and depth compression for displays whose depth budget is not a barrier's
// virtual gap: a slanted lenticular panel (docs/lenticular.md, "Depth of field").
#pragma once

#include <memory>

#include "parallax/display/display_model.h"
#include "parallax/display/lenticular.h"

namespace parallax {

// The depth criterion: a point's image may spread, through the lens's angular window, over this
// many lenses before it counts as blurred (the G4 criterion of barriers: the angular blur's
// footprint equals the spatial sample, docs/lenticular.md "Depth of field").
inline constexpr double kSharpLenses = 1.0;

// The lens's angular window, in subpixels along a row: the width at half height of what one eye
// integrates through a lens (lensSpotWeight: a subpixel's box convolved with the focal spot's box
// of W subpixels, a trapezoid max(1, W) subpixels wide at half height). An ideal lens (W = 0) or
// the default spot of one subpixel shows the eye one subpixel's width of view fraction.
double lensWindowSubpixels(const LensOptics& optics);

// The depth (mm either side of the panel) at which a point's image, seen through the lens's
// angular window of w = lensWindowSubpixels(design.optics) subpixels, spreads over `lenses`
// horizontal lens pitches:
//   |z| = lenses * p_h * S / (w * 2 tan(viewCone / 2))
// with p_h the lens pitch along a row and S the subpixels per lens: the lens maps a panel
// offset u under it to the direction tan(theta) = u / F with p_h / F = 2 tan(viewCone / 2), so
// a window of w subpixels spans w (p_h / S) / F in tan(theta), which spreads over |z| times that
// at depth z.
double lensDepthOfFieldMm(const LenticularDesign& design, double lenses = kSharpLenses);

// The display with its camera's rays turned toward the panel's normal by `depthScale` k in
// (0, 1]: each ray keeps its panel point and its vertical slope, and its horizontal slope is
// multiplied by k. An eye at (x, y, z) then sees through the panel what the camera sees from
// (x, y, z / k), which shows a point at depth z at depth k z, its x and y kept: the lenticular
// depth budget's compression (the barrier's is its virtual gap). intendedEye says so; the
// optics (the simulator's, the interlacer's) stay the inner display's.
std::unique_ptr<DisplayModel> scaleDisplayedDepth(std::unique_ptr<DisplayModel> display,
                                                  double depthScale);
// The same viewing `display`, which must outlive it (k = 1 too: then every figure is display's).
std::unique_ptr<DisplayModel> depthScaledView(const DisplayModel& display, double depthScale);

}  // namespace parallax
