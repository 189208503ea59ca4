#include "parallax/render/render.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <vector>

#include "parallax/render/packet_tracer.h"
#include "parallax/render/packet_types.h"
#include "parallax/render/tile_packets.h"

namespace parallax {

namespace {

void renderTile(int tile, const TileGrid& grid, const Camera& camera, const PacketTracer& tracer,
                const PacketWalk& walk, Image& image, RenderStats& stats) {
  const int x0 = grid.x0(tile), y0 = grid.y0(tile);
  // The tile's sums per channel. Every lane of a packet lies inside the tile's rectangle, and
  // inactive lanes carry zero radiance, so all sixteen add without a branch.
  const size_t size = size_t(grid.width) * TileGrid::kRows;
  std::vector<float> sums(3 * size, 0.0f);
  float* sumR = sums.data();
  float* sumG = sumR + size;
  float* sumB = sumG + size;
  Color16 radiance, weight;
  weight.fill(1.0f);
  const int width = grid.width;
  forEachPacket(grid, tile, camera, walk, [&](FilmPacket& packet) {
    stats.cameraRays += uint64_t(packet.activeCount);
    radiance.fill(0.0f);
    tracer.trace(packet.rays, weight, packet.rngs, radiance, 0, stats);
    alignas(64) int index[16];
    PARALLAX_SIMD
    for (int lane = 0; lane < 16; ++lane)
      index[lane] = (packet.y[lane] - y0) * width + (packet.x[lane] - x0);
    for (int lane = 0; lane < 16; ++lane) {
      const size_t i = size_t(index[lane]);
      sumR[i] += radiance.r[lane], sumG[i] += radiance.g[lane], sumB[i] += radiance.b[lane];
    }
  });
  const float perSample = 1.0f / float(walk.samplesPerPixel);
  const int x1 = std::min(x0 + grid.width, grid.filmWidth);
  const int y1 = std::min(y0 + TileGrid::kRows, grid.filmHeight);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const size_t i = size_t(y - y0) * size_t(width) + size_t(x - x0);
      image.at(x, y) = Vec3f(sumR[i], sumG[i], sumB[i]) * perSample;
    }
}

}  // namespace

Image render(const Scene& scene, const Accelerator& accelerator, const Camera& camera,
             const RenderSettings& settings, RenderStats* stats, const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  Image image(camera.width(), camera.height());
  const LightSampler lights(scene);
  const PacketTracer tracer(scene, accelerator, lights);
  const TileGrid grid(camera);
  const PacketWalk walk(settings.samplesPerPixel, settings.seed, settings.jitter, camera);

  std::mutex statsMutex;
  RenderStats total;
  std::atomic<int> done{0};
  const int threads = settings.threads > 0 ? settings.threads : tbb::task_arena::automatic;
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, grid.count(), 1),
                      [&](const tbb::blocked_range<int>& range) {
                        RenderStats local;
                        for (int tile = range.begin(); tile != range.end(); ++tile) {
                          renderTile(tile, grid, camera, tracer, walk, image, local);
                          const int finished = ++done;
                          if (progress) progress(finished, grid.count());
                        }
                        const std::lock_guard lock(statsMutex);
                        total.cameraRays += local.cameraRays;
                        total.shadowRays += local.shadowRays;
                        total.secondaryRays += local.secondaryRays;
                      });
  });
  total.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats) *stats = total;
  return image;
}

}  // namespace parallax
