// The barrier's effective gap, mask panel offset and rotation from photos of its "grid" shot
// (barrier_shot.h; docs/calibration.md, "From photos"). The model the estimate rests on, stated
// once: light reaches the camera's centre C along straight lines (the gap is the air-equivalent
// gap straight rays see), through front point F and rear point R = F + (F - C) g / C_z; the rear
// panel sits turned by theta about its centre, which is displaced by (s_x, s_y) from the front
// panel's. The camera (one focal length and radial distortion for all photos of a set, a pose
// per photo) comes from the front's markers.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "parallax/display/display.h"
#include "parallax/photocal/barrier_shot.h"
#include "parallax/photocal/marker_camera.h"
#include "parallax/photocal/photo_sampler.h"

namespace parallax::photocal {

struct BarrierPhotoReport {
  std::string name;
  std::array<double, 3> cameraMm{};     // the camera's centre, display frame
  double offAxisDegrees = 0;            // between the panel's normal and the line to the camera
  int markers = 0;                      // markers found of the ring's
  double markerRmsPx = 0;               // the camera fit's reprojection error for this photo
  int frontBlocks = 0, rearBlocks = 0;  // grating blocks used
  double contrast = 0;                  // the rear gratings' median amplitude over the mean
};

struct BarrierMeasurement {
  double gapMm = 0, gapSigmaMm = 0;                      // effective (air-equivalent) gap
  double rearOffsetXMm = 0, rearOffsetSigmaMm = 0;       // rear panel's centre against the front's
  double rearOffsetYMm = 0;                              // and upward
  double rotationDegrees = 0, rotationSigmaDegrees = 0;  // rear against front, counter-clockwise
  // The same as the display file means them: the mask panel against the image panel.
  double maskPanelOffsetPx = 0, maskPanelOffsetSigmaPx = 0;
  double maskRotationDegrees = 0;
  // What the rotation costs: the drawn mask is off by up to this many mask pixels at the top
  // and bottom rows (the display file has no key for a rotation).
  double rotationEdgeErrorPx = 0;
  double focalPx = 0, focalSigmaPx = 0, k1 = 0, k2 = 0;
  double residualPx = 0;  // rms of the rear blocks' phase residuals, rear pixels
  std::vector<BarrierPhotoReport> photos;
};

// Measures from the photos (any order, at least one; every photo from one camera). Throws
// InputError(photo name, "", what is missing) for a photo that does not show the shot well
// enough, and InputError("photos", ...) when the set does not constrain the gap.
// `progress(done, total)` is called as the photos are read.
BarrierMeasurement measureBarrier(const DisplaySpec& nominal, const std::vector<NamedPhoto>& photos,
                                  const std::function<void(int, int)>& progress = {});

// ---- the parts, for tests ------------------------------------------------------------------

// Where the front really is, per band and block: the shift (front pixels) from where the camera
// put it, across and down; NaN where the gratings are not seen (off the photo, or in a dark band
// of the two panels' moire).
struct FrontBlocks {
  int bands = 0, across = 0;
  std::vector<double> shiftX, shiftY;
  std::vector<double> white;  // each fitted block's white light
  std::vector<int> whiteAt;   // and its index
  int seen = 0;
  double at(const std::vector<double>& v, int band, int block) const {
    return v[size_t(band * across + block)];
  }
};

// The front's gratings block by block, read through `photo`'s camera.
FrontBlocks measureFront(const BarrierShot& shot, const PhotoSampler& photo);
// The blocks as points of the panel plane for a camera fit: the photo shows, where the camera
// put each block's centre, the front point its phases say.
// Only blocks within trustedShiftPx of where the camera puts them (a farther one may have
// slipped a period).
std::vector<vision::PlaneCorrespondence> frontPoints(const BarrierShot& shot,
                                                     const FrontBlocks& blocks,
                                                     const vision::CameraFit& camera, size_t photo,
                                                     double trustedShiftPx);

}  // namespace parallax::photocal
