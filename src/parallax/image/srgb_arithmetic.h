// The sRGB encoding in arithmetic that vectorises, for the loops that encode every value of
// whole images: the layer solvers' errors (layers/layer_solver.cpp) and the dense measure's
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

// The encoding of one value (F = float, I = int32_t) or of 16 lanes at once (F = FloatLanes16,
// I = IntLanes16): the same operations in the same order, so the same results bit for bit.
template <class F, class I>
[[gnu::always_inline]] inline void srgbEncodeArithmetic(F x, F& encoded, F& slope) {
  const F zero{}, one = zero + 1.0f;
  const F clamped = x < 1e-30f ? zero + 1e-30f : (x > 1.0f ? one : x);
  // x = 2^e m with m in [sqrt(1/2), sqrt(2)): offset the bits by sqrt(1/2)'s so that the
  // exponent field is e and the mantissa field m's (integer arithmetic only: no selects).
  const I offset = __builtin_bit_cast(I, clamped) - 0x3F3504F3;
  const I exponent = offset >> 23;
  const F m = __builtin_bit_cast(F, I((offset & 0x007FFFFF) + 0x3F3504F3));
  const F u = m - 1.0f;
  F q = zero + kLog2Interpolant[8];
  for (int k = 7; k >= 0; --k) q = q * u + kLog2Interpolant[k];
  const F log2m = u * q;
  const F y = (5.0f / 12.0f) * (convertLanes<F>(exponent) + log2m);
  const I n = convertLanes<I>(y + 64.0f) - 64;  // floor for y > -64 (y >= -62 here)
  const F z = (y - convertLanes<F>(n) - 0.5f) * 0.693147181f;
  F e = zero + kExp2Series[7];
  for (int k = 6; k >= 0; --k) e = e * z + kExp2Series[k];
  const F power = __builtin_bit_cast(F, I((n + 127) << 23)) * 1.41421356f * e;
  const auto linear = clamped <= 0.0031308f;
  encoded = linear ? 12.92f * (x < 0.0f ? zero : clamped) : 1.055f * power - 0.055f;
  F reciprocal = __builtin_bit_cast(F, I(0x7EF311C3 - __builtin_bit_cast(I, clamped)));
  for (int step = 0; step < 3; ++step) reciprocal = reciprocal * (2.0f - clamped * reciprocal);
  slope = x > 1.0f ? zero : (linear ? zero + 12.92f : (1.055f * 5.0f / 12.0f) * power * reciprocal);
}

[[gnu::always_inline]] inline void srgbEncodeArithmetic(float x, float& encoded, float& slope) {
  srgbEncodeArithmetic<float, int32_t>(x, encoded, slope);
}

// out[i] = S(in[i]) (srgbEncodeArithmetic: x clamped to [0, 1]) for n values, vectorised.
void srgbEncodeValues(const float* in, float* out, size_t n);

}  // namespace parallax
