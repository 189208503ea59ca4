#include "parallax/image/box_row.h"

#include "parallax/core/lane_kernel.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <utility>

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#define PARALLAX_SHIFTED_STENCIL 1
#endif

#include "parallax/core/error.h"

namespace parallax {

BoxRow::BoxRow(int columns, double widthPx) : columns_(columns) {
  if (!(widthPx > 0) || !std::isfinite(widthPx))
    throw InputError("", "", "the box filter's width must be positive");
  a_ = 0.5 - 0.5 * widthPx;
  b_ = 0.5 + 0.5 * widthPx;
  firstTap_ = int(std::floor(a_));
  for (int d = firstTap_; d < b_; ++d) {
    const double overlap = std::min(d + 1.0, b_) - std::max(double(d), a_);
    taps_.push_back(float(std::max(0.0, overlap) / widthPx));
  }
  interiorBegin_ = std::min(columns_, int(std::ceil(-a_)));
  interiorEnd_ = std::max(interiorBegin_, std::min(columns_, int(std::floor(columns_ - b_)) + 1));
  makeEdges();
}

double BoxRow::windowLo(int x) const {
  return std::max(0.0, x + a_);
}

double BoxRow::windowHi(int x) const {
  return std::min(double(columns_), x + b_);
}

// Output x is the integral of the box-pixel row over
// [lo_x, hi_x] = [x + a, x + b] clipped to the row, over its length. Inside the row a stencil
// (one vectorised loop over the row's floats, each output's taps in a register, the three
// channels 3 floats apart); the few columns whose window the row clips, summed directly. Its
// transpose: pixel k receives sum_x y_x / |[lo_x, hi_x]| times the overlap of [k, k+1] with x's
// window: inside, the same taps mirrored; near the ends, summed directly.
namespace {

// |[k, k+1] n [lo, hi]|.
double overlapWithPixel(int k, double lo, double hi) {
  return std::max(0.0, std::min(k + 1.0, hi) - std::max(double(k), lo));
}

// into[n] = sum_t taps[t] from[n + offset + step t] for n in [begin, end), the taps added in
// order (the same sums on every CPU but for fused multiply-adds). 16 outputs at a time as one
// FloatLanes16 (core/lane_kernel.h: one 512-bit register in the x86-64-v4 clone, where GCC's
// vectoriser chose 256-bit ones), so each sum stays in a register; with the tap count known at
// compile time (every screen period up to 15 pixels wide) the taps stay in registers too. The
// last outputs one at a time, in the same order.
template <int kTaps>
[[gnu::always_inline]] inline void stencilLoop(const float* from, int offset, int step,
                                               const float* taps, int tapCount, float* into,
                                               int begin, int end) {
  float fixed[kTaps > 0 ? kTaps : 1];
  for (int t = 0; t < kTaps; ++t) fixed[t] = taps[t];
  const int count = kTaps > 0 ? kTaps : tapCount;
  const float* weights = kTaps > 0 ? fixed : taps;
  int n = begin;
  for (; n + 16 <= end; n += 16) {
    const float* source = from + (n + offset);
    FloatLanes16 sum{};
    for (int t = 0; t < count; ++t) {
      FloatLanes16 values;
      std::memcpy(&values, source + step * t, sizeof(values));
      sum += weights[t] * values;
    }
    std::memcpy(into + n, &sum, sizeof(sum));
  }
  for (; n < end; ++n) {
    const float* source = from + (n + offset);
    float sum = 0;
    for (int t = 0; t < count; ++t) sum += weights[t] * source[step * t];
    into[n] = sum;
  }
}

// stencilLoop<tapCount> for 2 .. kMostTaps taps, else the loop with the count at run time.
template <int kTaps = 2>
[[gnu::always_inline]] inline void stencilOfCount(const float* from, int offset, int step,
                                                  const float* taps, int tapCount, float* into,
                                                  int begin, int end) {
  if (tapCount == kTaps)
    return stencilLoop<kTaps>(from, offset, step, taps, tapCount, into, begin, end);
  if constexpr (kTaps < BoxRow::kMostTaps)
    return stencilOfCount<kTaps + 1>(from, offset, step, taps, tapCount, into, begin, end);
  else
    return stencilLoop<0>(from, offset, step, taps, tapCount, into, begin, end);
}

#ifdef PARALLAX_SHIFTED_STENCIL
// stencilLoop on AVX-512 CPUs for taps 3 floats apart (a pixel's channels): the 16 inputs of
// every tap of 16 outputs lie in the few vectors from the lowest tap's, so those are loaded
// once and each tap's 16 are shifted out of two of them (valignd) instead of loaded again (one
// unaligned 64-byte load a tap, two cache lines for most: the loads, not the multiply-adds, set
// the loop's pace; GCC's own shuffles of vector extensions became two-source permutations that
// ran no faster). The same multiply-adds in the same tap order as stencilLoop's x86-64-v4
// clone, so the same sums. Taps t at from + n + offset + step t, step 3 or -3 (the transpose:
// tap t is then the (count - 1 - t)-th from the lowest). Reads nothing stencilLoop would not:
// it stops where its last vector would pass the last float stencilLoop reads, and returns the
// output it stopped at for stencilLoop to go on from.
template <int kShift>
[[gnu::always_inline, gnu::target("avx512f")]] inline __m512 shiftedOut(const __m512i* vectors) {
  if constexpr (kShift % 16 == 0)
    return _mm512_castsi512_ps(vectors[kShift / 16]);
  else
    // (The all-lanes mask form: the plain one's undefined source trips -Wmaybe-uninitialized.)
    return _mm512_castsi512_ps(_mm512_mask_alignr_epi32(vectors[kShift / 16], __mmask16(0xFFFF),
                                                        vectors[kShift / 16 + 1],
                                                        vectors[kShift / 16], kShift % 16));
}

template <int kTaps, bool kBackward, int... kT>
[[gnu::target("avx512f")]] int shiftedStencilAvx512(const float* from, int offset,
                                                    const float* taps, float* into, int begin,
                                                    int end, std::integer_sequence<int, kT...>) {
  constexpr int kSpan = 3 * (kTaps - 1);                // floats from the lowest tap to the highest
  constexpr int kVectors = (kSpan + 15) / 16 + 1;       // the vectors that hold every tap's 16
  const int lowest = offset - (kBackward ? kSpan : 0);  // the lowest tap's offset
  // Tap t's floats from the lowest tap's.
  constexpr auto tapShift = [](int t) { return kBackward ? kSpan - 3 * t : 3 * t; };
  __m512 weights[kTaps];
  for (int t = 0; t < kTaps; ++t) weights[t] = _mm512_set1_ps(taps[t]);
  int n = begin;
  for (; n + 16 <= end && n + 16 * kVectors <= end + kSpan; n += 16) {
    const float* source = from + (n + lowest);
    __m512i vectors[kVectors];
    for (int v = 0; v < kVectors; ++v) vectors[v] = _mm512_loadu_si512(source + 16 * v);
    __m512 sum = _mm512_mul_ps(weights[0], shiftedOut<tapShift(0)>(vectors));
    ((sum = kT == 0 ? sum : _mm512_fmadd_ps(weights[kT], shiftedOut<tapShift(kT)>(vectors), sum)),
     ...);
    _mm512_storeu_ps(into + n, sum);
  }
  return n;
}

template <int kTaps = 2>
int shiftedStencilAvx512OfCount(const float* from, int offset, int step, const float* taps,
                                int tapCount, float* into, int begin, int end) {
  if (tapCount == kTaps) {
    constexpr auto kAll = std::make_integer_sequence<int, kTaps>();
    return step > 0 ? shiftedStencilAvx512<kTaps, false>(from, offset, taps, into, begin, end, kAll)
                    : shiftedStencilAvx512<kTaps, true>(from, offset, taps, into, begin, end, kAll);
  }
  if constexpr (kTaps < BoxRow::kMostTaps)
    return shiftedStencilAvx512OfCount<kTaps + 1>(from, offset, step, taps, tapCount, into, begin,
                                                  end);
  else
    return begin;
}

std::atomic<bool> shiftedStencilAllowed{true};

bool shiftedStencilAvx512Runs() {
  static const bool runs = __builtin_cpu_supports("avx512f");
  return runs && shiftedStencilAllowed.load(std::memory_order_relaxed);
}
#endif

PARALLAX_LANE_KERNEL
void stencil(const float* from, int offset, int step, const float* taps, int tapCount, float* into,
             int begin, int end) {
#ifdef PARALLAX_SHIFTED_STENCIL
  if ((step == 3 || step == -3) && tapCount >= 2 && shiftedStencilAvx512Runs())
    begin = shiftedStencilAvx512OfCount(from, offset, step, taps, tapCount, into, begin, end);
#endif
  stencilOfCount(from, offset, step, taps, tapCount, into, begin, end);
}

}  // namespace

bool allowShiftedStencil(bool allow) {
#ifdef PARALLAX_SHIFTED_STENCIL
  return shiftedStencilAllowed.exchange(allow);
#else
  (void)allow;
  return false;
#endif
}

// The edge columns' terms in the order the sums below add them (the arithmetic of summing each
// window directly, in double: precomputed here because those few columns cost as much as the
// whole row's stencil when their overlaps were worked out on every call).
void BoxRow::makeEdges() {
  const auto edge = [&](int x) {
    const double lo = windowLo(x), hi = windowHi(x);
    EdgeColumn column{x, hi - lo, {}};
    for (int k = std::max(0, int(std::floor(lo))); k < std::min(columns_, int(std::ceil(hi))); ++k)
      column.terms.push_back({k, overlapWithPixel(k, lo, hi)});
    edges_.push_back(std::move(column));
  };
  for (int x = 0; x < interiorBegin_; ++x) edge(x);
  for (int x = interiorEnd_; x < columns_; ++x) edge(x);
  // Pixel k meets the windows of x = k - d for the taps d; inside, all of those are interior.
  const int lastTap = firstTap_ + int(taps_.size()) - 1;
  transposedBegin_ = std::min(columns_, interiorBegin_ + lastTap);
  transposedEnd_ = std::max(transposedBegin_, interiorEnd_ + firstTap_);
  const auto transposedEdge = [&](int k) {
    EdgeColumn column{k, 1.0, {}};
    for (int x = std::max(0, k - lastTap); x <= std::min(columns_ - 1, k - firstTap_); ++x) {
      const double lo = windowLo(x), hi = windowHi(x);
      column.terms.push_back({x, overlapWithPixel(k, lo, hi) / (hi - lo)});
    }
    transposedEdges_.push_back(std::move(column));
  };
  for (int k = 0; k < transposedBegin_; ++k) transposedEdge(k);
  for (int k = transposedEnd_; k < columns_; ++k) transposedEdge(k);
}

void BoxRow::edgeSums(const std::vector<EdgeColumn>& columns, const Vec3f* in, Vec3f* out) {
  for (const EdgeColumn& column : columns) {
    double sum[3] = {0, 0, 0};
    for (const EdgeTerm& term : column.terms)
      for (int c = 0; c < 3; ++c) sum[c] += term.weight * in[term.from][c];
    // B^T's length 1 divides exactly.
    for (int c = 0; c < 3; ++c) out[column.column][c] = float(sum[c] / column.length);
  }
}

void BoxRow::apply(const Vec3f* row, Vec3f* out) const {
  stencil(&row[0].x, 3 * firstTap_, 3, taps_.data(), int(taps_.size()), &out[0].x,
          3 * interiorBegin_, 3 * interiorEnd_);
  edgeSums(edges_, row, out);
}

void BoxRow::applyTransposed(const Vec3f* row, Vec3f* out) const {
  stencil(&row[0].x, -3 * firstTap_, -3, taps_.data(), int(taps_.size()), &out[0].x,
          3 * transposedBegin_, 3 * transposedEnd_);
  edgeSums(transposedEdges_, row, out);
}

}  // namespace parallax
