// The Gaussian model (scene/gaussians.h) against independent truths: the spherical-harmonics
// basis against the standard library's spherical harmonics (std::sph_legendre), the response
// along a ray against the covariance's own inverse minimised along the ray by search, and the
// bounding radius against its defining equation.
#include "parallax/scene/gaussians.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace parallax {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The real spherical harmonic of degree l and order m with the Condon-Shortley phase, from
// std::sph_legendre (which carries the phase): sqrt(2) Y_l^|m| cos(m phi) for m > 0,
// sqrt(2) Y_l^|m| sin(|m| phi) for m < 0, Y_l^0 for m = 0; theta from +z, phi from +x.
double realSh(int l, int m, double theta, double phi) {
  const unsigned degree = unsigned(l), order = unsigned(std::abs(m));
  const double y = std::sph_legendre(degree, order, theta);
  if (m == 0) return y;
  return std::sqrt(2.0) * y * (m > 0 ? std::cos(m * phi) : std::sin(-m * phi));
}

Vec3f randomDirection(std::mt19937& rng) {
  std::normal_distribution<float> n;
  return normalize(Vec3f(n(rng), n(rng), n(rng)));
}

TEST(Gaussians, ShBasisIsTheRealSphericalHarmonicsWithTheCondonShortleyPhase) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3f d = randomDirection(rng);
    float basis[16];
    shBasis(3, d, basis);
    const double theta = std::acos(std::clamp(double(d.z), -1.0, 1.0));
    const double phi = std::atan2(double(d.y), double(d.x));
    for (int l = 0; l <= 3; ++l)
      for (int m = -l; m <= l; ++m)
        EXPECT_NEAR(basis[l * (l + 1) + m], realSh(l, m, theta, phi), 2e-6)
            << "l " << l << " m " << m << " at " << d.x << "," << d.y << "," << d.z;
  }
}

TEST(Gaussians, ShColourIsTheCoefficientsOverTheBasisPlusAHalfClampedAtZero) {
  // Degree 0: the file's DC term c shows C0 c + 1/2 from every side.
  const Vec3f dc[1] = {Vec3f(1.0f, -0.5f, -3.0f)};
  const Vec3f c = shColour(dc, 0, {0, 0, 1});
  EXPECT_NEAR(c.x, 0.28209479177387814 + 0.5, 1e-6);
  EXPECT_NEAR(c.y, -0.5 * 0.28209479177387814 + 0.5, 1e-6);
  EXPECT_EQ(c.z, 0.0f);  // clamped
  // Degree 1: a coefficient on Y_1^0 (k = 2, C1 z) brightens toward +z and darkens toward -z.
  Vec3f one[4] = {};
  one[2] = Vec3f(0.2f);
  EXPECT_NEAR(shColour(one, 1, {0, 0, 1}).x, 0.5 + 0.2 * 0.4886025119029199, 1e-6);
  EXPECT_NEAR(shColour(one, 1, {0, 0, -1}).x, 0.5 - 0.2 * 0.4886025119029199, 1e-6);
  // Only the degree asked for counts.
  EXPECT_NEAR(shColour(one, 0, {0, 0, 1}).x, 0.5, 1e-6);
}

// The squared Mahalanobis distance (x - mu)^T Sigma^-1 (x - mu) with Sigma^-1 = R S^-2 R^T built
// as a matrix in double: the second code path.
struct Mahalanobis {
  double inverse[3][3];
  Vec3d centre;
  Mahalanobis(const Vec3f& mu, const Vec3f& scale, const Quatf& q) : centre{mu.x, mu.y, mu.z} {
    const double n =
        std::sqrt(double(q.w) * q.w + double(q.x) * q.x + double(q.y) * q.y + double(q.z) * q.z);
    const double w = q.w / n, x = q.x / n, y = q.y / n, z = q.z / n;
    const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                            {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                            {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
    const double s[3] = {scale.x, scale.y, scale.z};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        inverse[i][j] = 0;
        for (int k = 0; k < 3; ++k) inverse[i][j] += r[i][k] * r[j][k] / (s[k] * s[k]);
      }
  }
  double at(const Vec3d& p) const {
    const double v[3] = {p.x - centre.x, p.y - centre.y, p.z - centre.z};
    double sum = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) sum += v[i] * inverse[i][j] * v[j];
    return sum;
  }
};

TEST(Gaussians, RayResponseIsTheLeastMahalanobisDistanceAlongTheRay) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), size(0.01f, 0.5f);
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3f mu(unit(rng), unit(rng), unit(rng));
    const Vec3f scale(size(rng), size(rng), 0.2f * size(rng));  // flat ones too, as captures have
    const Quatf q{unit(rng), unit(rng), unit(rng), unit(rng)};
    const Vec3f origin = mu + Vec3f(3 * unit(rng), 3 * unit(rng), 4.0f);
    const Vec3f direction = normalize(mu + Vec3f(0.3f * unit(rng), 0.3f * unit(rng), 0) - origin);
    const RayResponse r = gaussianRayResponse(mu, scale, q, origin, direction);
    const Mahalanobis m(mu, scale, q);
    const auto along = [&](double t) {
      return m.at(
          {origin.x + t * direction.x, origin.y + t * direction.y, origin.z + t * direction.z});
    };
    // A convex quadratic in t: golden-section search over a bracket holding the centre.
    double lo = 0, hi = 20;
    const double g = (std::sqrt(5.0) - 1) / 2;
    for (int i = 0; i < 200; ++i) {
      const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
      if (along(a) < along(b))
        hi = b;
      else
        lo = a;
    }
    const double tBest = 0.5 * (lo + hi);
    EXPECT_NEAR(r.t, tBest, 1e-3 * (1 + tBest)) << trial;
    EXPECT_NEAR(r.distanceSquared, along(tBest), 1e-3 * (1 + along(tBest))) << trial;
    EXPECT_NEAR(r.alpha(0.7f), std::min(0.99, 0.7 * std::exp(-0.5 * along(tBest))), 1e-4);
  }
}

TEST(Gaussians, ARayThroughTheCentreSeesThePeak) {
  const Vec3f mu(1, 2, 3);
  const RayResponse r = gaussianRayResponse(mu, {0.1f, 0.2f, 0.3f}, {0.9f, 0.1f, -0.3f, 0.2f},
                                            {1, 2, 10}, {0, 0, -1});
  EXPECT_NEAR(r.t, 7.0f, 1e-5);
  EXPECT_NEAR(r.distanceSquared, 0.0f, 1e-8);
  EXPECT_FLOAT_EQ(r.alpha(0.5f), 0.5f);
  EXPECT_FLOAT_EQ(r.alpha(1.0f), kMaxSplatAlpha);
}

TEST(Gaussians, TheBoundingRadiusIsWhereTheAlphaFallsToTheThreshold) {
  for (const float opacity : {0.01f, 0.1f, 0.5f, 0.99f, 1.0f}) {
    const float r = boundingRadius(opacity);
    EXPECT_NEAR(opacity * std::exp(-0.5 * double(r) * r), kMinSplatAlpha, 1e-6) << opacity;
  }
  EXPECT_EQ(boundingRadius(kMinSplatAlpha), 0.0f);
  EXPECT_EQ(boundingRadius(0.001f), 0.0f);
  EXPECT_EQ(boundingRadius(std::nanf("")), 0.0f);
}

TEST(HalfFloat, EveryFiniteHalfIsReadExactlyAndWrittenBackTheSame) {
  for (uint32_t bits = 0; bits < 0x10000u; ++bits) {
    const uint16_t half = uint16_t(bits);
    const uint32_t exponent = (bits >> 10) & 0x1fu, mantissa = bits & 0x3ffu;
    if (exponent == 0x1fu) continue;  // infinities and NaNs are never kept
    // The value by its definition: (-1)^s 2^(e - 15) (1 + m / 1024), or 2^-14 m / 1024.
    const double magnitude = exponent == 0 ? std::ldexp(double(mantissa), -24)
                                           : std::ldexp(1024.0 + mantissa, int(exponent) - 25);
    const double expected = (bits & 0x8000u) ? -magnitude : magnitude;
    ASSERT_EQ(double(fromHalf(half)), expected) << std::hex << bits;
    ASSERT_EQ(toHalf(fromHalf(half)), half) << std::hex << bits;
  }
}

TEST(HalfFloat, WritingRoundsToTheNearestTiesToEvenAndClampsBeyondTheLargest) {
  // Between 1 and 1 + 2^-10 (the next half): below, at and above the midpoint.
  EXPECT_EQ(toHalf(1.0f + 0x1p-12f), 0x3c00u);
  EXPECT_EQ(toHalf(1.0f + 0x1p-11f), 0x3c00u);  // a tie: to the even mantissa, 1
  EXPECT_EQ(toHalf(1.0f + 0x1p-11f + 0x1p-20f), 0x3c01u);
  EXPECT_EQ(toHalf(1.0f + 0x1p-10f + 0x1p-11f), 0x3c02u);  // a tie: up to the even one
  EXPECT_EQ(toHalf(0x1p-25f), 0x0000u);                    // half the smallest subnormal: even
  EXPECT_EQ(toHalf(0x1p-24f * 1.5f), 0x0002u);             // a subnormal tie: up to even
  EXPECT_EQ(toHalf(-2.0f), 0xc000u);
  EXPECT_EQ(toHalf(65504.0f), 0x7bffu);
  EXPECT_EQ(toHalf(1e9f), 0x7bffu);
  EXPECT_EQ(toHalf(-1e9f), 0xfbffu);
  // Every float in a sweep lands on one of its two neighbouring halves, the nearer.
  for (float x = 1e-6f; x < 6e4f; x *= 1.0137f) {
    const float back = fromHalf(toHalf(x));
    const uint16_t h = toHalf(x);
    const float below = fromHalf(uint16_t(h - 1)), above = fromHalf(uint16_t(h + 1));
    EXPECT_LE(std::abs(back - x), std::abs(below - x)) << x;
    EXPECT_LE(std::abs(back - x), std::abs(above - x)) << x;
  }
}

}  // namespace
}  // namespace parallax
