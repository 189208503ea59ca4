// The lenticular calibration shot from photos (docs/calibration.md, "From photos"): one shot,
// "lens", on the panel under the lens sheet: a ring of markers (seen through the lenses: large
// cells, a few lenses each, stay readable) and inside it every subpixel lit by its own view
// fraction f under the nominal calibration: red 1/2 + 1/2 cos(2 pi f), green 1/2, blue
// 1/2 + 1/2 sin(2 pi f). Through each lens a camera sees one line of subpixels; where the true
// sheet differs from the nominal one, the fraction seen drifts from lens to lens, and the photo
// shows slow fringes whose phase, read as red + i blue, is that drift (the moire of the lenses
// against the nominal pattern, read in quadrature so its sign is known).
#pragma once

#include "parallax/display/lenticular.h"
#include "parallax/image/image.h"
#include "parallax/photocal/shot_layout.h"

namespace parallax::photocal {

struct LenticularShot {
  PanelGrid panel;
  MarkerRing ring;
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // the interior, panel pixels
  static constexpr int kFirstMarkerId = 100;
};

// Throws InputError naming the calibration when its panel is too small for the shot.
LenticularShot lenticularShot(const LenticularDesign& design);
Image drawLenticularShot(const LenticularShot& shot, const LenticularDesign& design);

}  // namespace parallax::photocal
