#include "parallax/render/render.h"

#include "parallax/core/lane_kernel.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "parallax/core/parallel.h"
#include "parallax/image/metrics.h"
#include "parallax/render/packet_tracer.h"
#include "parallax/render/packet_types.h"
#include "parallax/render/tile_packets.h"

namespace parallax {

namespace {

// A packet's pixels come through all their samples in a row (tile_packets.h), so each lane
// adds its samples' radiance up in the packet itself, and the pixel is written once, after the
// last sample. `image` holds the film's rows from `firstRow` on.
PARALLAX_LANE_KERNEL void renderTile(int tile, const TileGrid& grid, const Camera& camera,
                                     const PacketTracer& tracer, const PacketWalk& walk,
                                     const RenderSettings& settings, const Look& look, Image& image,
                                     int firstRow, RenderStats& stats) {
  Color16 sum, weight;
  sum.fill(0.0f);
  weight.fill(1.0f);
  // The film pixel: the mean of its samples, through the scene's look (exposure and view
  // transform, scene/look.h) unless it is the identity.
  const bool looks = !look.identity();
  const auto pixel = [&](int lane, int taken) {
    const Vec3f mean = sum.at(lane) * (1.0f / float(taken));
    return looks ? look.apply(mean) : mean;
  };
  // Adaptive sampling: each lane's sample luminance (sRGB-encoded), summed over the current
  // group, its squares over the first group, and the sums of its group means and their squares.
  // A lane counts its own groups: one that has stopped keeps its mean for its neighbours.
  double groupLum[16] = {}, firstSquares[16] = {}, meanSum[16] = {}, meanSquares[16] = {};
  int lanesGroups[16] = {};
  const int last = walk.samplesPerPixel - 1;
  const double threshold2 = settings.adaptiveThreshold * settings.adaptiveThreshold;
  const double neighbourLimit =
      RenderSettings::kNeighbourOverThreshold * settings.adaptiveThreshold;
  forEachPacket(grid, tile, camera, walk, [&](FilmPacket& packet) {
    if (packet.pass == 0) {
      sum.fill(0.0f);
      for (double* a : {groupLum, firstSquares, meanSum, meanSquares}) std::fill(a, a + 16, 0.0);
      std::fill(lanesGroups, lanesGroups + 16, 0);
    }
    stats.cameraRays += uint64_t(packet.activeCount);
    Color16 before;
    if (settings.adaptive) before = sum;
    tracer.trace(packet.rays, weight, packet.rngs, sum, 0, stats);
    const int taken = packet.pass + 1;
    if (settings.adaptive) {
      const int group = walk.groupSize;
      for (int lane = 0; lane < 16; ++lane) {
        if (!packet.rays.active[lane]) continue;
        const Vec3f sample = sum.at(lane) - before.at(lane);
        const double l = linearToSrgb(std::clamp(luminance(sample), 0.0f, 1.0f));
        groupLum[lane] += l;
        if (taken <= group) firstSquares[lane] += l * l;
      }
      if (taken % group == 0) {
        for (int lane = 0; lane < 16; ++lane) {
          if (!packet.rays.active[lane]) continue;
          const double groupMean = groupLum[lane] / group;
          meanSum[lane] += groupMean, meanSquares[lane] += groupMean * groupMean;
          groupLum[lane] = 0;
          ++lanesGroups[lane];
        }
      }
      // After each whole group, stop the pixels whose mean is already certain. The standard
      // error of the mean comes from the spread of the group means once there are two groups:
      // each group is stratified (a Latin set), and a stratified mean varies far less than
      // independent samples would say. After the first group only the samples' own spread
      // is known (the independent-sample estimate, which overstates the error, so errs on the
      // safe side); it needs at least 3 samples to mean something.
      const int groups = taken / group;
      const bool check =
          taken != walk.samplesPerPixel && taken % group == 0 && (groups >= 2 || group >= 3);
      if (check) {
        // A few samples can all land on one side of an edge and agree; an edge that near
        // shows in the neighbouring pixels of the packet (the lanes beside and above or
        // below), so a pixel also stops only when its neighbours' means agree with its own.
        const PacketShape& shape = grid.shape;
        double mean[16];
        for (int lane = 0; lane < 16; ++lane)
          mean[lane] = lanesGroups[lane] > 0 ? meanSum[lane] / lanesGroups[lane] : 0.0;
        for (int lane = 0; lane < 16; ++lane) {
          if (!packet.rays.active[lane]) continue;
          const double squaredError =
              groups >= 2 ? std::max(0.0, meanSquares[lane] / groups - mean[lane] * mean[lane]) /
                                (groups - 1)
                          : std::max(0.0, firstSquares[lane] / group - mean[lane] * mean[lane]) /
                                (group - 1);
          if (squaredError > threshold2) continue;
          const int column = lane % shape.columns, row = lane / shape.columns;
          bool neighboursAgree = true;
          for (const auto& [dc, dr] : {std::pair{-1, 0}, {1, 0}, {0, -1}, {0, 1}}) {
            const int c = column + dc, r = row + dr;
            if (c < 0 || c >= shape.columns || r < 0 || r >= shape.rows) continue;
            const int other = r * shape.columns + c;
            if (packet.x[other] >= grid.filmWidth || packet.y[other] >= grid.filmHeight) continue;
            neighboursAgree &= std::abs(mean[other] - mean[lane]) <= neighbourLimit;
          }
          if (!neighboursAgree) continue;
          image.at(packet.x[lane], packet.y[lane] - firstRow) = pixel(lane, taken);
          packet.rays.active[lane] = 0;
          --packet.activeCount;
        }
      }
    }
    if (packet.pass != last) return;
    if (looks) {
      for (int lane = 0; lane < 16; ++lane)
        if (packet.rays.active[lane])
          image.at(packet.x[lane], packet.y[lane] - firstRow) = pixel(lane, taken);
      return;
    }
    // The means written channel by channel from the packet's planes: pixel()'s Vec3f went
    // through the stack a float at a time and was read back whole, a stalled store forward
    // per lane (about 5 % of an ideal view's render). The same values.
    const float inverse = 1.0f / float(taken);
    for (int lane = 0; lane < 16; ++lane) {
      if (!packet.rays.active[lane]) continue;
      float* into = &image.at(packet.x[lane], packet.y[lane] - firstRow).x;
      into[0] = sum.r[lane] * inverse, into[1] = sum.g[lane] * inverse;
      into[2] = sum.b[lane] * inverse;
    }
  });
}

}  // namespace

struct TileRenderer::Impl {
  Impl(const Scene& scene, const Accelerator& accelerator, const Camera& theCamera,
       const RenderSettings& theSettings)
      : camera(theCamera),
        settings(theSettings),
        lights(scene),
        look(scene.look),
        tracer(scene, accelerator, lights, theSettings.bounces),
        grid(theCamera),
        walk(theSettings.samplesPerPixel, theSettings.seed, theSettings.jitter, theCamera,
             theSettings.adaptive) {}
  const Camera& camera;
  const RenderSettings settings;
  const LightSampler lights;
  const Look look;
  const PacketTracer tracer;
  const TileGrid grid;
  const PacketWalk walk;
};

TileRenderer::TileRenderer(const Scene& scene, const Accelerator& accelerator, const Camera& camera,
                           const RenderSettings& settings)
    : impl_(std::make_unique<Impl>(scene, accelerator, camera, settings)) {}

TileRenderer::~TileRenderer() = default;

int TileRenderer::tileCount() const {
  return impl_->grid.count();
}

int TileRenderer::tileBand(int tile) const {
  return impl_->grid.y0(tile) / TileGrid::kRows;
}

void TileRenderer::renderTile(int tile, Image& image, RenderStats& stats) const {
  renderTile(tile, image, 0, stats);
}

void TileRenderer::renderTile(int tile, Image& image, int firstRow, RenderStats& stats) const {
  const Impl& i = *impl_;
  if (image.width() != i.grid.filmWidth || i.grid.y0(tile) < firstRow ||
      std::min(i.grid.y0(tile) + TileGrid::kRows, i.grid.filmHeight) > firstRow + image.height())
    throw std::logic_error("TileRenderer: the tile's rows are not in the image");
  parallax::renderTile(tile, i.grid, i.camera, i.tracer, i.walk, i.settings, i.look, image,
                       firstRow, stats);
}

Image render(const Scene& scene, const Accelerator& accelerator, const Camera& camera,
             const RenderSettings& settings, RenderStats* stats, const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  Image image(camera.width(), camera.height());
  const TileRenderer renderer(scene, accelerator, camera, settings);
  // This process's tiles: all of them, or its bands' (RenderSettings::bandParts).
  std::vector<int> mine;
  for (int tile = 0; tile < renderer.tileCount(); ++tile)
    if (settings.rendersBand(renderer.tileBand(tile))) mine.push_back(tile);
  const int tiles = int(mine.size());
  std::mutex statsMutex;
  RenderStats total;
  std::atomic<int> done{0};
  parallelFor(tiles, settings.threads, 1, [&](int64_t begin, int64_t end) {
    RenderStats local;
    for (int64_t k = begin; k != end; ++k) {
      renderer.renderTile(mine[size_t(k)], image, local);
      const int finished = ++done;
      if (progress) progress(finished, tiles);
    }
    const std::lock_guard lock(statsMutex);
    total += local;
  });
  total.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats) *stats = total;
  return image;
}

}  // namespace parallax
