#include "parallax/render/render.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <vector>

#include "parallax/render/film_sampler.h"
#include "parallax/render/packet_tracer.h"
#include "parallax/render/packet_types.h"

namespace parallax {

namespace {

constexpr int kTileRows = 16;

// A tile is kTileRows high and 4 * stride * repeats columns wide. Its packets take four rows
// and four columns `stride` apart: neighbouring pixels for a pinhole camera (4x4 blocks), the
// same view index in four neighbouring groups for the display camera, whose rays are nearly
// parallel and so traverse the same nodes of the Embree BVH.
struct TileGrid {
  int stride, repeats, width, columns, rows;

  TileGrid(const Camera& camera)
      : stride(camera.packetStride()),
        repeats(std::max(1, (4 + stride - 1) / stride)),
        width(4 * stride * repeats),
        columns((camera.width() + width - 1) / width),
        rows((camera.height() + kTileRows - 1) / kTileRows) {}
  int count() const { return columns * rows; }
};

void renderTile(int tile, const TileGrid& grid, const Camera& camera, const PacketTracer& tracer,
                const RenderSettings& settings, Image& image, RenderStats& stats) {
  const int x0 = (tile % grid.columns) * grid.width, y0 = (tile / grid.columns) * kTileRows;
  const int x1 = std::min(x0 + grid.width, camera.width());
  const int y1 = std::min(y0 + kTileRows, camera.height());
  const int spp = settings.samplesPerPixel;
  const int strata = stratificationOrder(spp);
  std::vector<Vec3f> sums(size_t(grid.width) * kTileRows, Vec3f(0.0f));

  RayPacket16 packet;
  FilmSamples16 film;
  std::array<Rng, 16> rngs;
  Color16 radiance, weight;
  weight.fill(1.0f);
  alignas(64) int laneX[16], laneY[16];
  const float inv = strata > 0 ? 1.0f / float(strata) : 1.0f;
  for (int sample = 0; sample < spp; ++sample) {
    // Stratum of this sample index (film_sampler.h): x and apertureV by index mod n, y and
    // apertureU by index div n.
    const float sx = strata > 0 ? float(sample % strata) : 0.0f;
    const float sy = strata > 0 ? float(sample / strata) : 0.0f;
    for (int by = y0; by < y1; by += 4) {
      for (int repeat = 0; repeat < grid.repeats; ++repeat) {
        for (int offset = 0; offset < grid.stride; ++offset) {
          const int bx = x0 + repeat * 4 * grid.stride + offset;
          int active = 0;
          for (int lane = 0; lane < 16; ++lane) {
            const int x = bx + (lane & 3) * grid.stride, y = by + (lane >> 2);
            laneX[lane] = x, laneY[lane] = y;
            packet.active[lane] = (x < x1 && y < y1) ? -1 : 0;
            active += packet.active[lane] != 0;
            rngs[size_t(lane)] =
                Rng::forSample(uint32_t(x), uint32_t(y), uint32_t(sample), settings.seed);
          }
          if (spp == 1) {
            for (int lane = 0; lane < 16; ++lane) {
              film.x[lane] = float(laneX[lane]) + 0.5f, film.y[lane] = float(laneY[lane]) + 0.5f;
              film.apertureU[lane] = film.apertureV[lane] = 0.5f;
            }
          } else {
            // Uniform jitter in the stratum (or in the whole pixel when spp is not a square).
            for (int lane = 0; lane < 16; ++lane) {
              Rng& rng = rngs[size_t(lane)];
              film.x[lane] = float(laneX[lane]) + (sx + rng.uniform()) * inv;
              film.y[lane] = float(laneY[lane]) + (sy + rng.uniform()) * inv;
              film.apertureU[lane] = (sy + rng.uniform()) * inv;
              film.apertureV[lane] = (sx + rng.uniform()) * inv;
            }
          }
          camera.generateRays16(film, packet);
          stats.cameraRays += uint64_t(active);
          radiance.fill(0.0f);
          tracer.trace(packet, weight, rngs, radiance, 0, stats);
          for (int lane = 0; lane < 16; ++lane)
            if (packet.active[lane])
              sums[size_t(laneY[lane] - y0) * size_t(grid.width) + size_t(laneX[lane] - x0)] +=
                  radiance.at(lane);
        }
      }
    }
  }
  const float perSample = 1.0f / float(spp);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      image.at(x, y) = sums[size_t(y - y0) * size_t(grid.width) + size_t(x - x0)] * perSample;
}

}  // namespace

Image render(const Scene& scene, const Accelerator& accelerator, const Camera& camera,
             const RenderSettings& settings, RenderStats* stats, const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  Image image(camera.width(), camera.height());
  const LightSampler lights(scene);
  const PacketTracer tracer(scene, accelerator, lights);
  const TileGrid grid(camera);
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
  total.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats) *stats = total;
  return image;
}

}  // namespace parallax
