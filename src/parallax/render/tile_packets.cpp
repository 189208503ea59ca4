#include "parallax/render/tile_packets.h"

#include "parallax/core/lane_kernel.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

#include "parallax/render/packet_types.h"

namespace parallax {

TileGrid::TileGrid(const Camera& camera)
    : shape(camera.packetShape()), filmWidth(camera.width()), filmHeight(camera.height()) {
  if (shape.columns * shape.rows != 16 || kRows % shape.rows != 0 || shape.stride < 1)
    throw std::logic_error("packet shape must be 16 lanes, its rows dividing a tile's 16");
  // At least 16 columns per tile, so that a tile is worth a task.
  const int footprint = shape.columns * shape.stride;
  width = footprint * std::max(1, (16 + footprint - 1) / footprint);
  columns = (filmWidth + width - 1) / width;
  rows = (filmHeight + kRows - 1) / kRows;
}

PacketWalk::PacketWalk(int spp, uint64_t renderSeed, JitterSharing jitter, const Camera& camera,
                       bool progressive)
    : samplesPerPixel(std::max(1, spp)),
      seed(renderSeed),
      shareJitter(jitter == JitterSharing::Packet ||
                  (jitter == JitterSharing::Auto && camera.packetShape().shareJitter)),
      drawsAperture(camera.packetShape().aperture) {
  const int n = stratificationOrder(samplesPerPixel);
  groupSize = n > 0 ? n : samplesPerPixel;
  if (!progressive || n <= 1) {
    for (int i = 0; i < samplesPerPixel; ++i) order.push_back(i);
    return;
  }
  // Shifts: 0, n/2, then the others in increasing order.
  std::vector<int> shifts{0};
  if (n / 2 != 0) shifts.push_back(n / 2);
  for (int s = 1; s < n; ++s)
    if (s != n / 2) shifts.push_back(s);
  for (int shift : shifts)
    for (int x = 0; x < n; ++x) order.push_back(((x + shift) % n) * n + x);
}

PARALLAX_LANE_KERNEL void samplePacket(const PacketWalk& walk, int strata, FilmPacket& packet) {
  // Plain local arrays and simple lane loops: they vectorise (64-bit multiplies included), which
  // matters because a packet draws 80 random numbers for 16 rays that Embree traces in a few
  // nanoseconds each.
  alignas(64) uint64_t state[16];
  alignas(64) int px[16], py[16];
  for (int lane = 0; lane < 16; ++lane) px[lane] = packet.x[lane], py[lane] = packet.y[lane];
  const uint32_t sample = uint32_t(packet.sample);
  const uint64_t seed = walk.seed;
  const uint64_t offset = Rng::sampleOffset(sample);
  for (int lane = 0; lane < 16; ++lane) state[lane] = packet.pixelStream[lane] + offset;
  FilmSamples16& film = packet.film;
  if (walk.samplesPerPixel == 1) {
    for (int lane = 0; lane < 16; ++lane) {
      packet.rngs[size_t(lane)] = Rng::fromState(state[lane]);
      film.x[lane] = float(px[lane]) + 0.5f, film.y[lane] = float(py[lane]) + 0.5f;
      film.apertureU[lane] = film.apertureV[lane] = 0.5f;
    }
    return;
  }
  // Stratum of this sample index (film_sampler.h): x and apertureV by index mod n, y and
  // apertureU by index div n; a uniform jitter within it (within the whole pixel and cell when
  // spp is not a square).
  const float inv = strata > 0 ? 1.0f / float(strata) : 1.0f;
  const float sx = strata > 0 ? float(packet.sample % strata) : 0.0f;
  const float sy = strata > 0 ? float(packet.sample / strata) : 0.0f;
  // The packet's shared stream is keyed by its first lane's pixel, on a stream of its own.
  Rng shared = Rng::forSample(uint32_t(px[0]), uint32_t(py[0]), sample, ~seed);
  const bool share = walk.shareJitter;
  const float sharedX = shared.uniform(), sharedU = shared.uniform(), sharedV = shared.uniform();
  // Four draws per lane, of which a shared packet needs only y's; skipping the rest keeps a
  // lane's shading stream the same either way.
  alignas(64) float jx[16], jy[16], ju[16], jv[16];
  if (share) {
    PARALLAX_SIMD
    for (int lane = 0; lane < 16; ++lane) {
      Rng rng = Rng::fromState(state[lane]);
      rng.skip(1);
      jy[lane] = rng.uniform();
      rng.skip(2);
      state[lane] = rng.state();
      jx[lane] = sharedX, ju[lane] = sharedU, jv[lane] = sharedV;
    }
  } else if (walk.drawsAperture) {
    PARALLAX_SIMD
    for (int lane = 0; lane < 16; ++lane) {
      Rng rng = Rng::fromState(state[lane]);
      jx[lane] = rng.uniform(), jy[lane] = rng.uniform();
      ju[lane] = rng.uniform(), jv[lane] = rng.uniform();
      state[lane] = rng.state();
    }
  } else {
    // Half the draws (each two 64-bit multiplies a lane: a few percent of an ideal view's
    // render), the streams the same.
    PARALLAX_SIMD
    for (int lane = 0; lane < 16; ++lane) {
      Rng rng = Rng::fromState(state[lane]);
      jx[lane] = rng.uniform(), jy[lane] = rng.uniform();
      rng.skip(2);
      ju[lane] = jv[lane] = 0.5f;
      state[lane] = rng.state();
    }
  }
  alignas(64) float x[16], y[16], u[16], v[16];
  PARALLAX_SIMD
  for (int lane = 0; lane < 16; ++lane) {
    // In float, px + (a jitter just below 1) can round up to px + 1, the next pixel (and, for
    // the display camera, the next view's ray); the largest float below px + 1 stays inside.
    // (px + 1 >= 1: its bits less one are that float, without a call to nextafter per lane.)
    x[lane] = std::min(float(px[lane]) + (sx + jx[lane]) * inv,
                       std::bit_cast<float>(std::bit_cast<uint32_t>(float(px[lane] + 1)) - 1u));
    y[lane] = std::min(float(py[lane]) + (sy + jy[lane]) * inv,
                       std::bit_cast<float>(std::bit_cast<uint32_t>(float(py[lane] + 1)) - 1u));
    u[lane] = (sy + ju[lane]) * inv;
    v[lane] = (sx + jv[lane]) * inv;
  }
  for (int lane = 0; lane < 16; ++lane) {
    packet.rngs[size_t(lane)] = Rng::fromState(state[lane]);
    film.x[lane] = x[lane], film.y[lane] = y[lane];
    film.apertureU[lane] = u[lane], film.apertureV[lane] = v[lane];
  }
}

}  // namespace parallax
