// The layer problem's targets and diffuser (layer_problem.h).
#include "parallax/layers/layer_problem.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "parallax/core/lane_kernel.h"
#include "parallax/core/parallel.h"
#include "parallax/image/srgb_arithmetic.h"
#include "parallax/sim/diffuser.h"

namespace parallax {

namespace {

// round(scaled) of a value in [0, 65535], rounding halves up as std::lround does for these
// non-negative values (truncation and the exact remainder: vectorised in the loops below,
// where lround is a libm call per value), at most 65535.
[[gnu::always_inline]] inline uint16_t sixteenBitCode(float scaled) {
  int rounded = int(scaled);
  rounded += scaled - float(rounded) >= 0.5f ? 1 : 0;
  return uint16_t(std::min(rounded, 65535));
}

// sixteenBitCode of 16 lanes (the same arithmetic).
[[gnu::always_inline]] inline HalfWordLanes16 sixteenBitCodes(FloatLanes16 scaled) {
  IntLanes16 rounded = convertLanes<IntLanes16>(scaled);
  rounded += scaled - convertLanes<FloatLanes16>(rounded) >= 0.5f ? 1 : 0;
  rounded = rounded < 65535 ? rounded : 65535;
  return __builtin_convertvector(rounded, HalfWordLanes16);
}

// round(65535 S(v / c)) of n values, 32 at a time as two FloatLanes16 side by side
// (srgbEncodeArithmetic), the last ones in zeroed lanes.
PARALLAX_LANE_KERNEL
void encodeTargetLanes(const float* values, uint16_t* encoded, size_t n, float inv) {
  for (size_t k = 0; k < n; k += 32) {
    const size_t count = std::min<size_t>(32, n - k);
    FloatLanes16 in[2] = {}, out[2], slope[2];
    std::memcpy(in, values + k, sizeof(float) * count);
    for (FloatLanes16& v : in) v *= inv;
    srgbEncodeArithmetic<FloatLanes16, IntLanes16, 2>(in, out, slope);
    const HalfWordLanes16 codes[2] = {sixteenBitCodes(out[0] * kEncodedUnit),
                                      sixteenBitCodes(out[1] * kEncodedUnit)};
    std::memcpy(encoded + k, codes, sizeof(uint16_t) * count);
  }
}

// round(v / unit) of n values, clamped to [0, 65535].
PARALLAX_LANE_KERNEL
void encodeLinearLanes(const float* values, uint16_t* encoded, size_t n, float inverseUnit) {
  PARALLAX_SIMD
  for (size_t i = 0; i < n; ++i)
    encoded[i] = sixteenBitCode(std::clamp(values[i] * inverseUnit, 0.0f, 65535.0f));
}

// codes[i] x unit into values, n of them. The codes stream from memory, a row of each eye in
// turn: asked for kPrefetchCodes ahead, a cache line (32 codes) at a time, as
// encodedErrorLoop does.
PARALLAX_LANE_KERNEL
void decodeLinearLanes(const uint16_t* codes, float* values, size_t n, float unit) {
  size_t k = 0;
  for (; k + 32 <= n; k += 32) {
    __builtin_prefetch(codes + k + kPrefetchCodes);
    PARALLAX_SIMD
    for (size_t i = k; i < k + 32; ++i) values[i] = float(codes[i]) * unit;
  }
  for (; k < n; ++k) values[k] = float(codes[k]) * unit;
}

}  // namespace

void TrainingView::encodeTarget(int threads) {
  const size_t rowValues = 3 * size_t(target.width());
  const int rows = target.height();
  const float* values = &target.pixels()[0].x;
  float inverse = 0;
  if (encodingScale > 0) {
    inverse = 1.0f / encodingScale;
  } else {
    // The unit: the largest value over 65535 (each row's largest, then theirs; a value that is
    // not a number makes its row's largest one).
    std::vector<float> rowLargest(size_t(rows), 0.0f);
    parallelFor(rows, threads, 8, [&](int64_t begin, int64_t end) {
      for (int64_t j = begin; j != end; ++j) {
        float largest = 0;
        bool numbers = true;
        const float* row = values + size_t(j) * rowValues;
        for (size_t k = 0; k < rowValues; ++k) {
          largest = std::max(largest, row[k]);
          numbers &= row[k] == row[k];
        }
        rowLargest[size_t(j)] = numbers ? largest : std::numeric_limits<float>::quiet_NaN();
      }
    });
    float largest = 0;
    for (const float value : rowLargest)
      largest = std::isnan(value) ? value : std::max(largest, value);
    if (!std::isfinite(largest))
      throw std::invalid_argument("TrainingView::encodeTarget: a target value is not finite");
    linearUnit = largest > 0 ? largest / 65535.0f : 1.0f;
    inverse = 1.0f / linearUnit;
  }
  encodedTarget.resize(rowValues * size_t(rows));
  parallelFor(rows, threads, 8, [&](int64_t begin, int64_t end) {
    const size_t first = size_t(begin) * rowValues, n = size_t(end - begin) * rowValues;
    if (encodingScale > 0)
      encodeTargetLanes(values + first, encodedTarget.data() + first, n, inverse);
    else
      encodeLinearLanes(values + first, encodedTarget.data() + first, n, inverse);
  });
  target = Image();
}

void TrainingView::encodeBoxedTarget(int threads) {
  if (encodingScale > 0 || target.empty())
    throw std::logic_error("TrainingView::encodeBoxedTarget: not a linear target");
  startBoxedTarget();
  parallelFor(target.height(), threads, 8, [&](int64_t begin, int64_t end) {
    encodeBoxedRows(&target.at(0, int(begin)), int(begin), int(end - begin));
  });
  target = Image();
}

void TrainingView::startBoxedTarget() {
  if (encodingScale > 0)
    throw std::logic_error("TrainingView::startBoxedTarget: not a linear target");
  const size_t rows = size_t(seen.height());
  rowTargetSquares.assign(rows, 0.0);
  rowUnits.assign(rows, 1.0f);
  encodedTarget.resize(3 * size_t(seen.width()) * rows);
  linearUnit = 0.0f;
  boxedTarget = true;
}

void TrainingView::encodeBoxedRows(Vec3f* rows, int firstRow, int count) {
  const size_t width = size_t(seen.width());
  if (!boxedTarget || firstRow < 0 || count < 0 || firstRow + count > seen.height())
    throw std::logic_error("TrainingView::encodeBoxedRows: not rows of a started boxed target");
  std::vector<Vec3f> boxed(width);
  for (int k = 0; k < count; ++k) {
    const size_t j = size_t(firstRow + k);
    const Vec3f* row = rows + size_t(k) * width;
    // |t_j|^2, then B^T t_j in the row's own unit (a value that is not a number makes it so).
    rowTargetSquares[j] = sumOfProductsLanes(&row[0].x, &row[0].x, nullptr, 3 * width);
    seen.boxTransposedRowInto(row, boxed.data());
    float largest = 0;
    bool numbers = true;
    for (const Vec3f& p : boxed)
      for (int c = 0; c < 3; ++c) largest = std::max(largest, p[c]), numbers &= p[c] == p[c];
    if (!numbers || !std::isfinite(largest))
      throw std::invalid_argument("TrainingView::encodeBoxedRows: a target value is not finite");
    rowUnits[j] = largest > 0 ? largest / 65535.0f : 1.0f;
    encodeLinearLanes(&boxed[0].x, encodedTarget.data() + 3 * width * j, 3 * width,
                      1.0f / rowUnits[j]);
  }
}

void TrainingView::boxedTargetRow(int j, Vec3f* out, Vec3f* scratch) const {
  const size_t width = size_t(seen.width());
  if (boxedTarget) {
    decodeLinearLanes(encodedTarget.data() + 3 * width * size_t(j), &out[0].x, 3 * width,
                      rowUnits[size_t(j)]);
    return;
  }
  seen.boxTransposedRowInto(linearTargetRow(j, scratch), out);
}

const Vec3f* TrainingView::linearTargetRow(int j, Vec3f* row) const {
  const size_t width = size_t(seen.width());
  if (boxedTarget)
    throw std::logic_error("TrainingView::linearTargetRow: the target is kept as B^T t");
  if (encodedTarget.empty()) return target.pixels().data() + size_t(j) * width;
  if (!(linearUnit > 0))
    throw std::logic_error("TrainingView::linearTargetRow: the target is kept as sRGB codes");
  decodeLinearLanes(encodedTarget.data() + 3 * width * size_t(j), &row[0].x, 3 * width, linearUnit);
  return row;
}

const Image& TrainingView::linearTarget(Image& holder, int threads) const {
  if (encodedTarget.empty()) return target;
  holder = Image(seen.width(), seen.height());
  parallelFor(seen.height(), threads, 8, [&](int64_t begin, int64_t end) {
    for (int64_t j = begin; j != end; ++j) linearTargetRow(int(j), &holder.at(0, int(j)));
  });
  return holder;
}

Image RearDiffuser::apply(const Image& layer, int threads) const {
  if (striped()) return stripedDiffuserBlurred(layer, stripes, sigmaMm, pitchMm, threads);
  return active() ? diffuserBlurred(layer, sigmaMm, pitchMm, threads) : layer;
}

Image RearDiffuser::applyTransposed(const Image& seen, int threads) const {
  if (striped()) return stripedDiffuserBlurredTransposed(seen, stripes, sigmaMm, pitchMm, threads);
  return apply(seen, threads);
}

}  // namespace parallax
