// What one seat sees of a lenticular display, from a phone photo taken there of the lens shot
// drawn with the display's calibration (`calibrate patterns --photo --display FILE`): the check
// that a calibration took (docs/calibration.md, "Checking a calibration"). The shot lights every
// subpixel with its own view fraction f in quadrature (red 1/2 + 1/2 cos 2 pi f, blue
// 1/2 + 1/2 sin 2 pi f, green 1/2), so the photo's colour phasor, read block by block over the
// panel as the estimator reads its fringes (lenticular_estimate.h), is
//
//   z = A exp(2 pi i f_seen):
//
// its phase the view fraction the seat sees, its gradient how that view changes across the
// panel (none from D with a right calibration), and its amplitude A the spread of the views the
// eye takes in: a lens that mixes views with the distribution w(df) shows A = |E w[exp(2 pi i
// df)]| (the camera's own blur does not lower it: neighbouring lenses show the same view). Read
// with the renderer's model of what an eye integrates (lensSpotWeight: a subpixel spans delta =
// 1 / subpixelsPerLens of the views, the focal spot W delta, both boxes), A = sinc(delta)
// sinc(W delta), sinc(u) = sin(pi u) / (pi u): the focal spot W that `simulate --lens-spot`
// takes, and the share of the light from other views than the one at the eye.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "parallax/display/lenticular.h"
#include "parallax/photocal/marker_camera.h"

namespace parallax::photocal {

struct SeatCheck {
  std::string name;                  // the photo
  std::array<double, 3> cameraMm{};  // where it was taken (display frame, over the pixels)
  double offAxisDegrees = 0;
  double distanceSigmaMm = 0;  // the camera's distance is as sure as its focal length
  int markers = 0;
  // The view fraction seen at the panel's centre (quilt view k of N is (k + 1/2) / N), and the
  // one a right calibration shows where the markers put the camera (the model of
  // lenticular_estimate.h with the file's own sheet: through slanted lenses the camera's height
  // counts too, which the renderer's horizontal bundles leave out): their difference is the
  // centre's error plus the camera's direction's (g |G| a radian: on a Portrait a degree is
  // 0.02 of a period).
  double viewSeen = 0, viewSeenSigma = 0, viewAimed = 0;
  // The view fraction seen at the panel's left and right edges (on its middle row) and at its
  // top and bottom (middle column), against a right calibration's (the camera's distance off D
  // fans the views; they do not change vertically): a pitch or slant error fans them further.
  std::array<double, 2> edgesSeen{}, edgesAimed{};
  std::array<double, 2> topBottomSeen{};
  double amplitude = 0;      // A: 1 one view only
  double spotSubpixels = 0;  // W with A = sinc(delta) sinc(W delta); 0 when A >= sinc(delta)
  double otherViews = 0;     // the share of the light from beyond half a view of f_seen
  double coherence = 0;      // how well one plane fits the blocks' phases (1 clean)
};

// Checks each photo (one phone at one zoom fitted to all, a pose each); throws InputError
// naming a photo whose panel or pattern is not found.
std::vector<SeatCheck> checkLenticularSeats(const LenticularDesign& shown,
                                            const std::vector<NamedPhoto>& photos,
                                            const std::function<void(int, int)>& progress = {});

// A = sinc(delta) sinc(W delta) for the renderer's spot model (the amplitude of the views an
// eye takes in), and its inverse (W from A, 0 where A is at or above the ideal lens's, capped
// at kMaxLensSpotSubpixels).
double seenAmplitudeOfSpot(const LenticularDesign& design, double spotSubpixels);
double spotOfSeenAmplitude(const LenticularDesign& design, double amplitude);
// The share of the light an eye takes in from beyond half a view (of design.quiltViews) of its
// own, with a focal spot of W subpixels (the same model).
double otherViewsShare(const LenticularDesign& design, double spotSubpixels);

}  // namespace parallax::photocal
