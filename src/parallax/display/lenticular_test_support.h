// Shared by the lenticular tests of several modules (camera, render, sim): a small invented
// calibration, about 5.8 pixels per lens on a 180-pixel-wide 40 DPI panel, quick to render.
#pragma once

#include "parallax/display/lenticular.h"

namespace parallax {

inline LenticularDesign smallLenticularDesign(int height = 120, bool flipImageX = false) {
  LenticularCalibration c;
  c.source = "small.json";
  c.pitch = 7.0;
  c.slope = -6.0;
  c.center = 0.3;
  c.viewConeDegrees = 40;
  c.dpi = 40;
  c.screenW = 180;
  c.screenH = height;
  c.invView = true;
  c.flipImageX = flipImageX;
  return designLenticular(c);
}

}  // namespace parallax
