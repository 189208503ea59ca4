// The photo maker: photos of physical panels made from the physics alone, the truth that
// calibration from photos (photocal) is tested against (docs/calibration.md, "The photo maker").
// It knows nothing of display files, the simulator or the estimator: a panel here is glass and
// liquid crystal at a place, a lens sheet is cylinders of glass, a camera is a pose, a lens, a
// sensor and a JPEG encoder's input.
//
// Frame (as docs/display-geometry.md): millimetres, the front of the display at z = 0 with its
// centre at the origin, x right, y up, z toward the viewer. Light is linear RGB in [0, 1].
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "parallax/image/image.h"

namespace parallax::photomaker {

// One colour LCD panel: width x height pixels of pitch pitchMm, each pixel three vertical
// stripes R, G, B (or B, G, R) of width pitch/3, of which the middle fillFactor (of the stripe's
// width and of the pixel's height) lets light through; the rest is the black matrix. Its centre
// sits at (offsetXMm, offsetYMm) in its own plane, turned by rotationDegrees (counter-clockwise
// as the viewer sees it) about that centre.
struct LcdPanel {
  int width = 1920, height = 1080;
  double pitchMm = 0.2745;
  bool bgr = false;
  double fillFactor = 0.85;
  double offsetXMm = 0, offsetYMm = 0;
  double rotationDegrees = 0;
};

// A two-layer barrier display: light from a uniform backlight passes the rear panel, crosses
// a gap (air-equivalent: the straight-ray gap) and passes the front panel. What the eye gets
// through front point p is rear(q) * front(p) for the straight line from the eye through p to
// q on the rear panel, per colour channel (the subpixel stripes of both panels included).
struct PhysicalBarrier {
  LcdPanel front;  // at z = 0
  LcdPanel rear;   // at z = -gapMm
  double gapMm = 3.0;
  double backlight = 1.0;
};

// A slanted lenticular display: an emitting panel under a sheet of cylindrical lenses. The lens
// sheet's vertex plane is z = 0; the pixels sit at z = -focalGapMm (air-equivalent), where each
// lens focuses. Lenses are pitchMm wide measured across them, their axes turned slantDegrees from
// vertical (positive: the top of a lens leans to the right as the viewer sees it), and lens 0's
// axis lies phaseMm from the origin measured across the lenses (the across coordinate of a
// point p is p . n with n = (cos slant, -sin slant), so lens k's axis is where
// p . n = phaseMm + k pitchMm; it crosses the x axis at x = phaseMm / cos slant). A lens images the
// pixel plane with a spot of spotSigmaMm (Gaussian, across the lens), plus whatever defocus a
// focal gap other than its focal length gives (focalLengthMm; 0: focused on the pixels).
struct PhysicalLenticular {
  LcdPanel panel;  // emits: a picture's value is light leaving the subpixel
  double pitchMm = 0.4885;
  double slantDegrees = 8.13;
  double phaseMm = 0;
  double focalGapMm = 1.0;
  double focalLengthMm = 0;
  double spotSigmaMm = 0.0;
};

// A phone camera: its centre at positionMm looking at lookAtMm, rolled by rollDegrees about its
// axis; a lens of focal length focalPx (in sensor pixels) with radial distortion k1, k2
// (OpenCV's model, normalised coordinates), focused at focusDistanceMm with an aperture
// apertureMm across (0: a pinhole, everything sharp); a sensor of width x height pixels
// with read noise noiseSigma (linear, Gaussian, per channel after exposure) and shot noise
// shotNoise (variance shotNoise * signal), exposure multiplying the light, an sRGB response,
// rounded to 8 bits. The principal point is the sensor's centre (width/2, height/2), pixel i
// spanning [i, i + 1). Picture x runs along the camera's right = forward x (0, 1, 0), y down;
// a positive roll turns the camera counter-clockwise as its user sees through it (its right
// toward its up), so the scene turns clockwise in the photo.
struct PhoneCamera {
  std::array<double, 3> positionMm{0, 0, 600};
  std::array<double, 3> lookAtMm{0, 0, 0};
  double rollDegrees = 0;
  int width = 4032, height = 3024;
  double focalPx = 3000;
  double k1 = 0, k2 = 0;
  double focusDistanceMm = 600;
  double apertureMm = 0;
  double exposure = 1.0;
  double noiseSigma = 0;
  double shotNoise = 0;
  // The lens's own blur, diffraction and the demosaicing, as one Gaussian point spread of this
  // sigma in sensor pixels (a phone's is about a pixel); 0 none.
  double blurSigmaPx = 0;
  int samplesPerPixel = 16;  // stratified over the pixel's area and the aperture
  uint64_t seed = 1;
};

// An 8-bit sRGB photo, row 0 at the top, R G B per pixel (what a phone stores before JPEG).
struct PhotoPixels {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
};

// Pictures on the panels: linear RGB per panel pixel, the panel's own width x height (row 0 the
// top row as the viewer sees it). Throws std::invalid_argument when a size differs.
// `threads`: workers (0: every core); the bytes are the same whatever the count (every pixel's
// random numbers come from the seed and the pixel alone).
PhotoPixels photographBarrier(const PhysicalBarrier& display, const Image& front, const Image& rear,
                              const PhoneCamera& camera, int threads = 0);
PhotoPixels photographLenticular(const PhysicalLenticular& display, const Image& panel,
                                 const PhoneCamera& camera, int threads = 0);

// What an eye (a point at eyeMm) sees through the front of the display: for each pixel (i, j)
// of a width x height picture spanning the front panel (barrier) or the lens sheet over the
// panel (lenticular), the mean light over that pixel's area (samplesPerPixel stratified points)
// arriving at the eye. The simulator's output is compared with this (tests).
Image eyeViewBarrier(const PhysicalBarrier& display, const Image& front, const Image& rear,
                     const std::array<double, 3>& eyeMm, int width, int height, int samplesPerPixel,
                     int threads = 0);
Image eyeViewLenticular(const PhysicalLenticular& display, const Image& panel,
                        const std::array<double, 3>& eyeMm, int width, int height,
                        int samplesPerPixel, int threads = 0);

}  // namespace parallax::photomaker
