#include "parallax/core/lane_kernel.h"

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

PARALLAX_LANE_KERNEL
void multiplyByGreyLanes(const float* rgb, const float* grey, float* out, size_t pixels) {
  PARALLAX_SIMD
  for (size_t i = 0; i < pixels; ++i) {
    out[3 * i] = rgb[3 * i] * grey[i];
    out[3 * i + 1] = rgb[3 * i + 1] * grey[i];
    out[3 * i + 2] = rgb[3 * i + 2] * grey[i];
  }
}

PARALLAX_LANE_KERNEL
void addProductsByGreyLanes(const float* rgb, const float* grey, float* into, size_t pixels) {
  PARALLAX_SIMD
  for (size_t i = 0; i < pixels; ++i) {
    into[3 * i] += rgb[3 * i] * grey[i];
    into[3 * i + 1] += rgb[3 * i + 1] * grey[i];
    into[3 * i + 2] += rgb[3 * i + 2] * grey[i];
  }
}

}  // namespace parallax
