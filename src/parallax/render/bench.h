// The benchmark: our renderer against raw Embree on the same rays, measured in one run.
#pragma once

#include <cstdint>

#include "parallax/accel/accelerator.h"
#include "parallax/camera/camera.h"
#include "parallax/scene/scene.h"

namespace parallax {

struct BenchResult {
  uint64_t rays = 0;  // ours: primary + shadow + secondary
  double seconds = 0.0;
  uint64_t limitRays = 0;  // raw Embree: primary + one shadow ray per hit
  double limitSeconds = 0.0;
  double raysPerSecond() const { return seconds > 0 ? double(rays) / seconds : 0.0; }
  double limitRaysPerSecond() const {
    return limitSeconds > 0 ? double(limitRays) / limitSeconds : 0.0;
  }
  double ratio() const {
    return limitRaysPerSecond() > 0 ? raysPerSecond() / limitRaysPerSecond() : 0.0;
  }
};

// Renders through `camera` at `samplesPerPixel` and traces the raw Embree limit for the
// coherent pinhole rays of `limitCamera` at the same rays per pixel, alternating `repeats`
// times and keeping the fastest of each (the machines are noisy). For the pinhole benchmark
// both cameras are the same; the display camera is measured against the same pinhole limit.
BenchResult benchmark(const Scene& scene, const Accelerator& accelerator, const Camera& camera,
                      const PinholeCamera& limitCamera, int samplesPerPixel, int repeats = 2,
                      int threads = 0);

}  // namespace parallax
