// What a walk through Gaussian splats returns (Accelerator::nextSplats, docs/splats.md,
// "Tracing"): plain values shared by the accelerator's interface and its Embree back end.
#pragma once

#include <cstdint>
#include <limits>

namespace parallax {

// A Gaussian splat met along a ray (docs/splats.md, "Tracing"): where its response peaks (t, in
// units of the ray's direction), which Gaussian (its index over every set of Scene::splats in
// order) and its alpha there (capped as 3DGS caps it).
struct SplatHit {
  float t = 0.0f;
  uint32_t gaussian = 0;
  float alpha = 0.0f;
};
// Where a ray's walk through the splats stands: hits are ordered by (t, gaussian), and a query
// returns only those after the cursor's.
struct SplatCursor {
  float t = -std::numeric_limits<float>::infinity();
  uint32_t gaussian = 0;
  bool started = false;  // false: nothing is behind the cursor yet
};

}  // namespace parallax
