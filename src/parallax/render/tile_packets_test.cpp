// The packet walk: every pixel sample exactly once, its strata as film_sampler.h promises, and
// for the display camera packets of parallel rays when the jitter is shared.
#include "parallax/render/tile_packets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "parallax/camera/display_camera.h"
#include "parallax/render/display_test_support.h"
#include "parallax/render/render.h"

namespace parallax {
namespace {

DisplaySpec smallDisplay() {
  return smallDisplaySpec(150, 40);
}

// Every (pixel, sample) of the film once, and lanes outside the film inactive.
void expectEveryPixelSampleOnce(const Camera& camera, int spp, JitterSharing jitter) {
  const TileGrid grid(camera);
  const PacketWalk walk(spp, 3, jitter, camera);
  std::map<std::tuple<int, int, int>, int> seen;
  // A packet's pixels come through samples 0 .. spp-1 in a row (the renderer sums in place).
  int expectedSample = 0;
  int previousX[16] = {}, previousY[16] = {};
  for (int tile = 0; tile < grid.count(); ++tile)
    forEachPacket(grid, tile, camera, walk, [&](const FilmPacket& p) {
      EXPECT_EQ(p.sample, expectedSample);
      for (int lane = 0; lane < 16 && p.sample > 0; ++lane) {
        EXPECT_EQ(p.x[lane], previousX[lane]);
        EXPECT_EQ(p.y[lane], previousY[lane]);
      }
      expectedSample = (expectedSample + 1) % spp;
      for (int lane = 0; lane < 16; ++lane)
        previousX[lane] = p.x[lane], previousY[lane] = p.y[lane];
      for (int lane = 0; lane < 16; ++lane) {
        const bool inside = p.x[lane] < camera.width() && p.y[lane] < camera.height();
        EXPECT_EQ(p.rays.active[lane] != 0, inside);
        if (inside) ++seen[{p.x[lane], p.y[lane], p.sample}];
      }
    });
  EXPECT_EQ(seen.size(), size_t(camera.width()) * size_t(camera.height()) * size_t(spp));
  for (const auto& [key, count] : seen) EXPECT_EQ(count, 1);
}

TEST(TilePackets, EveryPixelSampleIsTracedOnce) {
  const PinholeCamera pinhole({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40.0f, 37, 21);
  expectEveryPixelSampleOnce(pinhole, 4, JitterSharing::Pixel);
  const DisplayCamera display(designDisplay(smallDisplay()), {});
  expectEveryPixelSampleOnce(display, 4, JitterSharing::Auto);
}

// True if the 16 points (scaled to [0, 4)^2) put one in each of the 4 x 4 cells, allowing for
// the float rounding of film positions near a cell's edge.
bool fillsTheStrata(const std::vector<std::pair<float, float>>& points) {
  if (points.size() != 16) return false;
  constexpr float slack = 1e-3f;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      bool found = false;
      for (const auto& [a, b] : points)
        found |= a > float(i) - slack && a < float(i + 1) + slack && b > float(j) - slack &&
                 b < float(j + 1) + slack;
      if (!found) return false;
    }
  return true;
}

TEST(TilePackets, EachPixelKeepsItsStrataWhetherOrNotJitterIsShared) {
  const DisplayCamera camera(designDisplay(smallDisplay()), {});
  const TileGrid grid(camera);
  for (JitterSharing jitter : {JitterSharing::Pixel, JitterSharing::Packet}) {
    const PacketWalk walk(16, 0, jitter, camera);
    // pixel -> its samples' (x, apertureU) and (y, apertureV), scaled to strata units.
    std::map<std::pair<int, int>, std::vector<std::pair<float, float>>> xu, yv;
    for (int tile = 0; tile < grid.count(); ++tile)
      forEachPacket(grid, tile, camera, walk, [&](const FilmPacket& p) {
        for (int lane = 0; lane < 16; ++lane) {
          if (!p.rays.active[lane]) continue;
          const float fx = p.film.x[lane] - float(p.x[lane]);
          const float fy = p.film.y[lane] - float(p.y[lane]);
          const auto key = std::make_pair(p.x[lane], p.y[lane]);
          xu[key].push_back({4 * fx, 4 * p.film.apertureU[lane]});
          yv[key].push_back({4 * fy, 4 * p.film.apertureV[lane]});
        }
      });
    // 16 samples fill the 4 x 4 strata of both pairs (film_sampler.h).
    EXPECT_EQ(xu.size(), size_t(camera.width()) * size_t(camera.height()));
    for (const auto& [pixel, points] : xu) EXPECT_TRUE(fillsTheStrata(points));
    for (const auto& [pixel, points] : yv) EXPECT_TRUE(fillsTheStrata(points));
  }
}

// Cameras that ignore the aperture coordinates (all but the display camera) get their draws
// skipped: the same film positions and the same shading streams as when they are drawn, so the
// same pictures; the display camera, which reads them, still gets them drawn.
TEST(TilePackets, SkippedApertureDrawsLeaveTheFilmAndTheStreams) {
  const DisplayDesign design = designDisplay(smallDisplay());
  const WindowCamera window({10, 0, design.viewDistanceMm}, design, {}, 150, 40, true);
  const DisplayCamera display(design, {});
  EXPECT_FALSE(window.packetShape().aperture);
  EXPECT_TRUE(display.packetShape().aperture);
  EXPECT_FALSE(PacketWalk(4, 3, JitterSharing::Auto, window).drawsAperture);
  EXPECT_TRUE(PacketWalk(4, 3, JitterSharing::Auto, display).drawsAperture);
  for (const int spp : {4, 9}) {
    const PacketWalk skipping(spp, 3, JitterSharing::Pixel, window);
    PacketWalk drawing = skipping;
    drawing.drawsAperture = true;
    const TileGrid grid(window);
    int compared = 0;
    for (int tile = 0; tile < grid.count(); ++tile)
      forEachPacket(grid, tile, window, skipping, [&](const FilmPacket& p) {
        FilmPacket drawn = p;
        samplePacket(drawing, stratificationOrder(spp), drawn);
        for (int lane = 0; lane < 16; ++lane) {
          if (!p.rays.active[lane]) continue;
          ASSERT_EQ(p.film.x[lane], drawn.film.x[lane]);
          ASSERT_EQ(p.film.y[lane], drawn.film.y[lane]);
          ASSERT_EQ(p.rngs[size_t(lane)].state(), drawn.rngs[size_t(lane)].state());
          ++compared;
        }
      });
    EXPECT_EQ(compared, 150 * 40 * spp);
  }
}

// The largest difference in horizontal slope dx/dz between the active lanes of a packet, in
// the display's frame (a default placement: display mm = scene units / width).
double widestHorizontalSpread(const Camera& camera, JitterSharing jitter) {
  const TileGrid grid(camera);
  const PacketWalk walk(16, 5, jitter, camera);
  double widest = 0.0;
  for (int tile = 0; tile < grid.count(); ++tile)
    forEachPacket(grid, tile, camera, walk, [&](const FilmPacket& p) {
      double lo = INFINITY, hi = -INFINITY;
      for (int lane = 0; lane < 16; ++lane) {
        if (!p.rays.active[lane]) continue;
        const double slope = double(p.rays.dx[lane]) / double(p.rays.dz[lane]);
        lo = std::min(lo, slope), hi = std::max(hi, slope);
      }
      widest = std::max(widest, hi - lo);
    });
  return widest;
}

TEST(TilePackets, SharedJitterKeepsADisplayPacketsRaysParallel) {
  // A display packet is one film column over 16 rows: one pixel column, one aperture. With the
  // jitter shared, every lane crosses the image layer at the same x and its aperture cell at
  // the same x, so the horizontal slopes agree (to float rounding). With independent jitter
  // they spread by up to one angular stratum: a quarter of the filter's window over the gap
  // (a quarter view, 0.25 * 0.2745 mm / 3 mm = 0.023, for the one-view box; a quarter period,
  // 0.21, for the old whole-period cell), less the jitter's own randomness.
  const DisplayDesign design = designDisplay(smallDisplay());
  const double dx = design.spec.imagePanel.pitchMm, g = design.spec.gapMm;
  for (const auto& [filter, window] :
       {std::pair{ViewFilterKind::View, dx / g},
        std::pair{ViewFilterKind::Period, design.screenPeriodMm / g}}) {
    const DisplayCamera camera(design, {}, {filter, 1.0});
    EXPECT_TRUE(camera.packetShape().shareJitter);
    EXPECT_LT(widestHorizontalSpread(camera, JitterSharing::Auto), 1e-5);
    const double quarter = 0.25 * window;
    const double independent = widestHorizontalSpread(camera, JitterSharing::Pixel);
    EXPECT_GT(independent, 0.5 * quarter) << viewFilterName(filter);
    EXPECT_LT(independent, 1.3 * quarter) << viewFilterName(filter);
  }
}

TEST(TilePackets, SharedJitterConvergesAsIndependentJitterDoes) {
  // Sharing changes which pixels' errors are correlated, not how large each pixel's error
  // is: at 16 spp both images sit as far from a 256-spp reference, and the same image on
  // average.
  const DisplayDesign design = designDisplay(smallDisplay());
  Scene scene = defaultScene();
  scene.display.width = 1.5f;
  const Accelerator accel(scene);
  const DisplayCamera camera(design, scene.display);
  RenderSettings settings;
  settings.samplesPerPixel = 256;
  settings.jitter = JitterSharing::Pixel;
  settings.seed = 11;
  const Image reference = render(scene, accel, camera, settings);
  settings.samplesPerPixel = 16;
  settings.seed = 0;
  const Image independent = render(scene, accel, camera, settings);
  settings.jitter = JitterSharing::Packet;
  const Image shared = render(scene, accel, camera, settings);
  double errorIndependent = 0, errorShared = 0, meanReference = 0, meanShared = 0;
  for (size_t i = 0; i < reference.pixels().size(); ++i) {
    const Vec3f r = reference.pixels()[i];
    const Vec3f a = independent.pixels()[i] - r, b = shared.pixels()[i] - r;
    errorIndependent += dot(a, a), errorShared += dot(b, b);
    meanReference += r.x + r.y + r.z;
    meanShared += shared.pixels()[i].x + shared.pixels()[i].y + shared.pixels()[i].z;
  }
  EXPECT_GT(errorShared, 0.0);
  EXPECT_LT(errorShared, 1.25 * errorIndependent);
  EXPECT_GT(errorShared, 0.8 * errorIndependent);
  EXPECT_NEAR(meanShared / meanReference, 1.0, 0.01);
}

TEST(TilePackets, DisplayImageIsTheSameForAnyThreadCount) {
  const DisplayCamera camera(designDisplay(smallDisplay()), {});
  const Scene scene = defaultScene();
  const Accelerator accel(scene);
  RenderSettings one, two;
  one.samplesPerPixel = two.samplesPerPixel = 4;
  one.threads = 1, two.threads = 2;
  EXPECT_EQ(render(scene, accel, camera, one).pixels(), render(scene, accel, camera, two).pixels());
}

}  // namespace
}  // namespace parallax

namespace parallax {
namespace {

// The progressive order (adaptive sampling): a permutation of the sample indices whose groups
// of n are Latin sets, one sample in every x stratum (i mod n) and every angular stratum
// (i div n), so any whole number of groups is stratified.
TEST(TilePackets, ProgressiveOrderIsAPermutationOfLatinGroups) {
  const DisplayCamera camera(designDisplay(smallDisplay()), {});
  for (int n : {2, 3, 4, 5}) {
    const PacketWalk walk(n * n, 1, JitterSharing::Auto, camera, true);
    ASSERT_EQ(walk.groupSize, n);
    std::vector<int> sorted = walk.order;
    std::sort(sorted.begin(), sorted.end());
    for (int i = 0; i < n * n; ++i) EXPECT_EQ(sorted[size_t(i)], i);
    for (int group = 0; group < n; ++group) {
      std::set<int> xs, us;
      for (int k = 0; k < n; ++k) {
        const int index = walk.order[size_t(group * n + k)];
        xs.insert(index % n), us.insert(index / n);
      }
      EXPECT_EQ(int(xs.size()), n) << "n " << n << " group " << group;
      EXPECT_EQ(int(us.size()), n) << "n " << n << " group " << group;
    }
  }
  const PacketWalk plain(16, 1, JitterSharing::Auto, camera);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(plain.order[size_t(i)], i);
}

}  // namespace
}  // namespace parallax
