#include "parallax/render/bench.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "parallax/core/parallel.h"
#include "parallax/render/display_render.h"
#include "parallax/render/light_sampler.h"
#include "parallax/render/quilt.h"
#include "parallax/render/tile_packets.h"

namespace parallax {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Runs count(i) for i in [0, n) over the workers, as the renderer does, and returns the summed
// counts with the wall time.
template <class Count>
RayRate timedSum(int threads, int n, const Count& count) {
  const auto start = Clock::now();
  std::mutex mutex;
  RawTraceCount total;
  parallelFor(n, threads, 1, [&](int64_t begin, int64_t end) {
    RawTraceCount local;
    for (int64_t i = begin; i != end; ++i) local += count(int(i));
    const std::lock_guard lock(mutex);
    total += local;
  });
  return {total.rays, total.primaryRays, total.primaryMisses, since(start)};
}

void keepFastest(RayRate& best, const RayRate& run) {
  if (run.seconds < best.seconds) best = run;
}

}  // namespace

BenchResult benchmark(const Scene& scene, const Accelerator& accelerator, const Camera& camera,
                      const PinholeGrid& limitGrid, const RenderSettings& settings, int repeats,
                      const std::vector<PinholeGrid>& viewGrids) {
  BenchResult result;
  result.packetWidth = accelerator.packetWidth();
  result.nativePacketWidth = accelerator.nativePacketWidth();
  result.workers = workerCount(settings.threads);
  const double never = std::numeric_limits<double>::infinity();
  result.viewsLimit.seconds = viewGrids.empty() ? 0.0 : never;
  result.ours.seconds = result.limit.seconds = result.sameRays.seconds =
      result.embreeAlone.seconds = result.embreeOnOurs.seconds = never;
  const TileRenderer renderer(scene, accelerator, camera, settings);
  Image scratch(camera.width(), camera.height());
  const Vec3f light = LightSampler(scene).representativePoint(limitGrid.eye);
  std::vector<Vec3f> viewLights;
  for (const PinholeGrid& grid : viewGrids)
    viewLights.push_back(LightSampler(scene).representativePoint(grid.eye));
  const TileGrid tiles(camera);
  const PacketWalk walk(settings.samplesPerPixel, settings.seed, settings.jitter, camera);
  for (int i = 0; i < std::max(1, repeats); ++i) {
    // The pinhole limit in bands of 16 rows (4 packets high), parallelised like the renderer.
    keepFastest(result.limit,
                timedSum(settings.threads, (limitGrid.height + 15) / 16, [&](int band) {
                  return accelerator.traceRawLimit(limitGrid, band * 16, band * 16 + 16, light);
                }));
    if (!viewGrids.empty()) {
      // Each view in bands of 16 rows, all views' bands over the workers.
      const int bands = (viewGrids.front().height + 15) / 16;
      keepFastest(result.viewsLimit,
                  timedSum(settings.threads, bands * int(viewGrids.size()), [&](int index) {
                    const PinholeGrid& grid = viewGrids[size_t(index / bands)];
                    const int band = index % bands;
                    return accelerator.traceRawLimit(grid, band * 16, band * 16 + 16,
                                                     viewLights[size_t(index / bands)]);
                  }));
    }
    keepFastest(result.sameRays, timedSum(settings.threads, tiles.count(), [&](int tile) {
                  RawTraceCount count;
                  forEachPacket(tiles, tile, camera, walk, [&](const FilmPacket& packet) {
                    count += accelerator.traceRawPacket(packet.rays, light);
                  });
                  return count;
                }));
    // Embree alone: a tile's packets first (untimed), then only their tracing on the clock.
    std::atomic<int64_t> embreeNanoseconds{0};
    RayRate alone = timedSum(settings.threads, tiles.count(), [&](int tile) {
      std::vector<RayPacket16> packets;
      forEachPacket(tiles, tile, camera, walk,
                    [&](const FilmPacket& packet) { packets.push_back(packet.rays); });
      RawTraceCount count;
      const auto start = Clock::now();
      for (const RayPacket16& rays : packets) count += accelerator.traceRawPacket(rays, light);
      embreeNanoseconds +=
          std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start).count();
      return count;
    });
    alone.seconds = double(embreeNanoseconds.load()) * 1e-9 / double(result.workers);
    keepFastest(result.embreeAlone, alone);
    RenderStats stats;
    render(scene, accelerator, camera, settings, &stats);
    keepFastest(result.ours,
                {stats.totalRays(), stats.cameraRays, stats.cameraMisses, stats.seconds});
    // Embree on the renderer's own rays: each tile rendered with its packets logged (untimed),
    // then the log traced again on the clock.
    std::atomic<int64_t> replayNanoseconds{0};
    RayRate replayed = timedSum(settings.threads, renderer.tileCount(), [&](int tile) {
      PacketLog log;
      RenderStats tileStats;
      {
        const ScopedPacketLog open(log);
        renderer.renderTile(tile, scratch, tileStats);
      }
      const auto start = Clock::now();
      const RawTraceCount count = accelerator.replay(log);
      replayNanoseconds +=
          std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start).count();
      return count;
    });
    replayed.seconds = double(replayNanoseconds.load()) * 1e-9 / double(result.workers);
    keepFastest(result.embreeOnOurs, replayed);
  }
  return result;
}

namespace {

QuiltLayout deviceQuilt(const LenticularDesign& design, int& tileWidth, int& tileHeight) {
  const QuiltFormat& q = design.calibration.quilt;
  QuiltLayout layout;
  layout.columns = q.columns, layout.rows = q.rows;
  layout.aspect = design.widthMm / design.heightMm;
  tileWidth = q.tileWidth(), tileHeight = q.tileHeight();
  return layout;
}

}  // namespace

bool hasQuiltRoute(const DisplayModel& display) {
  return display.lenticularDesign() != nullptr;
}

double quiltRouteBytes(const DisplayModel& display) {
  const LenticularDesign* design = display.lenticularDesign();
  if (!design) return 0.0;
  const QuiltFormat& q = design->calibration.quilt;
  const FilmLayout film = display.film();
  // The float quilt and its views (RGB floats), and the panel picture twice (both routes).
  return 2.0 * 12.0 * double(q.width) * q.height + 2.0 * 12.0 * film.panelWidth * film.panelHeight;
}

QuiltRouteTimes benchmarkQuiltRoute(const Scene& scene, const Accelerator& accelerator,
                                    const DisplayModel& display, const RenderSettings& settings,
                                    int repeats) {
  const LenticularDesign* design = display.lenticularDesign();
  if (!design) throw std::invalid_argument("the quilt route is timed on lenticular displays only");
  QuiltRouteTimes times;
  const QuiltLayout layout = deviceQuilt(*design, times.tileWidth, times.tileHeight);
  times.views = layout.views();
  const double never = std::numeric_limits<double>::infinity();
  times.direct = times.quilt = times.interlace = never;
  for (int i = 0; i < std::max(1, repeats); ++i) {
    // Alternating, as benchmark() does, so that a slow spell of the machine hits both.
    auto start = Clock::now();
    const DisplayLayers direct = renderDisplay(scene, accelerator, display, settings);
    times.direct = std::min(times.direct, since(start));
    times.directRays = direct.stats.totalRays();
    RenderStats quiltStats;
    start = Clock::now();
    const Image quilt = renderQuilt(scene, accelerator, display, settings, layout, times.tileWidth,
                                    times.tileHeight, &quiltStats);
    times.quilt = std::min(times.quilt, since(start));
    times.quiltRays = quiltStats.totalRays();
    start = Clock::now();
    const std::vector<Image> views = splitQuilt(quilt, layout, "<bench>");
    const Image panel = interlaceQuiltLenticular(*design, views);
    times.interlace = std::min(times.interlace, since(start));
  }
  return times;
}

}  // namespace parallax
