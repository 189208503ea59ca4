#include "parallax/render/bench.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <limits>

#include "parallax/render/light_sampler.h"
#include "parallax/render/tile_packets.h"

namespace parallax {

namespace {

// Runs count(i) for i in [0, n) over the arena's threads, as the renderer does, and returns
// the summed rays with the wall time.
template <class Count>
RayRate timedSum(tbb::task_arena& arena, int n, const Count& count) {
  const auto start = std::chrono::steady_clock::now();
  tbb::enumerable_thread_specific<uint64_t> counts(0);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, n, 1), [&](const tbb::blocked_range<int>& r) {
      for (int i = r.begin(); i != r.end(); ++i) counts.local() += count(i);
    });
  });
  const uint64_t rays = counts.combine([](uint64_t a, uint64_t b) { return a + b; });
  return {rays, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

void keepFastest(RayRate& best, const RayRate& run) {
  if (run.seconds < best.seconds) best = run;
}

}  // namespace

BenchResult benchmark(const Scene& scene, const Accelerator& accelerator, const Camera& camera,
                      const PinholeGrid& limitGrid, const RenderSettings& settings, int repeats) {
  BenchResult result;
  const double never = std::numeric_limits<double>::infinity();
  result.ours.seconds = result.limit.seconds = result.sameRays.seconds = never;
  const Vec3f light = LightSampler(scene).representativePoint(limitGrid.eye);
  tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
  const TileGrid tiles(camera);
  const PacketWalk walk(settings.samplesPerPixel, settings.seed, settings.jitter, camera);
  for (int i = 0; i < std::max(1, repeats); ++i) {
    // The pinhole limit in bands of 16 rows (4 packets high), parallelised like the renderer.
    keepFastest(result.limit, timedSum(arena, (limitGrid.height + 15) / 16, [&](int band) {
                  return accelerator.traceRawLimit(limitGrid, band * 16, band * 16 + 16, light);
                }));
    keepFastest(result.sameRays, timedSum(arena, tiles.count(), [&](int tile) {
                  uint64_t rays = 0;
                  forEachPacket(tiles, tile, camera, walk, [&](const FilmPacket& packet) {
                    rays += accelerator.traceRawPacket(packet.rays, light);
                  });
                  return rays;
                }));
    RenderStats stats;
    render(scene, accelerator, camera, settings, &stats);
    keepFastest(result.ours, {stats.totalRays(), stats.seconds});
  }
  return result;
}

}  // namespace parallax
