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
// fuzzers).
#pragma once

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

// Which version of the lane kernels this process runs: "x86-64-v4" (AVX-512), "x86-64-v3"
// (AVX2, FMA) or "x86-64" (the baseline) when they were cloned; "native" when the build was
// compiled for its machine (or a compiler without clones). Reported by `bench`.
const char* laneKernelIsa();

}  // namespace parallax
