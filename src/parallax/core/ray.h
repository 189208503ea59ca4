// A ray: origin, direction (not necessarily unit) and the parametric interval [tMin, tMax].
#pragma once

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

}  // namespace parallax
