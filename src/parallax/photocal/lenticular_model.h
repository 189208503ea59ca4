// The lens sheet as photos see it and as the renderer reads it (docs/calibration.md, "From
// photos", the lenticular derivation). The renderer's calibration (visual.json's pitch, slope
// and center, docs/lenticular.md) gives every subpixel a raw phase r, the shader's
// (u + i/(3 screenW) + v tilt) pitch_px - center before invView; as a function of where the
// subpixel physically sits, r(P) = G . P + r0 (mod 1), a linear field. A physical sheet (lenses
// pitchMm wide across, axes slantDegrees from vertical, lens 0's axis at phaseMm across the
// origin, the pixels gapMm behind, air-equivalent) sends the light of the subpixel at P toward
// the eye line at the design distance D through the lens axis above it; bundles converging at D
// (docs/lenticular.md) then mean
//
//   r(P) = s (P . n) / p_D + 1/2 - s phaseMm / pitchMm,   p_D = pitchMm (D + gap) / D,
//
// n = (cos slant, -sin slant) the unit vector across the lenses, and s = +1 when the lens inverts
// the views (invView 1, every shipped device) or -1.
#pragma once

#include "parallax/display/lenticular.h"

namespace parallax::photocal {

// The raw phase of the subpixel physically at P (mm, display frame): gx x + gy y + r0 (mod 1).
struct PhaseField {
  double gx = 0, gy = 0;  // per mm
  double r0 = 0;          // at the panel's centre, in [0, 1)
};

// The design's field, fitted to its subpixels (every kind of subpixel cell and flip included).
PhaseField phaseFieldOf(const LenticularDesign& design);

// The calibration whose field is `target`, every key but pitch, slope and center kept from
// `nominal`; center is taken within half a period of the nominal's. Throws InputError (naming
// nominal.source) if no calibration gives it.
LenticularCalibration calibrationWithField(const LenticularCalibration& nominal,
                                           const PhaseField& target, double viewDistanceMm);

// The sheet's air-equivalent focal gap the calibration's view cone implies: a lens of
// horizontal width p_h sends a view cone of 2 atan(p_h / 2 g).
double sheetGapOfViewCone(const LenticularDesign& design);

// A physical lens sheet (the photo maker's own description of one).
struct LensSheet {
  double pitchMm = 0, slantDegrees = 0, phaseMm = 0, gapMm = 0;
};
// Its field for the renderer (the formula above), with s from `invView`.
PhaseField fieldOfSheet(const LensSheet& sheet, bool invView, double viewDistanceMm);

}  // namespace parallax::photocal
