#include "parallax/core/lane_kernel.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace parallax {
namespace {

// The CPU's feature flags as the kernel reports them: a truth independent of GCC's cpuid code.
std::set<std::string> cpuFlags() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line))
    if (line.rfind("flags", 0) == 0) {
      std::istringstream words(line.substr(line.find(':') + 1));
      std::set<std::string> flags;
      for (std::string word; words >> word;) flags.insert(word);
      return flags;
    }
  return {};
}

bool hasAll(const std::set<std::string>& flags, std::initializer_list<const char*> wanted) {
  for (const char* flag : wanted)
    if (!flags.count(flag)) return false;
  return true;
}

TEST(LaneKernel, ReportsTheWidestLevelTheCpuHas) {
  const std::set<std::string> flags = cpuFlags();
  if (flags.empty()) GTEST_SKIP() << "no /proc/cpuinfo flags on this system";
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__AVX512F__)
  // The x86-64 psABI's levels: v3 adds AVX, AVX2, BMI1/2, F16C, FMA, LZCNT, MOVBE to v2's
  // SSE4.2 and POPCNT; v4 adds AVX-512 F, BW, CD, DQ and VL.
  // LZCNT (v3) is left out: Linux lists it as "abm", which some hypervisors' CPU models hide
  // from /proc/cpuinfo while CPUID, which GCC's dispatcher reads, reports it (seen on a CI
  // machine with AVX-512 whose flags lacked "abm").
  const bool v3 = hasAll(flags, {"avx", "avx2", "bmi1", "bmi2", "f16c", "fma", "movbe", "sse4_2",
                                 "popcnt", "ssse3", "cx16"});
  const bool v4 = v3 && hasAll(flags, {"avx512f", "avx512bw", "avx512cd", "avx512dq", "avx512vl"});
  EXPECT_STREQ(laneKernelIsa(), v4 ? "x86-64-v4" : v3 ? "x86-64-v3" : "x86-64");
#else
  EXPECT_STREQ(laneKernelIsa(), "native");
#endif
}

// The row kernels against their scalar definitions, for every remainder of 16 and from an
// odd offset (rows of Vec3f start anywhere): multiplications and single additions are exact in
// IEEE arithmetic, so the lanes give the same bits; a product added may be fused (one rounding
// fewer), so within an ulp of the sum.
float anUlp(float value) {
  return 2.4e-7f * std::max(1.0f, std::abs(value));
}

TEST(LaneKernel, RowArithmeticIsTheScalarLoop) {
  std::vector<float> a(160), b(160);
  for (size_t k = 0; k < a.size(); ++k)
    a[k] = 0.37f * float(k % 13) - 1.1f, b[k] = 0.011f * float((k * 7) % 17) + 0.3f;
  // Up to 130 floats: the grey kernels' 16-pixel steps (48 floats) twice, and their tails.
  for (size_t n = 0; n <= 130; ++n) {
    const float* x = a.data() + 1;
    const float* y = b.data() + 3;
    std::vector<float> out(n + 1, -7.0f), products(n + 1, 0.5f), scaled(n + 1, 0.25f),
        factors(x, x + n + 1);
    multiplyLanes(x, y, out.data(), n);
    addProductsLanes(x, y, products.data(), n);
    addScaledLanes(x, 0.3f, scaled.data(), n);
    scaleLanes(factors.data(), 1.7f, n);
    for (size_t k = 0; k < n; ++k) {
      EXPECT_EQ(out[k], x[k] * y[k]) << n;
      EXPECT_NEAR(products[k], 0.5f + x[k] * y[k], anUlp(0.5f + x[k] * y[k])) << n;
      EXPECT_NEAR(scaled[k], 0.25f + 0.3f * x[k], anUlp(0.25f + 0.3f * x[k])) << n;
      EXPECT_EQ(factors[k], x[k] * 1.7f) << n;
    }
    // With a grey factor per RGB triple (n / 3 of them).
    std::vector<float> byGrey(n + 1, -7.0f), productsByGrey(n + 1, 0.5f);
    multiplyByGreyLanes(x, y, byGrey.data(), n / 3);
    addProductsByGreyLanes(x, y, productsByGrey.data(), n / 3);
    for (size_t k = 0; k < n / 3 * 3; ++k) {
      EXPECT_EQ(byGrey[k], x[k] * y[k / 3]) << n;
      EXPECT_NEAR(productsByGrey[k], 0.5f + x[k] * y[k / 3], anUlp(0.5f + x[k] * y[k / 3])) << n;
    }
    EXPECT_EQ(byGrey[n / 3 * 3], -7.0f);
    EXPECT_EQ(productsByGrey[n / 3 * 3], 0.5f);
    // Nothing past n is written.
    EXPECT_EQ(out[n], -7.0f);
    EXPECT_EQ(products[n], 0.5f);
    EXPECT_EQ(scaled[n], 0.25f);
    EXPECT_EQ(factors[n], x[n]);
  }
}

// The sums of products against the same products summed in double in the kernel's order (value
// k in chain k / 16 mod 4 and lane k mod 16; each chain's lanes in order, then the chains): the
// same double, for every remainder of 64, from odd offsets.
TEST(LaneKernel, SumsOfProductsAreTheLaneOrderedSums) {
  std::vector<float> a(150), b(150), c(150);
  for (size_t k = 0; k < a.size(); ++k)
    a[k] = 0.37f * float(k % 13) - 1.1f, b[k] = 0.011f * float((k * 7) % 17) + 0.3f,
    c[k] = 1.0f / float(k + 3);
  for (size_t n = 0; n <= 140; ++n) {
    const float *x = a.data() + 1, *y = b.data() + 3, *z = c.data() + 5;
    double lanes2[4][16] = {}, lanes3[4][16] = {};
    for (size_t k = 0; k < n; ++k) {
      lanes2[k / 16 % 4][k % 16] += double(x[k] * y[k]);
      lanes3[k / 16 % 4][k % 16] += double(x[k] * y[k] * z[k]);
    }
    double two = 0, three = 0;
    for (int chain = 0; chain < 4; ++chain) {
      double chain2 = 0, chain3 = 0;
      for (int l = 0; l < 16; ++l) chain2 += lanes2[chain][l], chain3 += lanes3[chain][l];
      two += chain2, three += chain3;
    }
    EXPECT_EQ(sumOfProductsLanes(x, y, nullptr, n), two) << n;
    EXPECT_EQ(sumOfProductsLanes(x, y, z, n), three) << n;
  }
}

}  // namespace
}  // namespace parallax
