// A lenticular display's pitch, slope and center (as the renderer reads them: bundles converging
// at D, docs/lenticular.md) from photos of its "lens" shot (lenticular_shot.h; the derivation is
// docs/calibration.md, "From photos"). The model, stated once: an ideal cylindrical lens focused
// on the pixels shows a camera at C, through the lens whose axis crosses the sheet at across-
// coordinate c_k, the line of pixels at c_k (1 + g/C_z) - (g/C_z) C . n (g the sheet's
// air-equivalent focal gap); so the raw phase seen there is the nominal field at that line, and
// the fringes' phase psi over the sheet is linear with
//
//   grad psi = G (1 + g / C_z) - m,   psi(0) = phi - (g / C_z) G . C + r0   (mod 1)
//
// (G, r0 the nominal field, lenticular_model.h; m = s n / pitch and phi = s phase / pitch the
// sheet's). Checked against the photo maker (calibrate_photo_job_test.cpp): the truth's own
// calibration seen from (0, 0, D) shows no fringes and the phase 1/2. The fringes are read as the
// phasor (R / (kR G) - 1) + i (B / (kB G) - 1) (no mean taken out: a fringe flatter than a cycle
// keeps its phase; kR, kB the colour balance from the white band). The phases pin g (through the
// lever G . C / C_z, which differs between photos from different sides) far better than the
// gradients do, but modulo 1 / (L_1 - L_2): the branch is the one the gradients and the nominal
// gap agree with best. Two photos from distances and sides apart separate g, m and phi.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "parallax/display/lenticular.h"
#include "parallax/photocal/lenticular_model.h"
#include "parallax/photocal/marker_camera.h"

namespace parallax::photocal {

struct LenticularPhotoReport {
  std::string name;
  std::array<double, 3> cameraMm{};  // the camera's centre over the lens sheet, display frame
  double offAxisDegrees = 0;
  int markers = 0;
  double markerRmsPx = 0;
  int samples = 0;
  double coherence = 0;                    // |mean phasor| after the fit: 1 clean fringes, 0 none
  std::array<double, 2> fringeGradient{};  // grad psi, cycles per mm
  double fringePhase = 0;                  // psi at the panel's centre
};

struct LenticularMeasurement {
  LenticularCalibration measured;  // the nominal with pitch, slope and center measured
  double pitchSigma = 0, slopeSigma = 0, centerSigma = 0;
  double slantDegrees = 0, slantSigmaDegrees = 0;  // the lenses' axes from vertical
  double gapMm = 0, gapSigmaMm = 0;                // the sheet's air-equivalent focal gap
  double focalPx = 0, focalSigmaPx = 0, k1 = 0, k2 = 0;
  std::vector<LenticularPhotoReport> photos;
};

// One photo's fringes read through a known camera (its pose of the pixel plane, as the markers
// give it: the lens sheet at z = gapMm): psi's gradient (cycles per mm of the sheet, display
// frame) and its phase at the panel's centre, the raw phase less the lens count as the model
// above means it, with their standard deviations; amplitude 1 for full contrast.
struct LenticularFringes {
  std::array<double, 2> gradient{}, gradientSigma{};
  double phase = 0, phaseSigma = 0;  // phase in [0, 1)
  double amplitude = 0, coherence = 0;
  int samples = 0;
};
LenticularFringes readLenticularFringes(const LenticularDesign& nominal, const vision::Photo& photo,
                                        const vision::CameraIntrinsics& intrinsics,
                                        const vision::CameraPose& pixelPlanePose, double gapMm);

// Measures from the photos (any order; at least two, from distances at least a fifth apart).
// Throws InputError(photo, "", what is missing) for a photo that does not show the shot well
// enough, and InputError(the photos, ...) when the set leaves the gap open.
// knownCamerasMm: where each photo's camera stood when that is known from elsewhere (display
// frame over the pixels, one per photo; `calibrate study --true-camera` gives the photo maker's,
// to tell the camera's share of the error from the rest); empty: the markers' camera alone.
LenticularMeasurement measureLenticular(
    const LenticularDesign& nominal, const std::vector<NamedPhoto>& photos,
    const std::function<void(int, int)>& progress = {},
    const std::vector<std::array<double, 3>>& knownCamerasMm = {});

}  // namespace parallax::photocal
