// The numerics both layer solvers share (layer_numerics.h).
#include "parallax/layers/layer_numerics.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "parallax/core/lane_kernel.h"
#include "parallax/image/srgb_arithmetic.h"

namespace parallax::layer_numerics {

// The view of one image and mask pair, whichever layer is in front.
Image viewOf(const SeenLayers& seen, const Image& image, const Image& mask, int threads) {
  return seen.imageInFront() ? seen.view(image, mask, threads) : seen.view(mask, image, threads);
}

void clampToUnit(Image& image) {
  for (Vec3f& p : image.pixels())
    for (int c = 0; c < 3; ++c) p[c] = std::clamp(std::isfinite(p[c]) ? p[c] : 0.0f, 0.0f, 1.0f);
}

namespace {

// The sRGB errors against an encoded target (TrainingView::encodedTarget) over n values, 16 at a
// time as FloatLanes16 (core/lane_kernel.h: one 512-bit register in the x86-64-v4 clone, where
// a loop left to GCC's vectoriser got 256-bit ones and ran 1.5x slower): each value's
// difference S(v / c) - target (and its residual and weight when asked), the squares added in
// 16 running sums in double, one per lane (value k in lane k mod 16), added in lane order at
// the end: the same sum for any thread count. The last n mod 16 values go through the same
// lanes, the unused ones zero. Returns sum (S(v / c) - target)^2 / 2.
template <bool kResidual, bool kWeights, int kN>
[[gnu::always_inline]] inline void encodedErrorStep(const float* seen, const uint16_t* encoded,
                                                    size_t at, int count, float inv,
                                                    float* residual, float* weights,
                                                    DoubleLanes8& low, DoubleLanes8& high) {
  // kN vectors of 16 (the last `count` values in all: fewer than 16 only for kN = 1), encoded
  // side by side (srgbEncodeArithmetic), their squares added to the sums in value order.
  FloatLanes16 values[kN] = {}, value[kN], slope[kN];
  HalfWordLanes16 codes[kN] = {};
  std::memcpy(values, seen + at, sizeof(float) * size_t(count));
  std::memcpy(codes, encoded + at, sizeof(uint16_t) * size_t(count));
  for (int v = 0; v < kN; ++v) values[v] *= inv;
  srgbEncodeArithmetic<FloatLanes16, IntLanes16, kN>(values, value, slope);
  for (int v = 0; v < kN; ++v) {
    FloatLanes16 diff = value[v] - convertLanes<FloatLanes16>(codes[v]) * kInverseEncodedUnit;
    if (count < 16)
      for (int l = count; l < 16; ++l) diff[l] = 0.0f;
    const FloatLanes16 s = slope[v] * inv;
    if constexpr (kResidual) {
      const FloatLanes16 r = s * diff;
      std::memcpy(residual + at + 16 * size_t(v), &r, sizeof(float) * size_t(std::min(count, 16)));
    }
    if constexpr (kWeights) {
      const FloatLanes16 w = s * s;
      std::memcpy(weights + at + 16 * size_t(v), &w, sizeof(float) * size_t(std::min(count, 16)));
    }
    const DoubleLanes8 first = lowHalfInDouble(diff), second = highHalfInDouble(diff);
    low += first * first;
    high += second * second;
  }
}

template <bool kResidual, bool kWeights>
[[gnu::always_inline]] inline double encodedErrorLoop(const float* seen, const uint16_t* encoded,
                                                      size_t n, float inv, float* residual,
                                                      float* weights) {
  DoubleLanes8 low{}, high{};
  size_t k = 0;
  for (; k + 32 <= n; k += 32) {
    // The targets stream from memory, a row of each eye in turn: ask for them a kilobyte ahead
    // (their loads stalled the loop otherwise, the prefetcher starting anew with each row).
    __builtin_prefetch(encoded + k + kPrefetchCodes);
    encodedErrorStep<kResidual, kWeights, 2>(seen, encoded, k, 32, inv, residual, weights, low,
                                             high);
  }
  for (; k < n; k += 16)
    encodedErrorStep<kResidual, kWeights, 1>(seen, encoded, k, int(std::min<size_t>(16, n - k)),
                                             inv, residual, weights, low, high);
  return 0.5 * sumInLaneOrder(low, high);
}

PARALLAX_LANE_KERNEL
double encodedErrorLanes(const float* seen, const uint16_t* encoded, size_t n, float inv,
                         float* residual, float* weights) {
  if (residual && weights)
    return encodedErrorLoop<true, true>(seen, encoded, n, inv, residual, weights);
  if (residual) return encodedErrorLoop<true, false>(seen, encoded, n, inv, residual, weights);
  if (weights) return encodedErrorLoop<false, true>(seen, encoded, n, inv, residual, weights);
  return encodedErrorLoop<false, false>(seen, encoded, n, inv, residual, weights);
}

// The linear-light errors over n values: 1/2 sum (v - t)^2, the residual v - t and the weights
// 1 when asked; the squares in kLanes running sums added in lane order (the same sum for any
// thread count).
PARALLAX_LANE_KERNEL
double linearErrorLanes(const float* seen, const float* target, size_t n, float* residual,
                        float* weights) {
  double lanes[kLanes] = {};
  size_t k = 0;
  for (; k + kLanes <= n; k += kLanes)
    for (int l = 0; l < kLanes; ++l) {
      const float diff = seen[k + size_t(l)] - target[k + size_t(l)];
      lanes[l] += double(diff) * double(diff);
    }
  for (int l = 0; k < n; ++k, ++l) {
    const float diff = seen[k] - target[k];
    lanes[l] += double(diff) * double(diff);
  }
  if (residual)
    for (size_t i = 0; i < n; ++i) residual[i] = seen[i] - target[i];
  if (weights) std::fill(weights, weights + n, 1.0f);
  double sum = 0;
  for (const double lane : lanes) sum += lane;
  return 0.5 * sum;
}

// linearErrorLanes against a target kept in 16-bit codes (TrainingView::linearUnit): each
// value's target code x unit, decoded in the loop (16 at a time as FloatLanes16), the squares
// in the same 16 running sums in double, added in lane order; the last n mod 16 values through
// the same lanes, the unused ones zero.
template <int kCount>
[[gnu::always_inline]] inline void linearCodeErrorStep(const float* seen, const uint16_t* codes,
                                                       size_t at, int count, float unit,
                                                       float* residual, DoubleLanes8& low,
                                                       DoubleLanes8& high) {
  const size_t n = size_t(kCount > 0 ? kCount : count);
  FloatLanes16 values{};
  HalfWordLanes16 target{};
  std::memcpy(&values, seen + at, sizeof(float) * n);
  std::memcpy(&target, codes + at, sizeof(uint16_t) * n);
  const FloatLanes16 diff = values - convertLanes<FloatLanes16>(target) * unit;
  if (residual) std::memcpy(residual + at, &diff, sizeof(float) * n);
  const DoubleLanes8 first = lowHalfInDouble(diff), second = highHalfInDouble(diff);
  low += first * first;
  high += second * second;
}

PARALLAX_LANE_KERNEL
double linearCodeErrorLanes(const float* seen, const uint16_t* codes, size_t n, float unit,
                            float* residual, float* weights) {
  DoubleLanes8 low{}, high{};
  size_t k = 0;
  for (; k + 16 <= n; k += 16) {
    __builtin_prefetch(codes + k + kPrefetchCodes);
    linearCodeErrorStep<16>(seen, codes, k, 16, unit, residual, low, high);
  }
  if (k < n) linearCodeErrorStep<0>(seen, codes, k, int(n - k), unit, residual, low, high);
  if (weights) std::fill(weights, weights + n, 1.0f);
  return 0.5 * sumInLaneOrder(low, high);
}

}  // namespace

double eyeErrorRange(const TrainingView& v, const Vec3f* seen, size_t first, size_t count,
                     Vec3f* residual, Vec3f* weights) {
  const bool srgb = v.encodingScale > 0;
  const float inv = srgb ? 1.0f / v.encodingScale : 1.0f;
  double sum = 0;
  const auto add = [&](size_t i, int c, float diff, float slope) {
    sum += 0.5 * double(diff) * double(diff);
    if (residual) residual[i][c] = slope * diff;
    if (weights) weights[i][c] = slope * slope;
  };
  if (srgb && !v.encodedTarget.empty())
    return encodedErrorLanes(&seen[0].x, v.encodedTarget.data() + 3 * first, 3 * count, inv,
                             residual ? &residual[0].x : nullptr,
                             weights ? &weights[0].x : nullptr);
  if (!srgb && !v.encodedTarget.empty())
    return linearCodeErrorLanes(&seen[0].x, v.encodedTarget.data() + 3 * first, 3 * count,
                                v.linearUnit, residual ? &residual[0].x : nullptr,
                                weights ? &weights[0].x : nullptr);
  const Vec3f* target = v.target.pixels().data() + first;
  if (!srgb)
    return linearErrorLanes(&seen[0].x, &target[0].x, 3 * count,
                            residual ? &residual[0].x : nullptr, weights ? &weights[0].x : nullptr);
  for (size_t i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) {
      const float value = seen[i][c];
      float a = 0, b = 0, slope = 0, unused = 0;
      srgbEncodeArithmetic(value * inv, a, slope);
      srgbEncodeArithmetic(target[i][c] * inv, b, unused);
      add(i, c, a - b, slope * inv);
    }
  return sum;
}

double eyeError(const TrainingView& v, const Image& seen, Image* residual, Image* weights) {
  return eyeErrorRange(v, seen.pixels().data(), 0, seen.pixels().size(),
                       residual ? residual->pixels().data() : nullptr,
                       weights ? weights->pixels().data() : nullptr);
}

Image elementwise(const Image& a, const Image& b) {
  Image out = a;
  for (size_t i = 0; i < out.pixels().size(); ++i) out.pixels()[i] = a.pixels()[i] * b.pixels()[i];
  return out;
}

// a += s * b, a -= b, <a, b>, |a|^2 over images of one size.
void addScaled(Image& a, const Image& b, float s) {
  for (size_t i = 0; i < a.pixels().size(); ++i) a.pixels()[i] += b.pixels()[i] * s;
}
// (<a, b> over every rowStride-th row only: the rows planeStep samples.)
double dot(const Image& a, const Image& b, int rowStride) {
  double sum = 0;
  for (int y = 0; y < a.height(); y += rowStride)
    for (int x = 0; x < a.width(); ++x)
      for (int c = 0; c < 3; ++c) sum += double(a.at(x, y)[c]) * double(b.at(x, y)[c]);
  return sum;
}

// The average view of the frames from one eye.
Image averageView(const TrainingView& v, const std::vector<LayerFrame>& frames, int threads) {
  Image sum;
  for (const LayerFrame& f : frames) {
    Image one = viewOf(v.seen, f.image, f.mask, threads);
    if (sum.empty()) {
      sum = std::move(one);
    } else {
      addScaled(sum, one, 1.0f);
    }
  }
  if (frames.size() > 1) {
    const float inv = 1.0f / float(frames.size());
    for (Vec3f& p : sum.pixels()) p = p * inv;
  }
  return sum;
}

double normaliser(const std::vector<TrainingView>& views) {
  if (views.empty()) return 1.0;
  return 1.0 / (double(views.front().seen.width()) * views.front().seen.height() * 3.0 *
                double(views.size()));
}

// `boxedTargets`: whether the solver reads targets kept as B^T t (factorizeLayers with the
// image in front); elsewhere they are refused.
void checkViews(const std::vector<TrainingView>& views, bool boxedTargets) {
  if (views.empty()) throw std::invalid_argument("layer solver: no training views");
  for (const TrainingView& v : views) {
    if (v.boxedTarget && !boxedTargets)
      throw std::invalid_argument(
          "layer solver: a target kept as B^T t, which this solve cannot read");
    const bool sized =
        v.encodedTarget.empty()
            ? v.target.width() == v.seen.width() && v.target.height() == v.seen.height()
            : (v.encodingScale > 0 || v.linearUnit > 0 || v.boxedTarget) &&
                  v.encodedTarget.size() == 3 * size_t(v.seen.width()) * v.seen.height();
    if (!sized) throw std::invalid_argument("layer solver: a target's size differs from its view");
  }
}

// The gradient of one eye's view with respect to the image layer (imageLayer) or the mask,
// the other layer fixed: the front or the rear adjoint, by the display's layer order.
void addLayerGradient(const TrainingView& v, const Image& residual, const Image& other, Image& grad,
                      bool imageLayer, int threads) {
  if (v.seen.imageInFront() == imageLayer)
    v.seen.addFrontGradient(residual, other, grad, threads);
  else
    v.seen.addRearGradient(residual, other, grad, threads);
}
void addImageGradient(const TrainingView& v, const Image& residual, const Image& mask, Image& grad,
                      int threads) {
  addLayerGradient(v, residual, mask, grad, true, threads);
}

// The frames as the eyes see them: each frame's rear layer (the mask with the image in front)
// through the diffuser: `frames` themselves without one, else blurred copies kept in `holder`.
const std::vector<LayerFrame>& seenFrames(const std::vector<TrainingView>& views,
                                          const std::vector<LayerFrame>& frames,
                                          const RearDiffuser& diffuser, int threads,
                                          std::vector<LayerFrame>& holder) {
  if (!diffuser.active()) return frames;
  const bool maskIsRear = views.front().seen.imageInFront();
  holder = frames;
  for (LayerFrame& f : holder) {
    Image& rear = maskIsRear ? f.mask : f.image;
    rear = diffuser.apply(rear, threads);
  }
  return holder;
}

bool rowsSeparable(const std::vector<TrainingView>& views) {
  return std::all_of(views.begin(), views.end(),
                     [](const TrainingView& v) { return v.seen.imageInFront(); });
}

}  // namespace parallax::layer_numerics

namespace parallax {

using namespace layer_numerics;

double layerObjective(const std::vector<TrainingView>& views, const std::vector<LayerFrame>& frames,
                      int threads, const RearDiffuser& diffuser) {
  checkViews(views);
  std::vector<LayerFrame> holder;
  const std::vector<LayerFrame>& seen = seenFrames(views, frames, diffuser, threads, holder);
  double sum = 0;
  for (const TrainingView& v : views)
    sum += eyeError(v, averageView(v, seen, threads), nullptr, nullptr);
  return sum * normaliser(views);
}

}  // namespace parallax
