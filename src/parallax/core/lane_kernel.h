// Runtime ISA dispatch for the hot lane loops (docs/install.md, "Portable and native builds").
//
// A portable build compiles our code for the x86-64 baseline (SSE2), where a 16-lane loop runs
// four SSE instructions a step. The few functions that carry the render's lane loops (shading,
// light sampling, camera and barrier rays, packet set-up) are marked PARALLAX_LANE_KERNEL: GCC
// then compiles each of them three times (x86-64-v4: AVX-512; x86-64-v3: AVX2 and FMA; the
// baseline) and an ifunc resolver picks the widest the CPU runs when the program loads. What is
// inlined into a kernel is compiled with it; calls out of it stay baseline, so no AVX
// instruction can reach a CPU without AVX. A build for an AVX-512 machine (-DPARALLAX_NATIVE=ON
// there) has nothing wider to dispatch to and makes no clones; neither do clang builds (the
// fuzzers). A loop that only AVX-512's own instructions make fast (intrinsics, which a clone for
// the baseline cannot compile) is a function of its own marked target("avx512f"), named
// ...Avx512..., and called only where __builtin_cpu_supports("avx512f") said yes
// (image/box_row.cpp's stencil); tests/portable_isa_test.sh lets such names through.
#pragma once

#include <cstddef>

#include <cstdint>
#include <type_traits>

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__AVX512F__)
#define PARALLAX_LANE_KERNEL \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define PARALLAX_LANE_KERNEL
#endif

// Marks a loop over the lanes of a packet as free of loop-carried dependencies, so that the
// compiler vectorises it without proving that the arrays do not alias, and if-converts its
// selects (the modules with lane loops compile with -fopenmp-simd).
#define PARALLAX_SIMD _Pragma("omp simd")
// The same for a loop that also adds up `variable` across the lanes.
#define PARALLAX_SIMD_PRAGMA(text) _Pragma(#text)
#define PARALLAX_SIMD_SUM(variable) PARALLAX_SIMD_PRAGMA(omp simd reduction(+ : variable))

namespace parallax {

// Sixteen lanes as one value of GCC's (and clang's) vector extensions, for loops whose width
// must not be left to the vectoriser: inside an x86-64-v4 clone GCC 12 vectorises long loops
// for 256-bit registers whatever -mprefer-vector-width says, where one of these is one 512-bit
// register (two AVX2 ones, four SSE ones in the other clones). Arithmetic, comparisons (lanes
// of -1 and 0) and `mask ? a : b` work lane by lane; `convertLanes` converts between the kinds.
// Used only inside always-inline helpers, so no call passes one between functions compiled for
// different ISAs (the build turns off GCC's -Wpsabi, which warns that such a call's ABI would
// differ between the clones).
using FloatLanes16 = float __attribute__((vector_size(64)));
using IntLanes16 = int32_t __attribute__((vector_size(64)));
using HalfWordLanes16 = uint16_t __attribute__((vector_size(32)));
using FloatLanes8 = float __attribute__((vector_size(32)));
using DoubleLanes8 = double __attribute__((vector_size(64)));

// Converts lane by lane (numeric conversion, truncation toward zero for float to int); a plain
// conversion for scalars, so that helpers written once serve a float and FloatLanes16 alike.
template <class To, class From>
[[gnu::always_inline]] inline To convertLanes(From value) {
  if constexpr (std::is_arithmetic_v<From>)
    return To(value);
  else
    return __builtin_convertvector(value, To);
}

// Lanes 0-7 and 8-15 of `value` in double, for running sums that must not round in float.
[[gnu::always_inline]] inline DoubleLanes8 lowHalfInDouble(const FloatLanes16& value) {
  return __builtin_convertvector(
      FloatLanes8(__builtin_shufflevector(value, value, 0, 1, 2, 3, 4, 5, 6, 7)), DoubleLanes8);
}
[[gnu::always_inline]] inline DoubleLanes8 highHalfInDouble(const FloatLanes16& value) {
  return __builtin_convertvector(
      FloatLanes8(__builtin_shufflevector(value, value, 8, 9, 10, 11, 12, 13, 14, 15)),
      DoubleLanes8);
}

// The 16 running sums of lowHalfInDouble (lanes 0-7) and highHalfInDouble (8-15) added in lane
// order: the same total wherever the values were summed.
[[gnu::always_inline]] inline double sumInLaneOrder(const DoubleLanes8& low,
                                                    const DoubleLanes8& high) {
  double sum = 0;
  for (int l = 0; l < 8; ++l) sum += low[l];
  for (int l = 0; l < 8; ++l) sum += high[l];
  return sum;
}

// Element-wise row arithmetic over n floats (a row of Vec3f is 3 x its width of them), in the
// CPU's widest lanes: the loops over Vec3f they replace ran in 128-bit ones.
// out[k] = a[k] b[k].
void multiplyLanes(const float* a, const float* b, float* out, size_t n);
// into[k] += a[k] b[k].
void addProductsLanes(const float* a, const float* b, float* into, size_t n);
// into[k] += weight from[k].
void addScaledLanes(const float* from, float weight, float* into, size_t n);
// values[k] *= factor.
void scaleLanes(float* values, float factor, size_t n);
// The same over `pixels` RGB triples with one grey factor each: out[3 i + c] = rgb[3 i + c]
// grey[i], and into[3 i + c] += rgb[3 i + c] grey[i].
void multiplyByGreyLanes(const float* rgb, const float* grey, float* out, size_t pixels);
void addProductsByGreyLanes(const float* rgb, const float* grey, float* into, size_t pixels);
// sum_k a[k] b[k] c[k] (c null: sum_k a[k] b[k]): each product in float, summed in double in
// 4 chains of 16 running sums (value k in chain (k / 16) mod 4, lane k mod 16), added chain by
// chain in lane order: the same sum on every CPU.
double sumOfProductsLanes(const float* a, const float* b, const float* c, size_t n);

// Which version of the lane kernels this process runs: "x86-64-v4" (AVX-512), "x86-64-v3"
// (AVX2, FMA) or "x86-64" (the baseline) when they were cloned; "native" when the build was
// compiled for its machine (or a compiler without clones). Reported by `bench`.
const char* laneKernelIsa();

}  // namespace parallax
