#include <cmath>

#include <limits>
#include <stdexcept>
#include "parallax/core/lane_kernel.h"

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

namespace {

// The lane loop of generateRays16, outside the class: GCC cannot make ISA clones of a virtual
// function (core/lane_kernel.h).
// The camera's vectors by value and a restricted packet: no store to the packet can change
// what the loop reads, so it vectorises.
PARALLAX_LANE_KERNEL void pinholeRays16(const Vec3f eye, const Vec3f pixel00, const Vec3f pixelDx,
                                        const Vec3f pixelDy, const FilmSamples16& s,
                                        RayPacket16& __restrict out) {
  for (int i = 0; i < 16; ++i) {
    out.ox[i] = eye.x, out.oy[i] = eye.y, out.oz[i] = eye.z;
    out.dx[i] = pixel00.x + pixelDx.x * s.x[i] + pixelDy.x * s.y[i];
    out.dy[i] = pixel00.y + pixelDx.y * s.x[i] + pixelDy.y * s.y[i];
    out.dz[i] = pixel00.z + pixelDx.z * s.x[i] + pixelDy.z * s.y[i];
    out.tMin[i] = 0.0f;
    out.tMax[i] = std::numeric_limits<float>::infinity();
  }
}

}  // namespace

void PinholeCamera::generateRays16(const FilmSamples16& s, RayPacket16& out) const {
  pinholeRays16(eye_, pixel00_, pixelDx_, pixelDy_, s, out);
}

PinholeGrid PinholeCamera::grid(int samplesPerPixel) const {
  // PinholeGrid holds the film as points; the camera keeps it as directions from the eye.
  return {eye_, eye_ + pixel00_, pixelDx_, pixelDy_, width_, height_, samplesPerPixel};
}

}  // namespace parallax
