#include "parallax/image/metrics.h"

#include "parallax/core/lane_kernel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/core/parallel.h"
#include "parallax/image/box_row.h"
#include "parallax/image/srgb_arithmetic.h"

namespace parallax {

namespace {

void checkSameSize(const Image& a, const Image& b, const char* metric) {
  if (a.width() != b.width() || a.height() != b.height() || a.empty())
    throw InputError("", "",
                     std::string(metric) + " needs two non-empty images of the same size (got " +
                         std::to_string(a.width()) + "x" + std::to_string(a.height()) + " and " +
                         std::to_string(b.width()) + "x" + std::to_string(b.height()) + ")");
}

double encode(float linear, MetricEncoding encoding) {
  if (encoding == MetricEncoding::Linear) return linear;
  return linearToSrgb(std::clamp(linear, 0.0f, 1.0f));
}

// Rows per chunk of work: the metrics run over whole images once per eye of the dense measure.
constexpr int64_t kRowGrain = 8;

// Output rows of SSIM per chunk of work: each chunk filters its own 10 extra input rows, and
// holds only its rows' moments, never a whole image of them.
constexpr int kSsimRowsPerChunk = 64;

}  // namespace

// Output row y is the integral of the box-pixel column over [y + 1/2 - h/2, y + 1/2 + h/2] (as
// boxFilterX along a row), summed as whole rows: each input row's overlap with the box times the
// row, so the rows are read in memory order.
Image boxFilterY(const Image& image, double heightPx) {
  if (!(heightPx > 0)) throw InputError("", "", "the box filter's height must be positive");
  const int w = image.width(), h = image.height();
  Image out(w, h);
  parallelFor(h, 0, kRowGrain, [&](int64_t begin, int64_t end) {
    std::vector<double> sum(size_t(w) * 3);
    for (int y = int(begin); y < int(end); ++y) {
      const double lo = std::max(0.0, y + 0.5 - 0.5 * heightPx);
      const double hi = std::min(double(h), y + 0.5 + 0.5 * heightPx);
      std::fill(sum.begin(), sum.end(), 0.0);
      for (int row = int(lo); row < h && row < hi; ++row) {
        const double weight = std::min(hi, row + 1.0) - std::max(lo, double(row));
        if (!(weight > 0)) continue;
        const float* in = &image.at(0, row).x;
        for (size_t i = 0; i < sum.size(); ++i) sum[i] += weight * in[i];
      }
      float* o = &out.at(0, y).x;
      for (size_t i = 0; i < sum.size(); ++i) o[i] = float(sum[i] / (hi - lo));
    }
  });
  return out;
}

double meanLuminance(const Image& image) {
  const double sum = parallelSum(image.height(), 0, kRowGrain, [&](int64_t y) {
    double row = 0;
    for (int x = 0; x < image.width(); ++x) row += luminance(image.at(x, int(y)));
    return row;
  });
  return image.empty() ? 0.0 : sum / double(image.pixels().size());
}

namespace {

// sum (a[k] - b[k])^2 over n floats, in double: 16 running sums (value k in lane k mod 16), 16
// values at a time as FloatLanes16, added in lane order at the end (the same sum wherever the
// row is summed).
[[gnu::always_inline]] inline void addSquaredDifferences(const float* a, const float* b,
                                                         size_t count, DoubleLanes8& low,
                                                         DoubleLanes8& high) {
  FloatLanes16 x{}, y{};
  std::memcpy(&x, a, sizeof(float) * count);
  std::memcpy(&y, b, sizeof(float) * count);
  const DoubleLanes8 dLow = lowHalfInDouble(x) - lowHalfInDouble(y),
                     dHigh = highHalfInDouble(x) - highHalfInDouble(y);
  low += dLow * dLow;
  high += dHigh * dHigh;
}

PARALLAX_LANE_KERNEL double squaredDifferences(const float* a, const float* b, size_t n) {
  DoubleLanes8 low{}, high{};
  size_t k = 0;
  for (; k + 16 <= n; k += 16) addSquaredDifferences(a + k, b + k, 16, low, high);
  if (k < n) addSquaredDifferences(a + k, b + k, n - k, low, high);
  return sumInLaneOrder(low, high);
}

// sum ((a - b) - (c - d))^2 over n floats, in double lanes as squaredDifferences.
[[gnu::always_inline]] inline void addSquaredChanges(const float* a, const float* b, const float* c,
                                                     const float* d, size_t count,
                                                     DoubleLanes8& low, DoubleLanes8& high) {
  FloatLanes16 la{}, lb{}, lc{}, ld{};
  std::memcpy(&la, a, sizeof(float) * count);
  std::memcpy(&lb, b, sizeof(float) * count);
  std::memcpy(&lc, c, sizeof(float) * count);
  std::memcpy(&ld, d, sizeof(float) * count);
  const DoubleLanes8 dLow = (lowHalfInDouble(la) - lowHalfInDouble(lb)) -
                            (lowHalfInDouble(lc) - lowHalfInDouble(ld)),
                     dHigh = (highHalfInDouble(la) - highHalfInDouble(lb)) -
                             (highHalfInDouble(lc) - highHalfInDouble(ld));
  low += dLow * dLow;
  high += dHigh * dHigh;
}

PARALLAX_LANE_KERNEL double squaredChanges(const float* a, const float* b, const float* c,
                                           const float* d, size_t n) {
  DoubleLanes8 low{}, high{};
  size_t k = 0;
  for (; k + 16 <= n; k += 16) addSquaredChanges(a + k, b + k, c + k, d + k, 16, low, high);
  if (k < n) addSquaredChanges(a + k, b + k, c + k, d + k, n - k, low, high);
  return sumInLaneOrder(low, high);
}

}  // namespace

EncodedComparison compareEncoded(const Image& picture, const Image& idealEncoded,
                                 const Image* previousEncoded, const Image* previousIdealEncoded) {
  checkSameSize(picture, idealEncoded, "the comparison");
  const bool flicker = previousEncoded && previousIdealEncoded;
  if (flicker) {
    checkSameSize(picture, *previousEncoded, "the comparison");
    checkSameSize(picture, *previousIdealEncoded, "the comparison");
  }
  const int w = picture.width(), h = picture.height();
  const size_t rowValues = 3 * size_t(w);
  EncodedComparison out{Image(w, h)};
  // Each row's three sums, added in row order afterwards.
  std::vector<std::array<double, 3>> rows(static_cast<size_t>(h));
  parallelFor(h, 0, kRowGrain, [&](int64_t begin, int64_t end) {
    for (int y = int(begin); y < int(end); ++y) {
      const float* linear = &picture.at(0, y).x;
      float* encoded = &out.encoded.at(0, y).x;
      srgbEncodeValues(linear, encoded, rowValues);
      const float* ideal = &idealEncoded.at(0, y).x;
      std::array<double, 3>& sums = rows[size_t(y)];
      sums[0] = squaredDifferences(encoded, ideal, rowValues);
      sums[1] = flicker ? squaredChanges(encoded, ideal, &previousEncoded->at(0, y).x,
                                         &previousIdealEncoded->at(0, y).x, rowValues)
                        : 0.0;
      double luminances = 0;
      for (int x = 0; x < w; ++x) luminances += luminance(picture.at(x, y));
      sums[2] = luminances;
    }
  });
  for (const std::array<double, 3>& sums : rows) {
    out.squaredError += sums[0];
    out.flickerSquares += sums[1];
    out.luminance += sums[2];
  }
  if (!flicker) out.flickerSquares = std::numeric_limits<double>::quiet_NaN();
  return out;
}

double meanSquaredError(const Image& a, const Image& b, MetricEncoding encoding) {
  checkSameSize(a, b, "the mean squared error");
  const double sum = parallelSum(a.height(), 0, kRowGrain, [&](int64_t y) {
    if (encoding == MetricEncoding::Linear)
      return squaredDifferences(&a.at(0, int(y)).x, &b.at(0, int(y)).x, 3 * size_t(a.width()));
    double row = 0;
    for (int x = 0; x < a.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        const double d =
            encode(a.at(x, int(y))[c], encoding) - encode(b.at(x, int(y))[c], encoding);
        row += d * d;
      }
    return row;
  });
  return sum / (3.0 * double(a.pixels().size()));
}

namespace {

// out[l] = S(in[l]) for l < count <= 32, as two FloatLanes16 side by side
// (srgbEncodeArithmetic). Always inlined, as are the other helpers of the lane kernels here: a
// lambda or a function left out of line would be compiled for the baseline, not for the kernel's
// clone.
[[gnu::always_inline]] inline void srgbEncodeLanes(const float* in, float* out, size_t count) {
  FloatLanes16 values[2] = {}, encoded[2], slope[2];
  std::memcpy(values, in, sizeof(float) * count);
  srgbEncodeArithmetic<FloatLanes16, IntLanes16, 2>(values, encoded, slope);
  std::memcpy(out, encoded, sizeof(float) * count);
}

}  // namespace

// 32 values at a time as FloatLanes16 (one 512-bit register in the x86-64-v4 clone, where GCC's
// vectoriser chose 256-bit ones); the last n mod 32 through the same lanes.
PARALLAX_LANE_KERNEL void srgbEncodeValues(const float* __restrict in, float* __restrict out,
                                           size_t n) {
  size_t k = 0;
  for (; k + 32 <= n; k += 32) srgbEncodeLanes(in + k, out + k, 32);
  if (k < n) srgbEncodeLanes(in + k, out + k, n - k);
}

Image srgbEncoded(const Image& image) {
  Image out(image.width(), image.height());
  const size_t rowValues = 3 * size_t(image.width());
  parallelFor(image.height(), 0, kRowGrain, [&](int64_t begin, int64_t end) {
    const size_t first = size_t(begin) * rowValues;
    srgbEncodeValues(&image.pixels()[0].x + first, &out.pixels()[0].x + first,
                     size_t(end - begin) * rowValues);
  });
  return out;
}

double psnr(const Image& a, const Image& b, double peak, MetricEncoding encoding) {
  const double mse = meanSquaredError(a, b, encoding);
  return mse > 0 ? 10.0 * std::log10(peak * peak / mse) : std::numeric_limits<double>::infinity();
}

namespace {

// SSIM's window: 11 taps of a Gaussian of sigma 1.5 along each axis (Wang et al. 2004).
constexpr int kSsimWindow = 11;

[[gnu::always_inline]] inline FloatLanes16 loadLanes(const float* from, size_t count) {
  FloatLanes16 lanes{};
  std::memcpy(&lanes, from, sizeof(float) * count);
  return lanes;
}

// into[x] = sum_k kernel[k] rows[k][x] for x < n, the taps added in order: SSIM's window along
// a row (rows[k] = the row from its k-th value) and down the columns (rows[k] = the k-th row of
// the window). 16 outputs at a time, each kept in a register through its taps (one 512-bit
// register in the x86-64-v4 clone, where GCC's vectoriser chose 256-bit ones).
PARALLAX_LANE_KERNEL void windowSums(const float* const* rows, const float* kernel,
                                     float* __restrict into, size_t n) {
  const auto lanes = [&](size_t x, size_t count) {
    FloatLanes16 sum = kernel[0] * loadLanes(rows[0] + x, count);
    for (int k = 1; k < kSsimWindow; ++k) sum += kernel[k] * loadLanes(rows[k] + x, count);
    std::memcpy(into + x, &sum, sizeof(float) * count);
  };
  size_t x = 0;
  for (; x + 16 <= n; x += 16) lanes(x, 16);
  if (x < n) lanes(x, n - x);
}

// The sum over n windows of SSIM's term from their five means (x, y, xx, yy, xy: planes n
// apart), in double: the variances are differences of nearly equal means.
PARALLAX_LANE_KERNEL double ssimTermSum(const float* __restrict means, size_t n) {
  constexpr double kC1 = 0.01 * 0.01, kC2 = 0.03 * 0.03;
  double sum = 0;
  for (size_t x = 0; x < n; ++x) {
    const double ux = means[x], uy = means[n + x];
    const double vx = means[2 * n + x] - ux * ux, vy = means[3 * n + x] - uy * uy,
                 cxy = means[4 * n + x] - ux * uy;
    sum += (2 * ux * uy + kC1) * (2 * cxy + kC2) / ((ux * ux + uy * uy + kC1) * (vx + vy + kC2));
  }
  return sum;
}

}  // namespace

double ssim(const Image& a, const Image& b) {
  checkSameSize(a, b, "SSIM");
  constexpr double kSigma = 1.5;
  if (a.width() < kSsimWindow || a.height() < kSsimWindow)
    throw InputError("", "", "SSIM needs images of at least 11x11 pixels");
  std::array<double, kSsimWindow> weights{};
  double total = 0;
  for (int i = 0; i < kSsimWindow; ++i) {
    const double d = i - kSsimWindow / 2;
    total += weights[size_t(i)] = std::exp(-d * d / (2 * kSigma * kSigma));
  }
  std::array<float, kSsimWindow> kernel{};
  for (int i = 0; i < kSsimWindow; ++i) kernel[size_t(i)] = float(weights[size_t(i)] / total);

  const int w = a.width(), h = a.height();
  const size_t n = size_t(w - kSsimWindow + 1);
  const int outHeight = h - kSsimWindow + 1;
  const int chunks = (outHeight + kSsimRowsPerChunk - 1) / kSsimRowsPerChunk;
  // Per chunk: the five moments (x, y, xx, yy, xy of the encoded luminance) of each input row
  // it needs, filtered along the row into a ring of the window's last 11 rows; each output row
  // then filters the ring down its columns. In float (the means' rounding moves SSIM by about
  // 1e-7), so that a chunk's ring stays in the core's cache.
  const double sum = parallelSum(chunks, 0, 1, [&](int64_t chunk) {
    const int first = int(chunk) * kSsimRowsPerChunk;
    const int rows = std::min(kSsimRowsPerChunk, outHeight - first);
    // ring[(slot * 5 + m) * n + x]: moment m of input row (first + r) for slot r mod 11.
    std::vector<float> ring(size_t(kSsimWindow) * 5 * n), means(5 * n);
    std::vector<float> luminances(2 * size_t(w)), moments(5 * size_t(w));
    const auto filterInputRow = [&](int r) {
      for (int x = 0; x < w; ++x) {
        luminances[size_t(x)] = luminance(a.at(x, first + r));
        luminances[size_t(w + x)] = luminance(b.at(x, first + r));
      }
      srgbEncodeValues(luminances.data(), moments.data(), 2 * size_t(w));
      float* plane[5];
      for (int m = 0; m < 5; ++m) plane[m] = &moments[size_t(m) * size_t(w)];
      for (int x = 0; x < w; ++x) {
        const float u = plane[0][x], v = plane[1][x];
        plane[2][x] = u * u, plane[3][x] = v * v, plane[4][x] = u * v;
      }
      const size_t slot = size_t(r % kSsimWindow);
      for (int m = 0; m < 5; ++m) {
        const float* taps[kSsimWindow];
        for (int k = 0; k < kSsimWindow; ++k) taps[k] = plane[m] + k;
        windowSums(taps, kernel.data(), &ring[(slot * 5 + size_t(m)) * n], n);
      }
    };
    for (int r = 0; r + 1 < kSsimWindow; ++r) filterInputRow(r);
    double chunkSum = 0;
    for (int r = 0; r < rows; ++r) {
      filterInputRow(r + kSsimWindow - 1);
      for (int m = 0; m < 5; ++m) {
        const float* taps[kSsimWindow];
        for (int k = 0; k < kSsimWindow; ++k)
          taps[k] = &ring[(size_t((r + k) % kSsimWindow) * 5 + size_t(m)) * n];
        windowSums(taps, kernel.data(), &means[size_t(m) * n], n);
      }
      chunkSum += ssimTermSum(means.data(), n);
    }
    return chunkSum;
  });
  return sum / (double(n) * double(outHeight));
}

// Row by row. Boxes of up to BoxRow::kMostTaps pixels (a screen period: the dense measure's,
// about nine) as BoxRow's stencil, each output's taps in registers. Wider ones by prefixes:
// the prefix integrals of the row's three channels interleaved as the row is (one pass in
// memory order), then each pixel's box from the prefixes at its two ends. Where the box lies
// inside the row its ends sit at fixed offsets from the pixel, so those pixels are one
// vectorised loop over the row's values; the few pixels whose box the row clips are summed
// one by one. (The prefixes' serial sum takes about three times the stencil's time at nine
// pixels.)
PARALLAX_LANE_KERNEL Image boxFilterX(const Image& image, double widthPx) {
  const int w = image.width();
  const BoxRow box(w, widthPx);
  Image out(w, image.height());
  if (box.tapCount() <= BoxRow::kMostTaps) {
    parallelFor(image.height(), 0, kRowGrain, [&](int64_t begin, int64_t end) {
      for (int64_t y = begin; y != end; ++y) box.apply(&image.at(0, int(y)), &out.at(0, int(y)));
    });
    return out;
  }
  return boxFilterXByPrefixes(image, widthPx, std::move(out));
}

PARALLAX_LANE_KERNEL Image boxFilterXByPrefixes(const Image& image, double widthPx, Image out) {
  if (!(widthPx > 0)) throw InputError("", "", "the box filter's width must be positive");
  const int w = image.width();
  if (out.width() != w || out.height() != image.height()) out = Image(w, image.height());
  // Pixel x's box is [x + a, x + b]; inside the row for x in [first, last): x + a >= 0 and
  // x + b <= w - 1 (so that floor(x + b) is a pixel of the row).
  const double a = 0.5 - 0.5 * widthPx, b = 0.5 + 0.5 * widthPx;
  const int first = std::min(w, int(std::ceil(-a)));
  const int last = std::max(first, std::min(w, int(std::floor(double(w - 1) - b)) + 1));
  const int lowOffset = int(std::floor(a)), highOffset = int(std::floor(b));
  const double lowFraction = a - lowOffset, highFraction = b - highOffset;
  parallelFor(image.height(), 0, kRowGrain, [&](int64_t begin, int64_t end) {
    // prefix[3 i + c]: the integral of channel c of the box-pixel row over [0, i).
    std::vector<double> prefix(3 * (size_t(w) + 1));
    for (int y = int(begin); y < int(end); ++y) {
      const float* in = &image.at(0, y).x;
      for (size_t i = 0; i < 3 * size_t(w); ++i) prefix[i + 3] = prefix[i] + in[i];
      float* o = &out.at(0, y).x;
      // The integral up to t is prefix[i] + (t - i) row[i], i = floor(t), the last pixel's at
      // t = w.
      const auto clipped = [&](int x) {
        const double lo = std::max(0.0, x + a), hi = std::min(double(w), x + b);
        const size_t il = size_t(std::min(int(lo), w - 1)), ih = size_t(std::min(int(hi), w - 1));
        const double fl = lo - double(il), fh = hi - double(ih);
        for (size_t c = 0; c < 3; ++c)
          o[3 * size_t(x) + c] = float(((prefix[3 * ih + c] + fh * in[3 * ih + c]) -
                                        (prefix[3 * il + c] + fl * in[3 * il + c])) /
                                       (hi - lo));
      };
      for (int x = 0; x < first; ++x) clipped(x);
      const double* p = prefix.data();
      const ptrdiff_t low = 3 * ptrdiff_t(lowOffset), high = 3 * ptrdiff_t(highOffset);
      for (ptrdiff_t v = 3 * ptrdiff_t(first); v < 3 * ptrdiff_t(last); ++v)
        o[v] = float(((p[v + high] + highFraction * in[v + high]) -
                      (p[v + low] + lowFraction * in[v + low])) /
                     widthPx);
      for (int x = last; x < w; ++x) clipped(x);
    }
  });
  return out;
}

}  // namespace parallax
