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
    return forSample(pixelStream(x, y, renderSeed), sampleIndex);
  }
  // The same in two steps, for loops that reuse a pixel's stream for all its samples: the
  // pixel's part costs one mix, a sample's part one add.
  static uint64_t pixelStream(uint32_t x, uint32_t y, uint64_t renderSeed = 0) {
    const uint64_t pixel = (uint64_t(y) << 32) | x;
    return mix64(pixel ^ (renderSeed * 0xd1b54a32d192ed03ull));
  }
  static Rng forSample(uint64_t pixelStream, uint32_t sampleIndex) {
    return fromState(pixelStream + sampleOffset(sampleIndex));
  }
  static constexpr uint64_t sampleOffset(uint32_t sampleIndex) {
    return uint64_t(sampleIndex) * 0x632be59bd9b4e019ull;
  }

  // The whole generator as one number, for code that keeps sixteen of them in a SIMD array.
  uint64_t state() const { return state_; }
  static Rng fromState(uint64_t state) {
    Rng rng;
    rng.state_ = state;
    return rng;
  }

  // Moves past `count` draws without computing them: the streams stay the same whichever
  // draws a caller needs.
  void skip(uint32_t count) { state_ += uint64_t(count) * 0x9e3779b97f4a7c15ull; }

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
