// Cross-talk between views, measured the way the paper calibrates its prototype (section 3.1):
// light one view's pixels at a time and see how much of it reaches an eye.
#pragma once

#include <vector>

#include "parallax/sim/simulator.h"

namespace parallax {

// (pixelViewCount, the views per group in pixel mode, is display/display.h's.)

// The image layer with white (1) at the pixels serving `view` and black elsewhere. Pixel mode
// always (one view per pixel, the camera's subpixel rays ignored).
Image viewCodedImage(const DisplayDesign& design, int view);

// Where the rays of one view (pixel mode) meet: on the view line (y = y_e, z = D). A pixel of
// view v sits delta_v = (v + 1/2 - Tx/(2 dx)) dx from its group centre c_k, and its aperture
// is c_k projected from the view-zone centre e_c onto the mask layer. The line through both
// crosses z = D at
//
//     x = e_c - delta_v (D - z_M) / (z_M - z_I),
//
// the same for every group: e_c + delta_v (1 + D/g) for barrier-back (z_I = 0, z_M = -g) and
// e_c - delta_v D/g for barrier-front (z_I = -g, z_M = 0), where views run the other way.
Vec3d designEyePosition(const DisplayDesign& design, int view);

struct CrosstalkResult {
  int ownView = 0;                   // the view whose pixels send the eye the most light
  double crosstalk = 0;              // 1 - light[own] / sum(light)
  std::vector<double> lightPerView;  // mean luminance of the view with only that view lit
  double brightness = 0;             // sum(light): the view of an all-white image layer
};

// Simulates the eye's view once per view-coded image layer, with the given mask layer.
CrosstalkResult measureCrosstalk(const DisplayDesign& design, const Image& maskLayer,
                                 const SimulationOptions& options, const Vec3d& eye);

}  // namespace parallax
