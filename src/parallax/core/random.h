// Deterministic random numbers. Every pixel sample seeds its own generator from
// (pixel, sample index, stream), so an image does not depend on thread count or tile order.
#pragma once

#include <cstdint>

namespace parallax {

// SplitMix64's finaliser (Steele et al. 2014): a bijective 64-bit mix with full avalanche.
constexpr uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// A counter-based generator: draw i is mix64(seed + i * golden), SplitMix64's sequence. Seeding
// costs one mix and the draws are independent of each other, so a pixel sample's numbers come
// out in a few cycles each, with no dependency chain between them.
class Rng {
 public:
  Rng() = default;
  explicit Rng(uint64_t seed, uint64_t stream = 0) : state_(mix64(seed ^ mix64(stream))) {}
  // Generator for one pixel sample of one render: the same inputs always give the same
  // numbers, whatever thread or tile order draws them.
  static Rng forSample(uint32_t x, uint32_t y, uint32_t sampleIndex, uint64_t renderSeed = 0) {
    Rng rng;
    const uint64_t pixel = (uint64_t(y) << 32) | x;
    rng.state_ = mix64(pixel ^ (renderSeed * 0xd1b54a32d192ed03ull)) +
                 uint64_t(sampleIndex) * 0x632be59bd9b4e019ull;
    return rng;
  }

  uint32_t next() {
    state_ += 0x9e3779b97f4a7c15ull;
    return uint32_t(mix64(state_) >> 32);
  }
  // Uniform in [0, 1), never 1.
  float uniform() { return float(next() >> 8) * 0x1p-24f; }

 private:
  uint64_t state_ = 0;
};

}  // namespace parallax
