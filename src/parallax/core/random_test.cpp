#include "parallax/core/random.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace parallax {
namespace {

TEST(Rng, SameSeedSameStream) {
  Rng a = Rng::forSample(3, 4, 5), b = Rng::forSample(3, 4, 5);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.next(), b.next());
}

TEST(Rng, NeighbouringSamplesDiffer) {
  Rng a = Rng::forSample(3, 4, 5), b = Rng::forSample(3, 4, 6), c = Rng::forSample(4, 3, 5);
  const uint32_t x = a.next();
  EXPECT_NE(x, b.next());
  EXPECT_NE(x, c.next());
}

TEST(Rng, UniformIsUniform) {
  // Chi-square over 16 bins for 64k draws; the 0.999 quantile for 15 d.o.f. is 37.7.
  Rng rng(42);
  std::vector<int> bins(16, 0);
  const int n = 1 << 16;
  for (int i = 0; i < n; ++i) {
    const float u = rng.uniform();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    ++bins[size_t(u * 16)];
  }
  double chi2 = 0;
  for (int b : bins) chi2 += std::pow(b - n / 16.0, 2) / (n / 16.0);
  EXPECT_LT(chi2, 37.7);
}

TEST(Rng, PixelSeedsAreNotCorrelated) {
  // First draws of 4096 neighbouring pixels must look uniform too.
  std::vector<int> bins(16, 0);
  for (uint32_t y = 0; y < 64; ++y)
    for (uint32_t x = 0; x < 64; ++x) ++bins[size_t(Rng::forSample(x, y, 0).uniform() * 16)];
  double chi2 = 0;
  for (int b : bins) chi2 += std::pow(b - 256.0, 2) / 256.0;
  EXPECT_LT(chi2, 37.7);
}

}  // namespace
}  // namespace parallax
