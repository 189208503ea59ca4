#include "parallax/render/bench.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <limits>

#include "parallax/render/light_sampler.h"
#include "parallax/render/render.h"

namespace parallax {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The raw limit, parallelised like the renderer: bands of 16 rows (4 packets high).
uint64_t traceLimit(const Accelerator& accelerator, const PinholeGrid& grid, const Vec3f& light,
                    tbb::task_arena& arena) {
  tbb::enumerable_thread_specific<uint64_t> counts(0);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, (grid.height + 15) / 16, 1),
                      [&](const tbb::blocked_range<int>& bands) {
                        for (int band = bands.begin(); band != bands.end(); ++band)
                          counts.local() += accelerator.traceRawLimit(
                              grid, band * 16, std::min(grid.height, band * 16 + 16), light);
                      });
  });
  return counts.combine([](uint64_t a, uint64_t b) { return a + b; });
}

}  // namespace

BenchResult benchmark(const Scene& scene, const Accelerator& accelerator, const Camera& camera,
                      const PinholeCamera& limitCamera, int samplesPerPixel, int repeats,
                      int threads) {
  BenchResult result;
  result.seconds = result.limitSeconds = std::numeric_limits<double>::infinity();
  const PinholeGrid grid = limitCamera.grid(samplesPerPixel);
  const Vec3f light = LightSampler(scene).representativePoint(grid.eye);
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  RenderSettings settings;
  settings.samplesPerPixel = samplesPerPixel;
  settings.threads = threads;
  for (int i = 0; i < std::max(1, repeats); ++i) {
    auto start = std::chrono::steady_clock::now();
    result.limitRays = traceLimit(accelerator, grid, light, arena);
    result.limitSeconds = std::min(result.limitSeconds, secondsSince(start));

    RenderStats stats;
    render(scene, accelerator, camera, settings, &stats);
    result.rays = stats.totalRays();
    result.seconds = std::min(result.seconds, stats.seconds);
  }
  return result;
}

}  // namespace parallax
