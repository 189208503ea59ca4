// The sRGB encoding in arithmetic that vectorises, for the loops that encode every value of
// whole images: the layer solvers' errors (layers/layer_numerics.cpp) and the dense measure's
// pictures (srgbEncodeValues, image/metrics.cpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "parallax/core/lane_kernel.h"

namespace parallax {

// The sRGB encoding S(x) = 1.055 x^(5/12) - 0.055 (12.92 x up to 0.0031308; IEC 61966-2-1) of
// x clamped to [0, 1], and its slope S'(x) (0 above 1, where the clamp holds S constant), in
// arithmetic that vectorises (no table reads: they would be gathers, which GCC's generic tuning
// does not vectorise), with no select on the way (GCC would evaluate both sides of one) and no
// division: x^(5/12) = 2^(5/12 log2 x), with
//   log2 x = e + log2 m, x = 2^e m, m in [sqrt(1/2), sqrt(2)): log2 m = u q(u), u = m - 1,
//     q of degree 8 interpolating log2(1 + u)/u at 9 Chebyshev nodes of u's interval (within
//     1.5e-8 of log2 m in exact arithmetic, 6.3e-8 in float);
//   2^y = 2^n sqrt(2) e^(z ln 2), n = floor(y), z = y - n - 1/2 in [-1/2, 1/2), the series to
//     z^7 (next term < 7e-9).
//   the slope's 1 / x by Newton's iteration r <- r (2 - x r) from the first guess of the
//     exponent-negating bit trick (within 1/8 of 1 / x; the error squares with each step: 6e-8
//     after three). A division of 16 lanes took a quarter of the solvers' error loop (it
//     issues once in about ten cycles here, the rest of the encoding's arithmetic two a cycle).
// Within 2e-7 of the formula in double (tested); encodeTarget encodes targets with it too.
// q's coefficients of u^0 .. u^8, and e^z's series (1/k!).
inline constexpr float kLog2Interpolant[9] = {1.442695f,     -0.721347468f, 0.480910753f,
                                              -0.360693268f, 0.287903261f,  -0.239169881f,
                                              0.216078226f,  -0.205861881f, 0.123109685f};
inline constexpr float kExp2Series[8] = {1.0f,      1.0f,       0.5f,       1.0f / 6,
                                         1.0f / 24, 1.0f / 120, 1.0f / 720, 1.0f / 5040};

// The encoding of kN values (F = float, I = int32_t) or of kN times 16 lanes (F = FloatLanes16,
// I = IntLanes16) at once, each step made for all kN before the next: the steps are a chain of
// about 40 dependent operations, and two or more chains side by side keep the core busy where
// one chain waited on its own results (the solvers' error loop ran 1.3x faster with two).
// Every value gets the same operations in the same order whatever kN and F, so the same
// results bit for bit.
template <class F, class I, int kN>
[[gnu::always_inline]] inline void srgbEncodeArithmetic(const F (&x)[kN], F (&encoded)[kN],
                                                        F (&slope)[kN]) {
  const F zero{}, one = zero + 1.0f;
  F clamped[kN], u[kN], q[kN], y[kN], z[kN], e[kN], power[kN], reciprocal[kN];
  I exponent[kN], n[kN];
  for (int i = 0; i < kN; ++i)
    clamped[i] = x[i] < 1e-30f ? zero + 1e-30f : (x[i] > 1.0f ? one : x[i]);
  // x = 2^e m with m in [sqrt(1/2), sqrt(2)): offset the bits by sqrt(1/2)'s so that the
  // exponent field is e and the mantissa field m's (integer arithmetic only: no selects).
  for (int i = 0; i < kN; ++i) {
    const I offset = __builtin_bit_cast(I, clamped[i]) - 0x3F3504F3;
    exponent[i] = offset >> 23;
    u[i] = __builtin_bit_cast(F, I((offset & 0x007FFFFF) + 0x3F3504F3)) - 1.0f;
    q[i] = zero + kLog2Interpolant[8];
  }
  for (int k = 7; k >= 0; --k)
    for (int i = 0; i < kN; ++i) q[i] = q[i] * u[i] + kLog2Interpolant[k];
  for (int i = 0; i < kN; ++i) {
    y[i] = (5.0f / 12.0f) * (convertLanes<F>(exponent[i]) + u[i] * q[i]);
    n[i] = convertLanes<I>(y[i] + 64.0f) - 64;  // floor for y > -64 (y >= -62 here)
    z[i] = (y[i] - convertLanes<F>(n[i]) - 0.5f) * 0.693147181f;
    e[i] = zero + kExp2Series[7];
  }
  for (int k = 6; k >= 0; --k)
    for (int i = 0; i < kN; ++i) e[i] = e[i] * z[i] + kExp2Series[k];
  for (int i = 0; i < kN; ++i) {
    power[i] = __builtin_bit_cast(F, I((n[i] + 127) << 23)) * 1.41421356f * e[i];
    const auto linear = clamped[i] <= 0.0031308f;
    encoded[i] = linear ? 12.92f * (x[i] < 0.0f ? zero : clamped[i]) : 1.055f * power[i] - 0.055f;
    reciprocal[i] = __builtin_bit_cast(F, I(0x7EF311C3 - __builtin_bit_cast(I, clamped[i])));
  }
  for (int step = 0; step < 3; ++step)
    for (int i = 0; i < kN; ++i)
      reciprocal[i] = reciprocal[i] * (2.0f - clamped[i] * reciprocal[i]);
  for (int i = 0; i < kN; ++i)
    slope[i] = x[i] > 1.0f ? zero
                           : (clamped[i] <= 0.0031308f
                                  ? zero + 12.92f
                                  : (1.055f * 5.0f / 12.0f) * power[i] * reciprocal[i]);
}

// One value, or 16 lanes.
template <class F, class I>
[[gnu::always_inline]] inline void srgbEncodeArithmetic(F x, F& encoded, F& slope) {
  const F in[1] = {x};
  F out[1], outSlope[1];
  srgbEncodeArithmetic<F, I, 1>(in, out, outSlope);
  encoded = out[0], slope = outSlope[0];
}

[[gnu::always_inline]] inline void srgbEncodeArithmetic(float x, float& encoded, float& slope) {
  srgbEncodeArithmetic<float, int32_t>(x, encoded, slope);
}

// out[i] = S(in[i]) (srgbEncodeArithmetic: x clamped to [0, 1]) for n values, vectorised.
void srgbEncodeValues(const float* in, float* out, size_t n);

}  // namespace parallax
