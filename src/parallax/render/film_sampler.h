// Where the samples of one pixel fall: spp = n*n is stratified n x n with a uniform jitter in
// each stratum; any other count is uniformly jittered; spp = 1 is the exact pixel centre (the
// un-anti-aliased baseline). The aperture dimensions are stratified so that the pairs that
// span the two-plane ray space, (x, apertureU) and (y, apertureV), are each jointly n x n
// stratified, as the paper's Fig. 8 draws them: sample i has x stratum i mod n and apertureU
// stratum i div n (and y stratum i div n, apertureV stratum i mod n).
#pragma once

#include <cmath>

namespace parallax {

inline int stratificationOrder(int samplesPerPixel) {
  const int n = int(std::lround(std::sqrt(double(samplesPerPixel))));
  return n * n == samplesPerPixel ? n : 0;
}

}  // namespace parallax
