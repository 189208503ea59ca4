// A photo as light: the sRGB codes decoded to linear values (the mean of R, G and B), looked up
// bilinearly at display-frame points through a fitted camera. Both estimators read photos so.
#pragma once

#include <array>
#include <vector>

#include "parallax/vision/vision.h"

namespace parallax::photocal {

class PhotoSampler {
 public:
  // colour: keep R, G and B apart (rgbAt); otherwise only their mean (at).
  PhotoSampler(const vision::Photo& photo, const vision::CameraIntrinsics& intrinsics,
               const vision::CameraPose& pose, bool colour = false);
  // The light at photo point p (pixel centres at +0.5); NaN outside the photo.
  float at(const vision::PhotoPoint& p) const;
  // R, G and B at photo point p (a colour sampler); false outside the photo.
  bool rgbAt(const vision::PhotoPoint& p, float rgb[3]) const;
  vision::PhotoPoint project(double xMm, double yMm, double zMm) const {
    return vision::projectPoint(intrinsics_, pose_, {xMm, yMm, zMm});
  }
  // The light where the camera shows the display-frame point (mm).
  float atPoint(double xMm, double yMm, double zMm) const {
    return at(vision::projectPoint(intrinsics_, pose_, {xMm, yMm, zMm}));
  }
  // The photo's scale there: photo pixels per mm of the panel plane (z = 0) along x.
  double pixelsPerMm(double xMm, double yMm) const;

 private:
  int width_, height_, channels_;
  std::vector<float> light_;  // channels_ floats per pixel
  vision::CameraIntrinsics intrinsics_;
  vision::CameraPose pose_;
};

}  // namespace parallax::photocal
