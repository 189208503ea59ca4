// The diffuser's blur: its kernel is the Gaussian's mass per cell (an analytic answer), and it
// is its own transpose (what the layer solvers' adjoints rely on).
#include "parallax/sim/diffuser.h"

#include <gtest/gtest.h>

#include <cmath>

#include "parallax/core/random.h"

namespace parallax {
namespace {

double mass(double lo, double hi, double sigma) {
  const auto cdf = [sigma](double x) { return 0.5 * std::erfc(-x / (sigma * std::sqrt(2.0))); };
  return cdf(hi) - cdf(lo);
}

TEST(Diffuser, OneCellSpreadsAsTheGaussiansMassPerCell) {
  const double pitch = 0.25, sigma = 0.4;  // 1.6 cells
  Image layer(41, 31);
  layer.at(20, 15) = Vec3f(1.0f, 2.0f, 4.0f);
  const Image out = diffuserBlurred(layer, sigma, pitch);
  const double s = sigma / pitch;
  for (int y = 10; y <= 20; ++y)
    for (int x = 15; x <= 25; ++x) {
      const int mx = x - 20, my = y - 15;
      const double expected = mass(mx - 0.5, mx + 0.5, s) * mass(my - 0.5, my + 0.5, s);
      EXPECT_NEAR(out.at(x, y).x, expected, 1e-6) << x << "," << y;
      EXPECT_NEAR(out.at(x, y).z, 4.0 * expected, 4e-6) << x << "," << y;
    }
  // Far from the edges the light is kept (to the Gaussian's mass within its 4-sigma kernel).
  double sum = 0;
  for (const Vec3f& p : out.pixels()) sum += p.y;
  EXPECT_NEAR(sum, 2.0, 1e-4);
  // Zero sigma: the layer as it is.
  EXPECT_EQ(diffuserBlurred(layer, 0.0, pitch).pixels(), layer.pixels());
}

TEST(Diffuser, IsItsOwnTranspose) {
  // <G a, b> = <a, G b> for any a, b, edges included (cells beyond the panel are dark).
  Rng rng(7);
  Image a(23, 17), b(23, 17);
  for (Image* image : {&a, &b})
    for (Vec3f& p : image->pixels()) p = {rng.uniform(), rng.uniform(), rng.uniform()};
  for (const double sigma : {0.1, 0.5, 1.3}) {
    const Image ga = diffuserBlurred(a, sigma, 0.25), gb = diffuserBlurred(b, sigma, 0.25);
    double left = 0, right = 0;
    for (size_t i = 0; i < a.pixels().size(); ++i)
      for (int c = 0; c < 3; ++c) {
        left += double(ga.pixels()[i][c]) * b.pixels()[i][c];
        right += double(a.pixels()[i][c]) * gb.pixels()[i][c];
      }
    EXPECT_NEAR(left, right, 1e-5 * std::fabs(left)) << sigma;
  }
}

}  // namespace
}  // namespace parallax
