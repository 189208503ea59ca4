// The benchmark: our renderer against raw Embree, measured in one run.
#pragma once

#include <cstdint>

#include "parallax/accel/accelerator.h"
#include "parallax/camera/camera.h"
#include "parallax/render/render.h"
#include "parallax/scene/scene.h"

namespace parallax {

// Rays traced in a time; the rate of the fastest of several runs.
struct RayRate {
  uint64_t rays = 0;
  double seconds = 0.0;
  double perSecond() const { return seconds > 0 ? double(rays) / seconds : 0.0; }
};

struct BenchResult {
  RayRate ours;      // primary + shadow + secondary, shaded
  RayRate limit;     // raw Embree, coherent pinhole rays: primary + one shadow ray per hit
  RayRate sameRays;  // raw Embree on our camera's own rays, in our packet order, the same way
  double ratio() const { return limit.perSecond() > 0 ? ours.perSecond() / limit.perSecond() : 0; }
};

// Renders through `camera` with `settings` and traces two raw Embree limits at the same rays
// per pixel, alternating `repeats` times and keeping the fastest of each (the machines are
// noisy): the coherent pinhole rays of `limitGrid` (for the display camera, a pinhole at the
// view-zone centre that sees what the display shows), and the camera's own rays. The gap
// between the two limits is what the camera's ray order costs Embree; the gap between the
// same-rays limit and ours is what shading costs.
BenchResult benchmark(const Scene& scene, const Accelerator& accelerator, const Camera& camera,
                      const PinholeGrid& limitGrid, const RenderSettings& settings,
                      int repeats = 2);

}  // namespace parallax
