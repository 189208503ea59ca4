// The sRGB encoding in arithmetic that vectorises, for the loops that encode every value of
// whole images: the layer solvers' errors (layers/layer_solver.cpp) and the dense measure's
// pictures (srgbEncodeValues, image/metrics.cpp).
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>

namespace parallax {

// The sRGB encoding S(x) = 1.055 x^(5/12) - 0.055 (12.92 x up to 0.0031308; IEC 61966-2-1) of
// x clamped to [0, 1], and its slope S'(x) (0 above 1, where the clamp holds S constant), in
// arithmetic that vectorises (no table reads: they would be gathers, which GCC's generic tuning
// does not vectorise): x^(5/12) = 2^(5/12 log2 x), with
//   log2 x = e + log2 m, x = 2^e m, m in [sqrt(1/2), sqrt(2)): log2 m = 2/ln 2 atanh(t),
//     t = (m - 1)/(m + 1), |t| < 0.172, the series to t^9 (next term < 3e-9);
//   2^y = 2^n sqrt(2) e^(z ln 2), n = floor(y), z = y - n - 1/2 in [-1/2, 1/2), the series to
//     z^7 (next term < 7e-9).
// Within 2e-7 of the formula in double (tested); encodeTarget encodes targets with it too.
[[gnu::always_inline]] inline void srgbEncodeArithmetic(float x, float& encoded, float& slope) {
  const float clamped = x < 1e-30f ? 1e-30f : (x > 1.0f ? 1.0f : x);
  const uint32_t bits = std::bit_cast<uint32_t>(clamped);
  int exponent = int(bits >> 23) - 127;
  float m = std::bit_cast<float>((bits & 0x007FFFFFu) | 0x3F800000u);
  const bool high = m > 1.41421356f;
  m = high ? 0.5f * m : m;
  exponent += high ? 1 : 0;
  const float t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
  const float atanh = t * (1.0f + t2 * (1.0f / 3 + t2 * (1.0f / 5 + t2 * (1.0f / 7 + t2 / 9))));
  const float y = (5.0f / 12.0f) * (float(exponent) + 2.88539008f * atanh);  // 2 / ln 2
  const int n = int(y + 64.0f) - 64;  // floor for y > -64 (y >= -62 here)
  const float z = (y - float(n) - 0.5f) * 0.693147181f;
  const float e =
      1.0f +
      z * (1.0f +
           z * (0.5f +
                z * (1.0f / 6 + z * (1.0f / 24 + z * (1.0f / 120 + z * (1.0f / 720 + z / 5040))))));
  const float power = std::bit_cast<float>(uint32_t(n + 127) << 23) * 1.41421356f * e;
  const bool linear = clamped <= 0.0031308f;
  encoded = linear ? 12.92f * (x < 0.0f ? 0.0f : clamped) : 1.055f * power - 0.055f;
  slope = x > 1.0f ? 0.0f : (linear ? 12.92f : (1.055f * 5.0f / 12.0f) * power / clamped);
}

// out[i] = S(in[i]) (srgbEncodeArithmetic: x clamped to [0, 1]) for n values, vectorised.
void srgbEncodeValues(const float* in, float* out, size_t n);

}  // namespace parallax
