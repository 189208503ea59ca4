#include <cmath>
#include <limits>
#include <stdexcept>

#include "parallax/camera/camera.h"

namespace parallax {

PinholeCamera::PinholeCamera(const Vec3f& eye, const Vec3f& lookAt, const Vec3f& up,
                             float fovDegrees, int width, int height)
    : eye_(eye), width_(width), height_(height) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("camera size must be positive");
  if (!(fovDegrees > 0.0f && fovDegrees < 180.0f))
    throw std::invalid_argument("field of view must be in (0, 180) degrees");
  const Vec3f forward = normalize(lookAt - eye);
  const Vec3f right = normalize(cross(forward, up));
  const Vec3f trueUp = cross(right, forward);
  // The film sits at unit distance; its half height is tan(fov / 2).
  const float halfHeight = std::tan(0.5f * fovDegrees * kPi / 180.0f);
  const float halfWidth = halfHeight * float(width) / float(height);
  pixelDx_ = right * (2.0f * halfWidth / float(width));
  pixelDy_ = trueUp * (-2.0f * halfHeight / float(height));
  pixel00_ = forward - right * halfWidth + trueUp * halfHeight;
}

void PinholeCamera::generateRays16(const FilmSamples16& s, RayPacket16& out) const {
  for (int i = 0; i < 16; ++i) {
    out.ox[i] = eye_.x, out.oy[i] = eye_.y, out.oz[i] = eye_.z;
    out.dx[i] = pixel00_.x + pixelDx_.x * s.x[i] + pixelDy_.x * s.y[i];
    out.dy[i] = pixel00_.y + pixelDx_.y * s.x[i] + pixelDy_.y * s.y[i];
    out.dz[i] = pixel00_.z + pixelDx_.z * s.x[i] + pixelDy_.z * s.y[i];
    out.tMin[i] = 0.0f;
    out.tMax[i] = std::numeric_limits<float>::infinity();
  }
}

PinholeGrid PinholeCamera::grid(int samplesPerPixel) const {
  // PinholeGrid holds the film as points; the camera keeps it as directions from the eye.
  return {eye_, eye_ + pixel00_, pixelDx_, pixelDy_, width_, height_, samplesPerPixel};
}

}  // namespace parallax
