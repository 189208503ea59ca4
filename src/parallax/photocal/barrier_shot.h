// The barrier's calibration shot from photos (docs/calibration.md, "From photos"): one shot,
// "grid", whose photos give the effective gap, the mask panel's sideways offset and the two
// panels' relative rotation.
//
// The front layer carries a ring of markers (the panel and the camera's pose) and, inside it,
// horizontal bands in which the front shows a grating and the rear is white, alternating with
// bands in which the rear shows gratings and the front is white:
//
//   band row  0..31  front: cos gratings across (periods P, P + 1) and down (32 rows); rear white
//            32..47  both white (a guard: rays cross the gap at a slant, and the panels may sit
//                    a few pixels apart vertically)
//            48..79  front: white; rear: the same gratings, in its own pixels
//            80..95  both white
//
// Seen through the white front, the rear gratings' phases at each front position say which rear
// point the straight line from the camera through that front point reaches, across and down:
// with the camera's centre C known, that is the gap (the rear looks magnified by (C_z + g)/C_z
// about C, and shifted by g tan of the camera's angle, whichever way the camera leans) and the
// rear panel's offset and rotation. The front gratings say where the front
// really is in the photo: thousands of points that fit the camera far better than the markers
// alone (which the moire of two colour panels' stripes hides in dark bands), and next to each
// rear band, so that what error is left of the mapping cancels in the difference. The two
// periods across form a vernier: together they fix a position within P (P + 1) pixels, not only
// modulo one period; a block of P (P + 1) columns holds whole periods of both.
#pragma once

#include "parallax/display/display.h"
#include "parallax/image/image.h"
#include "parallax/photocal/shot_layout.h"

namespace parallax::photocal {

struct BarrierShot {
  PanelGrid front, rear;
  bool frontIsImage = true;  // barrier-back: the image layer in front
  MarkerRing ring;
  // The banded interior, in front pixels: x from x0 to x1, whole bands from y0.
  int x0 = 0, x1 = 0, y0 = 0, bands = 0;
  static constexpr int kBandPx = 96;
  static constexpr int kFrontRows[2] = {0, 32};      // band rows of the front gratings
  static constexpr int kRearRows[2] = {48, 80};      // band rows of the rear gratings
  static constexpr double kPeriodsPx[2] = {12, 13};  // across, on both layers
  static constexpr double kFrontRowPeriodPx = 32;    // down, on the front
  static constexpr int kBlockPx = 156;               // 13 and 12 whole periods
  static constexpr int kFirstMarkerId = 0;
};

// The shot for a barrier display (its two panels and their order). Throws InputError naming the
// display when its front panel is too small for markers and bands.
BarrierShot barrierShot(const DisplaySpec& display);

// The two pictures: the front layer's and the rear layer's, linear RGB at each panel's size.
struct BarrierShotPictures {
  Image front, rear;
};
BarrierShotPictures drawBarrierShot(const BarrierShot& shot);

// The gratings' value at a panel pixel's centre (pixel coordinates relative to the panel's
// centre, x right and y down, in pixels), on either layer: what drawBarrierShot draws and what
// the estimator fits.
double shotGratings(double xFromCentrePx, double yFromCentrePx);

}  // namespace parallax::photocal
