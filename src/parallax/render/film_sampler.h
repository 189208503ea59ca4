// Where the samples of one pixel fall: spp = n*n is stratified n x n with a uniform jitter in
// each stratum; any other count is uniformly jittered; spp = 1 is the exact pixel centre (the
// un-anti-aliased baseline). The aperture dimensions are stratified so that the pairs that
// span the two-plane ray space, (x, apertureU) and (y, apertureV), are each jointly n x n
// stratified, as the paper's Fig. 8 draws them: sample i has x stratum i mod n and apertureU
// stratum i div n (and y stratum i div n, apertureV stratum i mod n).
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
    s.apertureU = (float(index / n) + rng.uniform()) * inv;
    s.apertureV = (float(index % n) + rng.uniform()) * inv;
  } else {
    s.x = float(x) + rng.uniform();
    s.y = float(y) + rng.uniform();
    s.apertureU = rng.uniform();
    s.apertureV = rng.uniform();
  }
  return s;
}

}  // namespace parallax
