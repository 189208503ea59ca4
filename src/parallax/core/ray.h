// A ray: origin, direction (not necessarily unit) and the parametric interval [tMin, tMax].
#pragma once

#include <cstdint>
#include <limits>

#include "parallax/core/math.h"

namespace parallax {

struct Ray {
  Vec3f origin;
  Vec3f direction;
  float tMin = 0.0f;
  float tMax = std::numeric_limits<float>::infinity();

  Vec3f at(float t) const { return origin + direction * t; }
};

// Sixteen rays in structure-of-arrays form (Embree's RTCRay16 layout, not its type).
struct alignas(64) RayPacket16 {
  static constexpr int kSize = 16;
  float ox[16], oy[16], oz[16];
  float dx[16], dy[16], dz[16];
  float tMin[16], tMax[16];
  int32_t active[16];  // -1 = trace this lane, 0 = ignore it

  void set(int lane, const Ray& ray) {
    ox[lane] = ray.origin.x, oy[lane] = ray.origin.y, oz[lane] = ray.origin.z;
    dx[lane] = ray.direction.x, dy[lane] = ray.direction.y, dz[lane] = ray.direction.z;
    tMin[lane] = ray.tMin, tMax[lane] = ray.tMax;
    active[lane] = -1;
  }
  void deactivate(int lane) { active[lane] = 0; }
  Ray ray(int lane) const {
    return {{ox[lane], oy[lane], oz[lane]}, {dx[lane], dy[lane], dz[lane]}, tMin[lane], tMax[lane]};
  }
};

// Pinhole rays for the raw limit: pixel (x, y) sample s has its origin at `eye` and passes
// through pixel00 + (x + jx) * pixelDx + (y + jy) * pixelDy, (jx, jy) on a stratified
// sqrt(spp) x sqrt(spp) grid (spp rounded down to a square).
struct PinholeGrid {
  Vec3f eye, pixel00, pixelDx, pixelDy;
  int width = 0, height = 0, samplesPerPixel = 1;
};

}  // namespace parallax
