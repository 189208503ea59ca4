// Deterministic random numbers. Every pixel sample seeds its own generator from
// (pixel, sample index, stream), so an image does not depend on thread count or tile order.
#pragma once

#include <cstdint>

namespace parallax {

// SplitMix64 finaliser: a bijective 64-bit mix with full avalanche.
constexpr uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// PCG32 (O'Neill 2014): small state, good statistics, cheap to seed per sample.
class Rng {
 public:
  Rng() : Rng(0) {}
  explicit Rng(uint64_t seed, uint64_t stream = 0) : state_(0), inc_((stream << 1u) | 1u) {
    next();
    state_ += mix64(seed);
    next();
  }
  // Seed for one pixel sample of one render: the same inputs always give the same stream.
  static Rng forSample(uint32_t x, uint32_t y, uint32_t sampleIndex, uint64_t renderSeed = 0) {
    const uint64_t key = (uint64_t(x) << 32) | y;
    return Rng(mix64(key ^ mix64(renderSeed)), sampleIndex);
  }

  uint32_t next() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const auto xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    const auto rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
  }
  // Uniform in [0, 1), never 1.
  float uniform() { return float(next() >> 8) * 0x1p-24f; }

 private:
  uint64_t state_;
  uint64_t inc_;
};

}  // namespace parallax
