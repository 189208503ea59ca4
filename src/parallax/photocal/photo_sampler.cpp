#include "parallax/photocal/photo_sampler.h"

#include <cmath>
#include <limits>

#include "parallax/image/image.h"

namespace parallax::photocal {

PhotoSampler::PhotoSampler(const vision::Photo& photo, const vision::CameraIntrinsics& intrinsics,
                           const vision::CameraPose& pose, bool colour)
    : width_(photo.width),
      height_(photo.height),
      channels_(colour ? 3 : 1),
      light_(size_t(photo.width) * size_t(photo.height) * size_t(channels_)),
      intrinsics_(intrinsics),
      pose_(pose) {
  const size_t pixels = size_t(photo.width) * size_t(photo.height);
  if (colour) {
    for (size_t i = 0; i < 3 * pixels; ++i) light_[i] = srgb8ToLinear(photo.rgb[i]);
    return;
  }
  for (size_t i = 0; i < pixels; ++i)
    light_[i] = (srgb8ToLinear(photo.rgb[3 * i]) + srgb8ToLinear(photo.rgb[3 * i + 1]) +
                 srgb8ToLinear(photo.rgb[3 * i + 2])) /
                3.0f;
}

bool PhotoSampler::rgbAt(const vision::PhotoPoint& p, float rgb[3]) const {
  const double x = p.x - 0.5, y = p.y - 0.5;
  if (channels_ != 3 || !(x >= 0 && y >= 0 && x < width_ - 1 && y < height_ - 1)) return false;
  const int x0 = int(x), y0 = int(y);
  const float fx = float(x - x0), fy = float(y - y0);
  const size_t stride = size_t(width_) * 3;
  const float* row = &light_[size_t(y0) * stride + size_t(x0) * 3];
  for (int c = 0; c < 3; ++c) {
    const float top = row[c] + fx * (row[3 + c] - row[c]);
    const float bottom = row[stride + c] + fx * (row[stride + 3 + c] - row[stride + c]);
    rgb[c] = top + fy * (bottom - top);
  }
  return true;
}

float PhotoSampler::at(const vision::PhotoPoint& p) const {
  const double x = p.x - 0.5, y = p.y - 0.5;
  if (!(x >= 0 && y >= 0 && x < width_ - 1 && y < height_ - 1))
    return std::numeric_limits<float>::quiet_NaN();
  if (channels_ != 1) {
    float rgb[3];
    return rgbAt(p, rgb) ? (rgb[0] + rgb[1] + rgb[2]) / 3.0f
                         : std::numeric_limits<float>::quiet_NaN();
  }
  const int x0 = int(x), y0 = int(y);
  const float fx = float(x - x0), fy = float(y - y0);
  const float* row = &light_[size_t(y0) * size_t(width_) + size_t(x0)];
  const float top = row[0] + fx * (row[1] - row[0]);
  const float bottom = row[width_] + fx * (row[width_ + 1] - row[width_]);
  return top + fy * (bottom - top);
}

double PhotoSampler::pixelsPerMm(double xMm, double yMm) const {
  const vision::PhotoPoint a = vision::projectPoint(intrinsics_, pose_, {xMm, yMm, 0});
  const vision::PhotoPoint b = vision::projectPoint(intrinsics_, pose_, {xMm + 1, yMm, 0});
  return std::hypot(b.x - a.x, b.y - a.y);
}

}  // namespace parallax::photocal
