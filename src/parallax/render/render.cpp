#include "parallax/render/render.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <vector>

#include "parallax/image/metrics.h"
#include "parallax/render/packet_tracer.h"
#include "parallax/render/packet_types.h"
#include "parallax/render/tile_packets.h"

namespace parallax {

namespace {

// A packet's pixels come through all their samples in a row (tile_packets.h), so each lane
// adds its samples' radiance up in the packet itself, and the pixel is written once, after the
// last sample.
void renderTile(int tile, const TileGrid& grid, const Camera& camera, const PacketTracer& tracer,
                const PacketWalk& walk, const RenderSettings& settings, Image& image,
                RenderStats& stats) {
  Color16 sum, weight;
  sum.fill(0.0f);
  weight.fill(1.0f);
  // Adaptive sampling: running sums of each lane's sample luminance (sRGB-encoded) and its
  // square, for the standard error of the mean.
  double lumSum[16] = {}, lumSquares[16] = {};
  const int last = walk.samplesPerPixel - 1;
  const double threshold2 = settings.adaptiveThreshold * settings.adaptiveThreshold;
  forEachPacket(grid, tile, camera, walk, [&](FilmPacket& packet) {
    if (packet.pass == 0) {
      sum.fill(0.0f);
      std::fill(std::begin(lumSum), std::end(lumSum), 0.0);
      std::fill(std::begin(lumSquares), std::end(lumSquares), 0.0);
    }
    stats.cameraRays += uint64_t(packet.activeCount);
    Color16 before = sum;
    tracer.trace(packet.rays, weight, packet.rngs, sum, 0, stats);
    const int taken = packet.pass + 1;
    if (settings.adaptive) {
      for (int lane = 0; lane < 16; ++lane) {
        if (!packet.rays.active[lane]) continue;
        const Vec3f sample = sum.at(lane) - before.at(lane);
        const double l = linearToSrgb(std::clamp(luminance(sample), 0.0f, 1.0f));
        lumSum[lane] += l, lumSquares[lane] += l * l;
      }
      // After each whole group (of at least 3 samples, for a variance to mean something):
      // stop the pixels whose mean is already certain.
      const int firstCheck = walk.groupSize >= 3 ? walk.groupSize : 2 * walk.groupSize;
      if (taken != walk.samplesPerPixel && taken >= firstCheck && taken % walk.groupSize == 0) {
        // A few samples can all land on one side of an edge and agree; an edge that near
        // shows in the neighbouring pixels of the packet (the lanes beside and above or
        // below), so a pixel also stops only when its neighbours' means agree with its own.
        const PacketShape& shape = grid.shape;
        double mean[16];
        for (int lane = 0; lane < 16; ++lane) mean[lane] = lumSum[lane] / taken;
        for (int lane = 0; lane < 16; ++lane) {
          if (!packet.rays.active[lane]) continue;
          const double variance = std::max(0.0, lumSquares[lane] / taken - mean[lane] * mean[lane]);
          if (variance / (taken - 1) > threshold2) continue;  // squared standard error
          const int column = lane % shape.columns, row = lane / shape.columns;
          bool neighboursAgree = true;
          for (const auto& [dc, dr] : {std::pair{-1, 0}, {1, 0}, {0, -1}, {0, 1}}) {
            const int c = column + dc, r = row + dr;
            if (c < 0 || c >= shape.columns || r < 0 || r >= shape.rows) continue;
            const int other = r * shape.columns + c;
            if (packet.x[other] >= image.width() || packet.y[other] >= image.height()) continue;
            neighboursAgree &= std::abs(mean[other] - mean[lane]) <= settings.adaptiveNeighbour;
          }
          if (!neighboursAgree) continue;
          image.at(packet.x[lane], packet.y[lane]) = sum.at(lane) * (1.0f / float(taken));
          packet.rays.active[lane] = 0;
          --packet.activeCount;
        }
      }
    }
    if (packet.pass != last) return;
    for (int lane = 0; lane < 16; ++lane)
      if (packet.rays.active[lane])
        image.at(packet.x[lane], packet.y[lane]) = sum.at(lane) * (1.0f / float(taken));
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
  const PacketWalk walk(settings.samplesPerPixel, settings.seed, settings.jitter, camera,
                        settings.adaptive);

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
                          renderTile(tile, grid, camera, tracer, walk, settings, image, local);
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
