// Where the samples of one pixel fall: spp = n*n is stratified n x n with a uniform jitter in
// each stratum; any other count is uniformly jittered; spp = 1 is the exact pixel centre (the
// un-anti-aliased baseline). The aperture dimensions are stratified the same way, shuffled
// against the pixel strata so that both stay stratified (Latin-square-style pairing).
#pragma once

#include <cmath>

#include "parallax/camera/camera.h"
#include "parallax/core/random.h"

namespace parallax {

inline int stratificationOrder(int samplesPerPixel) {
  const int n = int(std::lround(std::sqrt(double(samplesPerPixel))));
  return n * n == samplesPerPixel ? n : 0;
}

// Sample `index` of pixel (x, y); draws its jitter from `rng` (seeded for this sample).
inline FilmSample filmSample(int x, int y, int index, int samplesPerPixel, int strataOrder,
                             Rng& rng) {
  if (samplesPerPixel == 1) return {float(x) + 0.5f, float(y) + 0.5f, 0.5f, 0.5f};
  FilmSample s;
  if (strataOrder > 0) {
    const int n = strataOrder;
    const float inv = 1.0f / float(n);
    s.x = float(x) + (float(index % n) + rng.uniform()) * inv;
    s.y = float(y) + (float(index / n) + rng.uniform()) * inv;
    // Aperture strata: a fixed permutation of the pixel strata (index * (n+1) mod n*n walks
    // a different row and column for every sample when n > 1).
    const int a = (index * (n + 1) + index / n) % (n * n);
    s.apertureU = (float(a % n) + rng.uniform()) * inv;
    s.apertureV = (float(a / n) + rng.uniform()) * inv;
  } else {
    s.x = float(x) + rng.uniform();
    s.y = float(y) + rng.uniform();
    s.apertureU = rng.uniform();
    s.apertureV = rng.uniform();
  }
  return s;
}

}  // namespace parallax
