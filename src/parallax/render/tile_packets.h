// How the render loop cuts the film into tiles and a tile into 16-ray packets, and which film
// samples each packet carries. The renderer and the benchmark's same-rays limit both walk the
// film through this, so they trace identical rays in identical order.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "parallax/camera/camera.h"
#include "parallax/core/random.h"
#include "parallax/render/film_sampler.h"

namespace parallax {

// Where the within-stratum jitter comes from (film_sampler.h has the strata).
enum class JitterSharing {
  // What the camera asks for (PacketShape::shareJitter).
  Auto,
  // Every pixel sample draws its own: neighbouring pixels' errors are independent.
  Pixel,
  // The lanes of a packet share the horizontal film jitter and the aperture jitter (the
  // display camera's slit cell), so that its rays stay parallel and Embree traverses them as
  // one. Each pixel still gets one sample in every stratum, so its estimate is unchanged in
  // distribution; only the offsets within a stratum repeat across the packet's 16 pixels,
  // which for the display camera are 16 rows of one view.
  Packet,
};

// Tiles of `kRows` rows; a tile is a whole number of packet footprints wide.
struct TileGrid {
  static constexpr int kRows = 16;
  PacketShape shape;
  int filmWidth, filmHeight;
  int width;          // film columns per tile
  int columns, rows;  // tiles across and down

  explicit TileGrid(const Camera& camera);
  int count() const { return columns * rows; }
  int x0(int tile) const { return (tile % columns) * width; }
  int y0(int tile) const { return (tile / columns) * kRows; }
};

// One packet of the walk: its lanes' pixels and film samples, and the rays the camera made.
struct FilmPacket {
  FilmSamples16 film;
  RayPacket16 rays;          // active lanes flagged, rays generated
  std::array<Rng, 16> rngs;  // each lane's own stream for shading
  alignas(64) int x[16], y[16];
  alignas(64) uint64_t pixelStream[16];  // Rng::pixelStream of each lane's pixel
  int sample = 0;                        // the sample index (its strata and random streams)
  int pass = 0;                          // how many samples of these pixels came before this one
  int activeCount = 0;  // the visitor may turn lanes off (and lower this); at 0 the walk moves on
};

struct PacketWalk {
  int samplesPerPixel = 1;
  uint64_t seed = 0;
  bool shareJitter = false;
  // What the camera asks for (PacketShape::aperture): without it the aperture's two draws are
  // skipped, not made (film samples' apertureU and V then hold their strata's centres).
  bool drawsAperture = true;
  // The order the sample indices are visited in. Plain: 0 .. spp-1. Progressive (for adaptive
  // sampling, which may stop a pixel after any whole group): with spp = n^2, n groups of n
  // samples, group j holding sample u n + x with u = (x + s_j) mod n for x = 0 .. n-1: each
  // group is a Latin set (one sample in every x stratum and every angular stratum), so every
  // prefix of whole groups is itself stratified. The shifts s_j spread the first groups apart
  // (0, n/2, then the rest).
  std::vector<int> order;
  int groupSize = 1;  // samples per group of the progressive order (n, or spp if not square)

  // `jitter` resolved against what the camera asks for.
  PacketWalk(int samplesPerPixel, uint64_t seed, JitterSharing jitter, const Camera& camera,
             bool progressive = false);
};

// Calls visit(FilmPacket&) for every packet of `tile`: a packet's pixels through all their
// sample indices in a row (0 .. spp-1), then the next packet. Consecutive packets then revisit
// the same part of the BVH while it is in cache (worth 10-20 % of Embree's time here), and the
// renderer sums a pixel's samples in the packet itself (render.cpp relies on this order).
// Always inlined, so that its lane loops (the packet's pixels and streams) and the visitor's
// (the renderer's sums and pixel writes) are compiled with the lane kernel that calls it
// (renderTile: AVX-512 where the CPU has it) instead of for the baseline; the ideal views of a
// 1080p solve took about 3 % less.
template <class Visit>
[[gnu::always_inline]] inline void forEachPacket(const TileGrid& grid, int tile,
                                                 const Camera& camera, const PacketWalk& walk,
                                                 Visit&& visit);

// Fills the film samples and random streams of `packet` for the lanes at (packet.x, packet.y).
void samplePacket(const PacketWalk& walk, int strata, FilmPacket& packet);

template <class Visit>
[[gnu::always_inline]] inline void forEachPacket(const TileGrid& grid, int tile,
                                                 const Camera& camera, const PacketWalk& walk,
                                                 Visit&& visit) {
  const PacketShape& shape = grid.shape;
  const int x0 = grid.x0(tile), y0 = grid.y0(tile);
  const int x1 = std::min(x0 + grid.width, grid.filmWidth);
  const int y1 = std::min(y0 + TileGrid::kRows, grid.filmHeight);
  const int strata = stratificationOrder(walk.samplesPerPixel);
  const int footprint = shape.columns * shape.stride;  // film columns one packet spans
  // Each pixel's random stream, once for all its samples.
  std::vector<uint64_t> streams(size_t(grid.width) * TileGrid::kRows);
  for (int y = 0; y < TileGrid::kRows; ++y)
    for (int x = 0; x < grid.width; ++x)
      streams[size_t(y) * size_t(grid.width) + size_t(x)] =
          Rng::pixelStream(uint32_t(x0 + x), uint32_t(y0 + y), walk.seed);
  // Each lane's place in the packet's footprint, once for all packets.
  alignas(64) int laneX[16], laneY[16];
  for (int lane = 0; lane < 16; ++lane)
    laneX[lane] = (lane % shape.columns) * shape.stride, laneY[lane] = lane / shape.columns;
  FilmPacket packet;
  for (int by = y0; by < y1; by += shape.rows)
    for (int block = x0; block < x0 + grid.width; block += footprint)
      for (int offset = 0; offset < shape.stride; ++offset) {
        // Whole-array lane loops (SIMD stores that later SIMD loads can forward from).
        const int left = block + offset;
        int active = 0;
        for (int lane = 0; lane < 16; ++lane) {
          const int x = left + laneX[lane], y = by + laneY[lane];
          packet.x[lane] = x, packet.y[lane] = y;
          const bool inside = (x < x1) & (y < y1);
          packet.rays.active[lane] = inside ? -1 : 0;
          active += int(inside);
          packet.pixelStream[lane] = streams[size_t(y - y0) * size_t(grid.width) + size_t(x - x0)];
        }
        packet.activeCount = active;
        for (int pass = 0; pass < walk.samplesPerPixel && packet.activeCount > 0; ++pass) {
          packet.sample = walk.order[size_t(pass)];
          packet.pass = pass;
          samplePacket(walk, strata, packet);
          camera.generateRays16(packet.film, packet.rays);
          visit(packet);
        }
      }
}

}  // namespace parallax
