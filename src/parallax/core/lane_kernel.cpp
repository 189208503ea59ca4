#include "parallax/core/lane_kernel.h"

#include <algorithm>
#include <cstring>

namespace parallax {

// The same test GCC's ifunc resolvers make for target_clones("arch=x86-64-v4", "arch=x86-64-v3",
// "default"): the widest ISA level whose every feature the CPU has.
const char* laneKernelIsa() {
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__AVX512F__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("x86-64-v4")) return "x86-64-v4";
  if (__builtin_cpu_supports("x86-64-v3")) return "x86-64-v3";
  return "x86-64";
#else
  return "native";
#endif
}

PARALLAX_LANE_KERNEL
void multiplyLanes(const float* a, const float* b, float* out, size_t n) {
  PARALLAX_SIMD
  for (size_t k = 0; k < n; ++k) out[k] = a[k] * b[k];
}

PARALLAX_LANE_KERNEL
void addProductsLanes(const float* a, const float* b, float* into, size_t n) {
  PARALLAX_SIMD
  for (size_t k = 0; k < n; ++k) into[k] += a[k] * b[k];
}

PARALLAX_LANE_KERNEL
void addScaledLanes(const float* from, float weight, float* into, size_t n) {
  PARALLAX_SIMD
  for (size_t k = 0; k < n; ++k) into[k] += weight * from[k];
}

PARALLAX_LANE_KERNEL
void scaleLanes(float* values, float factor, size_t n) {
  PARALLAX_SIMD
  for (size_t k = 0; k < n; ++k) values[k] *= factor;
}

namespace {

// 16 RGB pixels' grey factors (one a pixel) spread over their 48 floats: three vectors of 16,
// [g0 g0 g0 g1 g1 g1 g2 ...], each one permutation of the 16 greys (where a loop over the pixels
// left to the vectoriser split the colours into three planes and back: twelve permutations).
struct GreyTriples {
  FloatLanes16 first, second, third;
};
[[gnu::always_inline]] inline GreyTriples greyTriples(const float* grey) {
  FloatLanes16 g;
  std::memcpy(&g, grey, sizeof(g));
  return {__builtin_shufflevector(g, g, 0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4, 5),
          __builtin_shufflevector(g, g, 5, 5, 6, 6, 6, 7, 7, 7, 8, 8, 8, 9, 9, 9, 10, 10),
          __builtin_shufflevector(g, g, 10, 11, 11, 11, 12, 12, 12, 13, 13, 13, 14, 14, 14, 15, 15,
                                  15)};
}

// into[k] = rgb[k] spread[k] (kAdd: += instead) for the 48 floats of 16 pixels.
template <bool kAdd>
[[gnu::always_inline]] inline void greyStep(const float* rgb, const float* grey, float* into) {
  const GreyTriples spread = greyTriples(grey);
  const FloatLanes16* factors[3] = {&spread.first, &spread.second, &spread.third};
  for (int part = 0; part < 3; ++part) {
    FloatLanes16 values, result;
    std::memcpy(&values, rgb + 16 * part, sizeof(values));
    result = values * *factors[part];
    if constexpr (kAdd) {
      FloatLanes16 sum;
      std::memcpy(&sum, into + 16 * part, sizeof(sum));
      result += sum;
    }
    std::memcpy(into + 16 * part, &result, sizeof(result));
  }
}

template <bool kAdd>
[[gnu::always_inline]] inline void greyLoop(const float* rgb, const float* grey, float* into,
                                            size_t pixels) {
  size_t i = 0;
  for (; i + 16 <= pixels; i += 16) greyStep<kAdd>(rgb + 3 * i, grey + i, into + 3 * i);
  for (; i < pixels; ++i)
    for (int c = 0; c < 3; ++c) {
      const float product = rgb[3 * i + size_t(c)] * grey[i];
      into[3 * i + size_t(c)] = kAdd ? into[3 * i + size_t(c)] + product : product;
    }
}

}  // namespace

PARALLAX_LANE_KERNEL
void multiplyByGreyLanes(const float* rgb, const float* grey, float* out, size_t pixels) {
  greyLoop<false>(rgb, grey, out, pixels);
}

PARALLAX_LANE_KERNEL
void addProductsByGreyLanes(const float* rgb, const float* grey, float* into, size_t pixels) {
  greyLoop<true>(rgb, grey, into, pixels);
}

namespace {

template <bool kThree>
[[gnu::always_inline]] inline void addProductStep(const float* a, const float* b, const float* c,
                                                  size_t count, DoubleLanes8& low,
                                                  DoubleLanes8& high) {
  FloatLanes16 x{}, y{}, z{};
  std::memcpy(&x, a, sizeof(float) * count);
  std::memcpy(&y, b, sizeof(float) * count);
  FloatLanes16 product = x * y;
  if constexpr (kThree) {
    std::memcpy(&z, c, sizeof(float) * count);
    product *= z;
  }
  low += lowHalfInDouble(product);
  high += highHalfInDouble(product);
}

template <bool kThree>
[[gnu::always_inline]] inline double sumOfProductsLoop(const float* a, const float* b,
                                                       const float* c, size_t n) {
  // Four chains of running sums (a chain's additions wait on each other: one chain would leave
  // the loop waiting on the adder's latency).
  DoubleLanes8 low[4] = {}, high[4] = {};
  size_t k = 0;
  for (; k + 64 <= n; k += 64)
    for (int chain = 0; chain < 4; ++chain) {
      const size_t at = k + 16 * size_t(chain);
      addProductStep<kThree>(a + at, b + at, kThree ? c + at : c, 16, low[chain], high[chain]);
    }
  // The last values in zeroed lanes (adding +0 changes no sum).
  for (int chain = 0; k < n; k += 16, ++chain)
    addProductStep<kThree>(a + k, b + k, kThree ? c + k : c, std::min<size_t>(16, n - k),
                           low[chain], high[chain]);
  double sum = 0;
  for (int chain = 0; chain < 4; ++chain) sum += sumInLaneOrder(low[chain], high[chain]);
  return sum;
}

}  // namespace

PARALLAX_LANE_KERNEL
double sumOfProductsLanes(const float* a, const float* b, const float* c, size_t n) {
  return c ? sumOfProductsLoop<true>(a, b, c, n) : sumOfProductsLoop<false>(a, b, c, n);
}

}  // namespace parallax
