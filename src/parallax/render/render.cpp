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

// A packet's pixels come through all their samples in a row (tile_packets.h), so each lane
// adds its samples' radiance up in the packet itself, and the pixel is written once, after the
// last sample.
void renderTile(int tile, const TileGrid& grid, const Camera& camera, const PacketTracer& tracer,
                const PacketWalk& walk, Image& image, RenderStats& stats) {
  Color16 sum, weight;
  sum.fill(0.0f);
  weight.fill(1.0f);
  const int last = walk.samplesPerPixel - 1;
  const float perSample = 1.0f / float(walk.samplesPerPixel);
  forEachPacket(grid, tile, camera, walk, [&](FilmPacket& packet) {
    stats.cameraRays += uint64_t(packet.activeCount);
    tracer.trace(packet.rays, weight, packet.rngs, sum, 0, stats);
    if (packet.sample != last) return;
    for (int lane = 0; lane < 16; ++lane)
      if (packet.rays.active[lane])
        image.at(packet.x[lane], packet.y[lane]) = sum.at(lane) * perSample;
    sum.fill(0.0f);
  });
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
