#include "parallax/render/render.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>

#include "parallax/render/film_sampler.h"
#include "parallax/render/packet_tracer.h"

namespace parallax {

namespace {

constexpr int kTileSize = 16;  // pixels; a tile is a grid of 4x4-pixel packets

struct TileGrid {
  int columns, rows;
  int count() const { return columns * rows; }
};

// Renders one tile: for every sample index, every 4x4 block of pixels becomes one packet of
// sixteen rays, which keeps neighbouring, nearly parallel rays together.
void renderTile(int tile, const TileGrid& grid, const Camera& camera, const PacketTracer& tracer,
                const RenderSettings& settings, Image& image, RenderStats& stats) {
  const int x0 = (tile % grid.columns) * kTileSize, y0 = (tile / grid.columns) * kTileSize;
  const int x1 = std::min(x0 + kTileSize, camera.width());
  const int y1 = std::min(y0 + kTileSize, camera.height());
  const int spp = settings.samplesPerPixel;
  const int strata = stratificationOrder(spp);
  Vec3f sums[kTileSize][kTileSize] = {};

  RayPacket16 packet;
  std::array<Rng, 16> rngs;
  std::array<Vec3f, 16> radiance;
  std::array<Vec3f, 16> weight;
  weight.fill(Vec3f(1.0f));
  for (int sample = 0; sample < spp; ++sample) {
    for (int by = y0; by < y1; by += 4) {
      for (int bx = x0; bx < x1; bx += 4) {
        for (int lane = 0; lane < 16; ++lane) {
          const int x = bx + (lane & 3), y = by + (lane >> 2);
          radiance[size_t(lane)] = Vec3f(0.0f);
          if (x >= x1 || y >= y1) {
            packet.deactivate(lane);
            continue;
          }
          Rng& rng = rngs[size_t(lane)] =
              Rng::forSample(uint32_t(x), uint32_t(y), uint32_t(sample), settings.seed);
          packet.set(lane, camera.generateRay(filmSample(x, y, sample, spp, strata, rng)));
          ++stats.cameraRays;
        }
        tracer.trace(packet, weight, rngs, radiance, 0, stats);
        for (int lane = 0; lane < 16; ++lane)
          if (packet.active[lane]) sums[by - y0 + (lane >> 2)][bx - x0 + (lane & 3)] += radiance[size_t(lane)];
      }
    }
  }
  const float inv = 1.0f / float(spp);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) image.at(x, y) = sums[y - y0][x - x0] * inv;
}

}  // namespace

Image render(const Scene& scene, const Accelerator& accelerator, const Camera& camera,
             const RenderSettings& settings, RenderStats* stats,
             const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  Image image(camera.width(), camera.height());
  const LightSampler lights(scene);
  const PacketTracer tracer(scene, accelerator, lights);
  const TileGrid grid{(camera.width() + kTileSize - 1) / kTileSize,
                      (camera.height() + kTileSize - 1) / kTileSize};
  RenderSettings checked = settings;
  checked.samplesPerPixel = std::max(1, settings.samplesPerPixel);

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
                          renderTile(tile, grid, camera, tracer, checked, image, local);
                          const int finished = ++done;
                          if (progress) progress(finished, grid.count());
                        }
                        const std::lock_guard lock(statsMutex);
                        total.cameraRays += local.cameraRays;
                        total.shadowRays += local.shadowRays;
                        total.secondaryRays += local.secondaryRays;
                      });
  });
  total.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats) *stats = total;
  return image;
}

}  // namespace parallax
