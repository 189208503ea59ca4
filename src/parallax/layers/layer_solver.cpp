#include "parallax/layers/layer_solver.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <stdexcept>

#include "parallax/core/lane_kernel.h"
#include "parallax/core/parallel.h"
#include "parallax/image/srgb_arithmetic.h"
#include "parallax/sim/diffuser.h"

namespace parallax {

namespace detail {
PlaneStep planeStep(double gd, double gp, Curvatures h) {
  PlaneStep step{-gd / h.dd, 0.0};
  // The sampled rows' sums scaled to all rows.
  if (h.ddSampled > 0) {
    const double scale = h.dd / h.ddSampled;
    h.dp *= scale, h.pp *= scale;
  }
  const double det = h.dd * h.pp - h.dp * h.dp;
  // Degenerate below a millionth of the product (p within a thousandth of a radian of d, in
  // the model's metric).
  if (!(h.pp > 0) || !(det > 1e-6 * h.dd * h.pp)) return step;
  const double a = (-gd * h.pp + gp * h.dp) / det, b = (gd * h.dp - gp * h.dd) / det;
  // A descent direction: its slope a <g, d> + b <g, p> = -(model decrease) x 2 < 0.
  if (std::isfinite(a) && std::isfinite(b) && a * gd + b * gp < 0) step = {a, b};
  return step;
}

}  // namespace detail

namespace {

using detail::Curvatures;
using detail::PlaneStep;
using detail::planeStep;

// optimizeImageLayer's whole-image steps (the barrier in front): the curvatures that involve the
// previous step p are sums over every planeRowStride-th row only (scaled by the ratio of
// <d, d>'s full and sampled sums): they set
// only how much of p the step takes, which the solve's objective shows is as good from a
// quarter of the rows (540p, 7 iterations: 4.55813e-4 against 4.55803e-4 from every row), and
// the view of p every eye needs for them then costs a quarter of one. Images of fewer rows
// than a few hundred use every row (a 2-row one sampled at row 0 took 30 iterations to come
// within 1.3 % of its minimum instead of 0.01 %).
int planeRowStride(int rows) {
  return rows >= 256 ? 4 : 1;
}

// The view of one image and mask pair, whichever layer is in front.
Image viewOf(const SeenLayers& seen, const Image& image, const Image& mask, int threads) {
  return seen.imageInFront() ? seen.view(image, mask, threads) : seen.view(mask, image, threads);
}

void clampToUnit(Image& image) {
  for (Vec3f& p : image.pixels())
    for (int c = 0; c < 3; ++c) p[c] = std::clamp(std::isfinite(p[c]) ? p[c] : 0.0f, 0.0f, 1.0f);
}

// TrainingView::encodedTarget's unit: S in [0, 1] as 0 .. 65535.
constexpr float kEncodedUnit = 65535.0f, kInverseEncodedUnit = 1.0f / 65535.0f;

// Running sums of squares are kept in kLanes lanes, added in lane order at the end.
constexpr int kLanes = 16;

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

constexpr size_t kPrefetchCodes = 512;

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

// One eye's error E_e for its view `seen`, and optionally the residual dE_e/dV (what the
// adjoint takes) and the Gauss-Newton weights (E_e's curvature along V). In linear light
// E_e = 1/2 |V - t|^2 (residual V - t, weights 1); with TrainingView::encodingScale c > 0,
// E_e = 1/2 |S(V/c) - S(t/c)|^2, the dense measure's own squared error (residual
// S'(V/c)/c (S(V/c) - S(t/c)), weights (S'(V/c)/c)^2).
// eyeError on `count` values from offset `first` of the view: the error, and the residual and
// weights of those values (either may be null).
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
double dot(const Image& a, const Image& b, int rowStride = 1) {
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
void checkViews(const std::vector<TrainingView>& views, bool boxedTargets = false) {
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

// One worker's row buffers for the passes that run row by row (output row j of every eye's
// view depends on the front layer's row j only, and writes only its gradient's row j).
struct RowWork {
  explicit RowWork(int width)
      : seen(size_t(width)),
        residual(size_t(width)),
        weights(size_t(width)),
        other(size_t(width)),
        seenRear(size_t(width)) {}
  size_t first(int row) const { return size_t(row) * seen.size(); }
  std::vector<Vec3f> seen, residual, weights, other, seenRear;
  std::vector<Vec3f> frameMasks;  // factorizeLayers: every frame's seen mask row
  std::vector<Vec3f> eyeWeights;  // ImageLayerPasses::rowPass: every eye's W_e row
  std::vector<Vec3f> ones;        // ImageLayerPasses::rowPass: a row of 1 (the preconditioner)
  SeenLayers::RowScratch scratch;
};

// body(row, work) for every view row, in parallel, `grain` rows to a task; the rows' results
// (a double, or anything with +=) added in row order, so the sum is the same for any thread
// count.
template <class Result = double, class Body>
Result sumOverRows(const std::vector<TrainingView>& views, int threads, const Body& body,
                   int grain = 2) {
  const int width = views.front().seen.width(), rows = views.front().seen.height();
  std::vector<Result> perRow(size_t(rows), Result{});
  parallelFor(rows, threads, grain, [&](int64_t begin, int64_t end) {
    RowWork work(width);
    for (int64_t row = begin; row != end; ++row) perRow[size_t(row)] = body(int(row), work);
  });
  Result sum{};
  for (const Result& v : perRow) sum += v;
  return sum;
}

// The projected, preconditioned descent direction of optimizeImageLayer over n values:
// d = -P g, except 0 where x sits at a bound of [0, 1] and g points out of it; the previous
// step p (when given) projected the same way, in place.
void projectedDirections(const Vec3f* x, const Vec3f* grad, const Vec3f* precondition, Vec3f* d,
                         Vec3f* previousStep, size_t n) {
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const float value = x[i][c], g = grad[i][c];
      const bool stuck = (value <= 0.0f && g > 0.0f) || (value >= 1.0f && g < 0.0f);
      d[i][c] = stuck ? 0.0f : -g * precondition[i][c];
      if (previousStep && stuck) previousStep[i][c] = 0.0f;
    }
}

// The diagonal preconditioner from the curvature diagonal, in place: 1 / c where c > 0, else 0.
void invertCurvature(Vec3f* curvature, size_t n) {
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      curvature[i][c] = curvature[i][c] > 0.0f ? 1.0f / curvature[i][c] : 0.0f;
}

// One eye-row's share of the curvatures on the plane of d and p: <A_e d, A_e d>, and with
// A_e p's row also <A_e d, A_e p> and <A_e p, A_e p>, weighted by W_e (1 in linear light:
// `weights` is then not read), n pixels. One pass over the rows, 16 values at a time as
// FloatLanes16 (one 512-bit register in the x86-64-v4 clone), the last ones in zeroed lanes
// (adding +0 changes no sum); each product summed in 16 running sums in float over the row
// (value k in lane k mod 16: a row's 5760 values are 360 terms a lane, within a few
// millionths of the exact sum, and only the step's length depends on it), added in lane order
// in double (the same sums for any thread count).
template <bool kWithP>
[[gnu::always_inline]] inline void addPlaneProducts(const float* ad, const float* ap,
                                                    const float* w, size_t count, bool srgb,
                                                    FloatLanes16& dd, FloatLanes16& dp,
                                                    FloatLanes16& pp) {
  FloatLanes16 d{}, weight{};
  std::memcpy(&d, ad, sizeof(float) * count);
  if (srgb) std::memcpy(&weight, w, sizeof(float) * count);
  const FloatLanes16 wd = srgb ? d * weight : d;
  dd += wd * d;
  if constexpr (kWithP) {
    FloatLanes16 p{};
    std::memcpy(&p, ap, sizeof(float) * count);
    dp += wd * p;
    pp += (srgb ? p * weight : p) * p;
  }
}

[[gnu::always_inline]] inline double sumLanes(const FloatLanes16& lanes) {
  double sum = 0;
  for (int l = 0; l < 16; ++l) sum += double(lanes[l]);
  return sum;
}

// from + k, or null where `from` is (w and ap when not read: no offset is added to null).
[[gnu::always_inline]] inline const float* at(const float* from, size_t k) {
  return from ? from + k : from;
}

template <bool kWithP>
[[gnu::always_inline]] inline Curvatures planeProductsLoop(const float* ad, const float* ap,
                                                           const float* w, size_t values,
                                                           bool srgb) {
  FloatLanes16 dd{}, dp{}, pp{};
  size_t k = 0;
  for (; k + 16 <= values; k += 16)
    addPlaneProducts<kWithP>(ad + k, at(ap, k), at(w, k), 16, srgb, dd, dp, pp);
  if (k < values)
    addPlaneProducts<kWithP>(ad + k, at(ap, k), at(w, k), values - k, srgb, dd, dp, pp);
  Curvatures sums;
  sums.dd = sumLanes(dd);
  if (kWithP) sums.ddSampled = sums.dd, sums.dp = sumLanes(dp), sums.pp = sumLanes(pp);
  return sums;
}

// viewOfP null: the sums with p stay 0 (and so does ddSampled).
PARALLAX_LANE_KERNEL
Curvatures planeProducts(const Vec3f* viewOfD, const Vec3f* viewOfP, const Vec3f* weights, size_t n,
                         bool srgb) {
  const float* w = srgb ? &weights[0].x : nullptr;
  return viewOfP ? planeProductsLoop<true>(&viewOfD[0].x, &viewOfP[0].x, w, 3 * n, srgb)
                 : planeProductsLoop<false>(&viewOfD[0].x, nullptr, w, 3 * n, srgb);
}

// The average view of the frames (image in front) on row j into w.seen, with every frame's mask
// as the eye sees it through the row kept in w.frameMasks (for the sums that follow).
void averageViewRow(const TrainingView& v, const std::vector<LayerFrame>& frames, int j,
                    RowWork& w) {
  const size_t width = w.seen.size(), values = 3 * width;
  w.frameMasks.resize(frames.size() * width);
  for (size_t t = 0; t < frames.size(); ++t) {
    Vec3f* m = w.frameMasks.data() + t * width;
    v.seen.seenRearRow(frames[t].mask, j, m, w.scratch);
    std::vector<Vec3f>& into = t == 0 ? w.seen : w.other;
    v.seen.viewRowSeen(&frames[t].image.at(0, j), m, into.data(), w.scratch);
    if (t > 0) addScaledLanes(&w.other[0].x, 1.0f, &w.seen[0].x, values);
  }
  if (frames.size() > 1) scaleLanes(&w.seen[0].x, 1.0f / float(frames.size()), values);
}

// factorizeLayers' pass over eye v's row j with the image in front: averageViewRow (the view
// V_j in w.seen, the seen masks in w.frameMasks, made once for the view and both updates' sums)
// and E_j at these layers; with `withBoxedTarget` also B^T t_j (w.residual), which a boxed
// target (TrainingView::boxedTarget) needs for E_j anyway:
// E_j = |V_j|^2 / 2 - <P_j, B^T t_j> + |t_j|^2 / 2 with P_j = sum_t front_t,j .* m_t,j / T.
double frameRowError(const TrainingView& v, const std::vector<LayerFrame>& frames, int j,
                     RowWork& w, bool withBoxedTarget) {
  averageViewRow(v, frames, j, w);
  const size_t width = w.seen.size(), values = 3 * width;
  if (withBoxedTarget || v.boxedTarget) v.boxedTargetRow(j, w.residual.data(), w.other.data());
  if (!v.boxedTarget) return eyeErrorRange(v, w.seen.data(), w.first(j), width, nullptr, nullptr);
  double cross = 0;
  for (size_t t = 0; t < frames.size(); ++t)
    cross += sumOfProductsLanes(&frames[t].image.at(0, j).x, &w.frameMasks[t * width].x,
                                &w.residual[0].x, values);
  return 0.5 * sumOfProductsLanes(&w.seen[0].x, &w.seen[0].x, nullptr, values) -
         cross / double(frames.size()) + 0.5 * v.rowTargetSquares[size_t(j)];
}

// Whether each image row is a problem of its own for optimizeImageLayer: with the image in
// front, output row j of every eye's view depends on the image's row j only (the mask fixed),
// so E is a sum of one term per row, each a function of its row alone.
bool rowsSeparable(const std::vector<TrainingView>& views) {
  return std::all_of(views.begin(), views.end(),
                     [](const TrainingView& v) { return v.seen.imageInFront(); });
}

// Each eye's view of a fixed mask over the rows a solve works on (ImageLayerPasses): one float
// a pixel for a grey mask seen grey, else three; kept by the caller across bands of rows so that
// their blocks are not handed back and touched anew for every band.
struct SeenMasks {
  std::vector<UninitializedLargeVector<float>> grey;
  std::vector<UninitializedLargeVector<Vec3f>> colour;
};

// The passes of optimizeImageLayer over every training eye. When the image layer is in front
// (the barrier behind it, the default order) output row j of every eye's view depends on the
// image's row j only, so each row is a problem of its own (rowsSeparable), solved by rowPass: one
// task walks every eye's view, residual and adjoint for that row in turn, with buffers of one
// row (solveRowsSeparately). Otherwise (the barrier in front) the whole-image operators, eye by
// eye (addGradientAndStep).
class ImageLayerPasses {
 public:
  int passes() const { return passes_; }
  // `byRows`: rows solved on their own by rowPass (rowsSeparable only); false: the whole-image
  // passes of addGradientAndStep, in either order (also the tests' second code path).
  // `mask`: as the eyes see it (already through the diffuser when the mask is the rear layer).
  // `diffuser`: applied to the image when the image is the rear layer (the barrier in front).
  // `firstRow`, `rows`: the image rows solved (byRows only; rows < 0: to the last),
  // for which the views hold targets and the grey mask's views are made.
  // `store`: where the seen masks are kept (none: in the passes themselves).
  ImageLayerPasses(const std::vector<TrainingView>& views, const Image& mask, int threads,
                   bool byRows, const RearDiffuser& diffuser, int firstRow = 0, int rows = -1,
                   SeenMasks* store = nullptr)
      : views_(views),
        mask_(mask),
        threads_(threads),
        firstRow_(firstRow),
        seenMasks_(store ? store->grey : ownSeenMasks_.grey),
        seenColourMasks_(store ? store->colour : ownSeenMasks_.colour) {
    const bool imageInFront = rowsSeparable(views);
    if (!imageInFront && diffuser.active()) imageBlur_ = &diffuser;
    rowSeparable_ = byRows && imageInFront;
    // A grey mask (every barrier the paper draws) is seen grey: each eye's view of it, one
    // float per pixel, is made once here for the whole solve instead of once per pass.
    const bool grey = std::all_of(mask.pixels().begin(), mask.pixels().end(),
                                  [](const Vec3f& p) { return p.x == p.y && p.y == p.z; });
    if (rows < 0) rows = views.front().seen.height() - firstRow;
    // Through colour filters (or a tinted mask) it is seen in colour: three floats a pixel,
    // kept for a band of rows (optimizeImageLayerByBands) only.
    const bool greySeen = grey && views.front().seen.seesGreyAsGrey();
    const bool kept = rowSeparable_ && (greySeen || rows <= kTargetBandRows);
    // The store's vectors keep their blocks from band to band (only the kind in use is kept).
    seenMasks_.resize(kept && greySeen ? views.size() : 0);
    seenColourMasks_.resize(kept && !greySeen ? views.size() : 0);
    if (kept) {
      const int width = views.front().seen.width();
      // Sized without being written: the row tasks below touch their pages first, in parallel
      // (a band's blocks again after the first band's: no new pages).
      const size_t values = size_t(width) * size_t(rows);
      for (UninitializedLargeVector<float>& seenMask : seenMasks_) seenMask.resize(values);
      for (UninitializedLargeVector<Vec3f>& seenMask : seenColourMasks_) seenMask.resize(values);
      parallelFor(rows, threads, 2, [&](int64_t begin, int64_t end) {
        std::vector<Vec3f> row(static_cast<size_t>(width));
        SeenLayers::RowScratch scratch;
        for (int64_t k = begin; k != end; ++k)
          for (size_t e = 0; e < views.size(); ++e) {
            const size_t first = size_t(k) * size_t(width);
            if (!greySeen) {
              views[e].seen.seenRearRow(mask, firstRow + int(k), &seenColourMasks_[e][first],
                                        scratch);
              continue;
            }
            views[e].seen.seenRearRow(mask, firstRow + int(k), row.data(), scratch);
            float* into = seenMasks_[e].data() + first;
            for (int i = 0; i < width; ++i) into[i] = row[size_t(i)].x;
          }
      });
    }
  }

  // What an iteration needs at the point x: E at x (returned as `energy`), its gradient (added
  // to `grad`, zero on entry), the descent direction d there (projectedDirections with
  // `precondition`, which also projects the previous step p when one is given) and the
  // curvatures of E's Gauss-Newton model on the plane of d and p: sum_e <A_e u, A_e v>_{W_e}
  // for u, v in {d, p}.
  struct Point {
    double energy = 0;
    Curvatures curvatures;
  };
  // Over the whole image, eye by eye (byRows false). With `makePreconditioner` (the
  // first point) `precondition` (zero on entry) is made first: addCurvatureDiagonal, inverted.
  Point addGradientAndStep(const Image& x, Image& grad, Image& precondition, Image& d,
                           Image* previousStep, bool makePreconditioner = false) const {
    if (rowSeparable_) throw std::logic_error("ImageLayerPasses: the rows are solved separately");
    if (makePreconditioner) {
      addCurvatureDiagonal(x, precondition);
      invertCurvature(precondition.pixels().data(), precondition.pixels().size());
    }
    Point point;
    point.energy = addGradient(x, grad);
    projectedDirections(x.pixels().data(), grad.pixels().data(), precondition.pixels().data(),
                        d.pixels().data(), previousStep ? previousStep->pixels().data() : nullptr,
                        d.pixels().size());
    point.curvatures = curvatures(x, d, previousStep);
    return point;
  }

  // addGradientAndStep for image row j alone (byRows only), in one pass over the eyes'
  // rows: its rows given by pointer (x, grad, precondition, d: the image's width each; p the
  // previous step's row, or null). Row j of the gradient is whole once every eye has added its
  // adjoint to it, so d follows, and every eye's view of it (and of p) is weighted by the W_e
  // already made for the residual: the curvatures cost one view per eye and direction, not a
  // pass of their own. With `makePreconditioner` the preconditioner's row first (every eye's
  // share of sum_e A_e^T W_e A_e 1, then inverted).
  Point rowPass(int j, const Vec3f* x, Vec3f* grad, Vec3f* precondition, Vec3f* d, Vec3f* p,
                bool makePreconditioner, RowWork& w) const {
    const size_t width = w.seen.size();
    if (makePreconditioner) w.ones.assign(width, Vec3f(1.0f));
    w.eyeWeights.resize(views_.size() * width);
    Point point;
    for (size_t e = 0; e < views_.size(); ++e) {
      const TrainingView& v = views_[e];
      Vec3f* weights = w.eyeWeights.data() + e * width;
      withSeenMask(e, j, w, [&](const auto* m) {
        v.seen.viewRowSeen(x, m, w.seen.data(), w.scratch);
        point.energy += eyeErrorRange(v, w.seen.data(), w.first(j - v.firstTargetRow), width,
                                      w.residual.data(), weights);
        v.seen.addFrontGradientRowSeen(w.residual.data(), m, grad, w.scratch);
        if (makePreconditioner) {
          v.seen.viewRowSeen(w.ones.data(), m, w.other.data(), w.scratch);
          multiplyLanes(&w.other[0].x, &weights[0].x, &w.other[0].x, 3 * width);
          v.seen.addFrontGradientRowSeen(w.other.data(), m, precondition, w.scratch);
        }
      });
    }
    if (makePreconditioner) invertCurvature(precondition, width);
    projectedDirections(x, grad, precondition, d, p, width);
    for (size_t e = 0; e < views_.size(); ++e) {
      const TrainingView& v = views_[e];
      const Vec3f* weights = w.eyeWeights.data() + e * width;
      const bool srgb = v.encodingScale > 0;
      withSeenMask(e, j, w, [&](const auto* m) {
        v.seen.viewRowSeen(d, m, w.other.data(), w.scratch);
        // w.seen (this eye's view of x) is free again: it holds A_e p's row.
        if (p) v.seen.viewRowSeen(p, m, w.seen.data(), w.scratch);
        point.curvatures +=
            planeProducts(w.other.data(), p ? w.seen.data() : nullptr, weights, width, srgb);
      });
    }
    return point;
  }

 private:
  // The whole-image passes (the barrier in front, or the tests' second code path), which
  // addGradientAndStep runs.
  // grad += sum_e A_e^T dE_e/dV_e at the image x; returns sum_e E_e there.
  double addGradient(const Image& x, Image& grad) const {
    ++passes_;
    Image holder, blurredSum;
    const Image& xs = seen(x, holder);
    Image& into = throughDiffuser(grad, blurredSum);
    double sum = 0;
    for (const TrainingView& v : views_) {
      Image residual(v.seen.width(), v.seen.height());
      sum += eyeError(v, viewOf(v.seen, xs, mask_, threads_), &residual, nullptr);
      addImageGradient(v, residual, mask_, into, threads_);
    }
    if (imageBlur_) addScaled(grad, imageBlur_->applyTransposed(blurredSum, threads_), 1.0f);
    return sum;
  }

  // sum_e <A_e u, A_e v> weighted by E_e's Gauss-Newton weights at x (1 in linear light), for
  // u, v in {d, p} (p may be absent: its sums stay 0).
  Curvatures curvatures(const Image& x, const Image& d, const Image* p) const {
    ++passes_;
    Image holderX, holderD, holderP;
    const Image& xs = seen(x, holderX);
    const Image& ds = seen(d, holderD);
    const Image* ps = p ? &seen(*p, holderP) : nullptr;
    Curvatures sum;
    for (const TrainingView& v : views_) {
      const Image ad = viewOf(v.seen, ds, mask_, threads_);
      const Image ap = ps ? viewOf(v.seen, *ps, mask_, threads_) : Image();
      Image weights(v.seen.width(), v.seen.height(), Vec3f(1.0f));
      if (v.encodingScale > 0) eyeError(v, viewOf(v.seen, xs, mask_, threads_), nullptr, &weights);
      const Image wad = elementwise(ad, weights);
      sum.dd += dot(ad, wad);
      if (!ps) continue;
      sum.ddSampled += dot(ad, wad, planeRowStride_);
      sum.dp += dot(ap, wad, planeRowStride_);
      sum.pp += dot(ap, elementwise(ap, weights), planeRowStride_);
    }
    return sum;
  }

  // out += sum_e A_e^T (A_e 1 .* W_e), W_e the Gauss-Newton weights at x.
  void addCurvatureDiagonal(const Image& x, Image& out) const {
    ++passes_;
    const Image ones(x.width(), x.height(), Vec3f(1.0f));
    Image holderX, holderOnes, blurredSum;
    const Image& xs = seen(x, holderX);
    const Image& onesSeen = seen(ones, holderOnes);
    Image& into = throughDiffuser(out, blurredSum);
    for (const TrainingView& v : views_) {
      Image weights(v.seen.width(), v.seen.height());
      eyeError(v, viewOf(v.seen, xs, mask_, threads_), nullptr, &weights);
      addImageGradient(v, elementwise(viewOf(v.seen, onesSeen, mask_, threads_), weights), mask_,
                       into, threads_);
    }
    if (imageBlur_) addScaled(out, imageBlur_->applyTransposed(blurredSum, threads_), 1.0f);
  }

  // The image as the eyes see it: through the diffuser when it is the rear layer.
  const Image& seen(const Image& x, Image& holder) const {
    if (!imageBlur_) return x;
    holder = imageBlur_->apply(x, threads_);
    return holder;
  }
  // Where the eyes' sums for the image go: straight into `out`, or (the image blurred) into a
  // zeroed `blurredSum` (the seen image's size), which the caller then adds to `out` through
  // the diffuser's transpose.
  Image& throughDiffuser(Image& out, Image& blurredSum) const {
    if (!imageBlur_) return out;
    blurredSum = Image(imageBlur_->seenColumns(out.width()), out.height());
    return blurredSum;
  }

  // body(m) with the fixed rear layer as eye e sees it through front row j
  // (SeenLayers::seenRearRow): a grey row of seenMasks_ (one float a pixel, which the view and
  // its adjoint read as every channel's), else made in w.seenRear once per eye and row for every
  // view and adjoint of that row.
  template <class Body>
  void withSeenMask(size_t e, int j, RowWork& w, const Body& body) const {
    if (!seenMasks_.empty()) return body(seenMasks_[e].data() + w.first(j - firstRow_));
    if (!seenColourMasks_.empty())
      return body(static_cast<const Vec3f*>(seenColourMasks_[e].data() + w.first(j - firstRow_)));
    views_[e].seen.seenRearRow(mask_, j, w.seenRear.data(), w.scratch);
    body(static_cast<const Vec3f*>(w.seenRear.data()));
  }

  const std::vector<TrainingView>& views_;
  const Image& mask_;
  int threads_;
  int firstRow_ = 0;
  int planeRowStride_ = planeRowStride(views_.front().seen.height());
  mutable int passes_ = 0;
  // Per eye, with a grey mask seen grey and the rows solved separately; the same seen in colour
  // (for a band of rows).
  SeenMasks ownSeenMasks_;
  std::vector<UninitializedLargeVector<float>>& seenMasks_;
  std::vector<UninitializedLargeVector<Vec3f>>& seenColourMasks_;
  bool rowSeparable_ = false;
  const RearDiffuser* imageBlur_ = nullptr;
};

}  // namespace

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

namespace {

// The iterations of optimizeImageLayer on the layer x: the whole image, or one row of it when
// the rows are solved separately (rowsSeparable). `pass(x, grad,
// precondition, d, p, makePreconditioner)` is ImageLayerPasses::addGradientAndStep at x (or its
// rowPass): E there (as the passes sum it, before the normaliser), its gradient, the direction
// and the curvatures. Returns E before and after each iteration; stops early where a step no
// longer lowers E. `afterIteration(done, E)` after each.
template <class Pass, class AfterIteration>
std::vector<double> descend(Image& image, int iterations, const Pass& pass,
                            const AfterIteration& afterIteration) {
  // A diagonal preconditioner: 1 / (sum_e A_e^T W_e A_e 1) at the starting layers, the
  // curvature each pixel would have if its neighbours moved with it (the scaling of SART and of
  // the multiplicative updates). It keeps pixels seen by many eyes from taking the step of
  // pixels seen by few.
  // It is made in the pass of the first gradient.
  Image precondition(image.width(), image.height());
  // Gradient of E: sum over eyes of A_e^T dE_e/dV_e, made in the pass that evaluates E: at the
  // start, then at each point the line search tries (the accepted one's is the next
  // iteration's). The projected, preconditioned direction d there (no move out of [0, 1] at a
  // bound), the previous step p projected the same way, and the curvatures on their plane come
  // from the same pass.
  const int width = image.width(), height = image.height();
  Image grad(width, height), nextGrad, d(width, height), nextD(width, height), next;
  Image p, nextP(width, height), move(width, height);
  auto point = pass(image, grad, precondition, d, nullptr, true);
  double e = point.energy;
  std::vector<double> energies{e};
  for (int it = 0; it < iterations; ++it) {
    // The exact step of the quadratic (Gauss-Newton: of its model) on the plane of d and the
    // previous step p (A_e linear in the image with the mask fixed): planeStep.
    const double slope = dot(grad, d);
    if (!(slope < 0)) break;
    if (!(point.curvatures.dd > 0)) break;
    // Along the plane's step, halved until E decreases; where that fails (the model off on
    // the plane: the weights W_e or the clamp), along d alone as steepest descent would.
    const auto lowersAlong = [&](const PlaneStep& plane) {
      for (size_t i = 0; i < move.pixels().size(); ++i)
        move.pixels()[i] = d.pixels()[i] * float(plane.a) +
                           (plane.b != 0 ? p.pixels()[i] * float(plane.b) : Vec3f(0.0f));
      float scale = 1.0f;
      for (int halving = 0; halving < 8; ++halving, scale *= 0.5f) {
        next = image;
        addScaled(next, move, scale);
        clampToUnit(next);
        // The step actually taken (after the clamp): the next iteration's p.
        for (size_t i = 0; i < nextP.pixels().size(); ++i)
          nextP.pixels()[i] = next.pixels()[i] - image.pixels()[i];
        nextGrad = Image(width, height);
        const auto nextPoint = pass(next, nextGrad, precondition, nextD, &nextP, false);
        if (nextPoint.energy < e) {
          std::swap(image, next);
          std::swap(grad, nextGrad);
          std::swap(d, nextD);
          if (p.empty()) p = Image(width, height);
          std::swap(p, nextP);
          point = nextPoint;
          e = nextPoint.energy;
          return true;
        }
      }
      return false;
    };
    const PlaneStep plane = planeStep(slope, p.empty() ? 0.0 : dot(grad, p), point.curvatures);
    const bool lowered =
        lowersAlong(plane) || (plane.b != 0 && lowersAlong({-slope / point.curvatures.dd, 0.0}));
    if (!lowered) break;
    energies.push_back(e);
    afterIteration(it + 1, e);
  }
  return energies;
}

// optimizeImageLayer with its rows solved separately (rowsSeparable): each row
// runs all its iterations in one task, with its own steps, on its eyes' rows of targets and seen
// masks (about a megabyte at 1920 pixels and 54 eyes: they stay in this core's cache through
// the row's passes instead of streaming from memory in every pass). Each row's step is the
// minimiser of its own model, where a whole-image step is one compromise for all rows.
// RowSolves keeps every row's E per iteration and its passes, and tells `progress(rows done,
// rows, the objective of the rows done so far)`.
class RowSolves {
 public:
  RowSolves(int rows, double norm, const SolveProgress& progress)
      : energies_(static_cast<size_t>(rows)),
        passes_(size_t(rows), 0),
        norm_(norm),
        progress_(progress) {}

  // Rows [firstRow, lastRow) of `image`, with `passes` made for them.
  void solve(const ImageLayerPasses& passes, Image& image, int firstRow, int lastRow,
             int iterations, int threads) {
    const int width = image.width();
    parallelFor(lastRow - firstRow, threads, 1, [&](int64_t begin, int64_t end) {
      RowWork work(width);
      Image row(width, 1);
      for (int64_t k = begin; k != end; ++k) {
        const int j = firstRow + int(k);
        std::copy_n(&image.at(0, j), width, &row.at(0, 0));
        int& count = passes_[size_t(j)];
        const auto rowPass = [&](const Image& x, Image& grad, Image& precondition, Image& d,
                                 Image* p, bool makePreconditioner) {
          ++count;
          return passes.rowPass(j, &x.at(0, 0), &grad.at(0, 0), &precondition.at(0, 0), &d.at(0, 0),
                                p ? &p->at(0, 0) : nullptr, makePreconditioner, work);
        };
        energies_[size_t(j)] = descend(row, iterations, rowPass, [](int, double) {});
        std::copy_n(&row.at(0, 0), width, &image.at(0, j));
        if (progress_) told(energies_[size_t(j)].back());
      }
    });
  }

  // E after k iterations: every row's after its k-th (or its last, where it stopped early),
  // added in row order (the same sum for any thread count); passes in passes over every row.
  void report(SolveReport& report) const {
    size_t longest = 0;
    int64_t passCount = 0;
    for (size_t j = 0; j < energies_.size(); ++j) {
      longest = std::max(longest, energies_[j].size());
      passCount += passes_[j];
    }
    report.objective.assign(longest, 0.0);
    for (size_t k = 0; k < longest; ++k) {
      for (const std::vector<double>& rowEnergies : energies_)
        report.objective[k] += rowEnergies[std::min(k, rowEnergies.size() - 1)];
      report.objective[k] *= norm_;
    }
    report.iterations = int(longest) - 1;
    const int64_t rows = int64_t(energies_.size());
    report.passes = int((passCount + rows - 1) / rows);
  }

 private:
  void told(double rowEnergy) {
    const std::lock_guard lock(mutex_);
    ++done_;
    doneEnergy_ += rowEnergy;
    const int rows = int(energies_.size());
    progress_(done_, rows, doneEnergy_ * norm_ * double(rows) / double(done_));
  }

  std::vector<std::vector<double>> energies_;
  std::vector<int> passes_;
  double norm_;
  const SolveProgress& progress_;
  std::mutex mutex_;
  int done_ = 0;
  double doneEnergy_ = 0;
};

// optimizeImageLayer's rows solved on their own, a band of `bandRows` rows at a time (all of them
// at once for whole targets): `beforeBand(firstRow, rows)` readies the views' targets for the
// band's rows, then the band's passes are made and its rows solved. `seenMask`: the mask as the
// eyes see it (through the diffuser: the mask is the rear layer).
template <class BeforeBand>
void solveRowBands(const std::vector<TrainingView>& views, Image& image, const Image& seenMask,
                   int bandRows, const BeforeBand& beforeBand, int iterations, int threads,
                   const RearDiffuser& diffuser, const SolveProgress& progress,
                   SolveReport& report) {
  const int rows = image.height();
  RowSolves solves(rows, normaliser(views), progress);
  SeenMasks seenMasks;  // every band's, in the same blocks
  for (int firstRow = 0; firstRow < rows; firstRow += bandRows) {
    const int count = std::min(bandRows, rows - firstRow);
    beforeBand(firstRow, count);
    const ImageLayerPasses passes(views, seenMask, threads, true, diffuser, firstRow, count,
                                  &seenMasks);
    solves.solve(passes, image, firstRow, firstRow + count, iterations, threads);
  }
  solves.report(report);
}

Image solveImageLayer(const std::vector<TrainingView>& views, Image image, const Image& mask,
                      int iterations, int threads, SolveReport* report,
                      const SolveProgress& progress, bool byRows, const RearDiffuser& diffuser) {
  checkViews(views);
  clampToUnit(image);
  // With the image in front the mask is the rear layer: the eyes see it through the diffuser,
  // once and for all (it is fixed). Otherwise the passes blur the image.
  const bool maskIsRear = views.front().seen.imageInFront();
  const Image seenMask = maskIsRear && diffuser.active() ? diffuser.apply(mask, threads) : mask;
  SolveReport local;
  if (byRows && rowsSeparable(views)) {
    solveRowBands(
        views, image, seenMask, image.height(), [](int, int) {}, iterations, threads, diffuser,
        progress, local);
  } else {
    const ImageLayerPasses passes(views, seenMask, threads, false, diffuser);
    const double norm = normaliser(views);
    const auto wholePass = [&](const Image& x, Image& grad, Image& precondition, Image& d, Image* p,
                               bool makePreconditioner) {
      return passes.addGradientAndStep(x, grad, precondition, d, p, makePreconditioner);
    };
    const auto afterIteration = [&](int done, double e) {
      if (progress) progress(done, iterations, e * norm);
    };
    local.objective = descend(image, iterations, wholePass, afterIteration);
    for (double& e : local.objective) e *= norm;
    local.iterations = int(local.objective.size()) - 1;
    local.passes = passes.passes();
  }
  if (report) *report = local;
  return image;
}

}  // namespace

Image optimizeImageLayerByBands(std::vector<TrainingView>& views, const BandTargets& targets,
                                int bandRows, Image image, const Image& mask, int iterations,
                                int threads, SolveReport* report, const SolveProgress& progress,
                                const RearDiffuser& diffuser) {
  if (views.empty()) throw std::invalid_argument("layer solver: no training views");
  const bool srgb = std::all_of(views.begin(), views.end(),
                                [](const TrainingView& v) { return v.encodingScale > 0; });
  if (!rowsSeparable(views) || !srgb || bandRows < 1)
    throw std::invalid_argument(
        "layer solver: bands need the image in front, sRGB errors and a band of rows");
  clampToUnit(image);
  const Image seenMask = diffuser.active() ? diffuser.apply(mask, threads) : mask;
  const size_t width = size_t(views.front().seen.width());
  const auto makeTargets = [&](int firstRow, int rows) {
    targets(firstRow, rows, views);
    for (const TrainingView& v : views)
      if (v.firstTargetRow != firstRow || v.encodedTarget.size() != 3 * width * size_t(rows))
        throw std::invalid_argument("layer solver: a band's targets are not its rows'");
  };
  SolveReport local;
  solveRowBands(views, image, seenMask, bandRows, makeTargets, iterations, threads, diffuser,
                progress, local);
  if (report) *report = local;
  return image;
}

Image optimizeImageLayer(const std::vector<TrainingView>& views, Image image, const Image& mask,
                         int iterations, int threads, SolveReport* report,
                         const SolveProgress& progress, const RearDiffuser& diffuser) {
  return solveImageLayer(views, std::move(image), mask, iterations, threads, report, progress, true,
                         diffuser);
}

namespace detail {
void srgbEncode(float x, float& encoded, float& slope) {
  srgbEncodeArithmetic(x, encoded, slope);
}

Image optimizeImageLayerByEye(const std::vector<TrainingView>& views, Image image,
                              const Image& mask, int iterations, int threads, SolveReport* report,
                              const RearDiffuser& diffuser) {
  return solveImageLayer(views, std::move(image), mask, iterations, threads, report, {}, false,
                         diffuser);
}
}  // namespace detail

float overRelaxedUpdate(float x, float multiplicative) {
  // Each multiplicative update minimises a separable quadratic upper bound Q of E that touches
  // it at x; each coordinate's term of Q is a convex quadratic symmetric about its minimiser
  // (`multiplicative`), so any point between x and x + 2 (minimiser - x), or a clamp of one
  // onto the segment from it back to x, has Q no higher than at x: E never increases for
  // kNmfOverRelaxation up to 2. The floor keeps a value from being driven to 0 faster than
  // the plain update would (a zero stays zero under multiplicative updates); the clamp to
  // [0, 1] happens after (clampToUnit), also onto the segment.
  const float over = x + kNmfOverRelaxation * (multiplicative - x);
  return std::max(over, std::min(multiplicative, kNmfShrinkFloor * x));
}

std::vector<LayerFrame> factorizeLayers(const std::vector<TrainingView>& views,
                                        std::vector<LayerFrame> frames, int iterations, int threads,
                                        SolveReport* report, const SolveProgress& progress,
                                        const RearDiffuser& diffuser) {
  const bool maskIsRear = views.front().seen.imageInFront();
  checkViews(views, maskIsRear);
  if (frames.empty()) throw std::invalid_argument("factorizeLayers: no frames");
  for (const TrainingView& v : views)
    if (v.encodingScale > 0)
      throw std::invalid_argument("factorizeLayers: multiplicative updates fit in linear light");
  for (LayerFrame& f : frames) clampToUnit(f.image), clampToUnit(f.mask);
  constexpr float kTiny = 1e-12f;
  // With the image in front the objective and the image's update run row by row over every
  // eye (as optimizeImageLayer's passes: row buffers only, the sums per row added in row
  // order); the mask's update gathers rear rows from several output rows, eye by eye.
  const auto objective = [&] {
    if (!maskIsRear) return layerObjective(views, frames, threads, diffuser);
    std::vector<LayerFrame> holder;
    const std::vector<LayerFrame>& seenLayers =
        seenFrames(views, frames, diffuser, threads, holder);
    return normaliser(views) * sumOverRows(views, threads, [&](int j, RowWork& w) {
             // The layers stay fixed through the pass: the eyes that see row j's mask through
             // the same mask rows (one distance) share its vertical blend.
             w.scratch.keepBlends = true;
             double sum = 0;
             for (const TrainingView& v : views) sum += frameRowError(v, seenLayers, j, w, false);
             return sum;
           });
  };
  SolveReport local;
  // With the image in front the first image update's pass evaluates E at the start as well (see
  // the loop below); otherwise the start's E takes a pass of its own.
  const bool startInFirstUpdate = maskIsRear && iterations > 0;
  if (!startInFirstUpdate) {
    local.objective.push_back(objective());
    local.passes = 1;
  }
  // One multiplicative update of every frame's image (updateImages) or mask: numerator
  // sum_e A^T t_e, denominator sum_e A^T V_e, where A is the view's derivative with respect to
  // that frame's layer (the other layer fixed); the 1/T of the average cancels in the ratio.
  // Through a diffuser the views see G rear: the front's A holds G rear, and the rear's A is
  // P_rear G, so its sums pass through G^T = G (S^T G through the rear's colour filters:
  // non-negative, so the updates stay multiplicative and never increase E).
  const auto update = [&](bool updateImages) {
    std::vector<LayerFrame> holder;
    const std::vector<LayerFrame>& seenLayers =
        seenFrames(views, frames, diffuser, threads, holder);
    // The sums are made for the layer as the eyes see it (the seen rear layer's size).
    std::vector<Image> numerator, denominator;
    for (const LayerFrame& f : seenLayers) {
      const Image& x = updateImages ? f.image : f.mask;
      numerator.emplace_back(x.width(), x.height());
      denominator.emplace_back(x.width(), x.height());
    }
    double before = std::numeric_limits<double>::quiet_NaN();
    if (updateImages && maskIsRear) {
      // Row by row over every eye: each frame's mask as the eye sees it through the row (made
      // once for the view and both sums), the average view V, E at these layers (the objective
      // the previous iteration left), and B^T t and B^T V, which every frame's sums share.
      const size_t width = size_t(views.front().seen.width());
      before =
          normaliser(views) * sumOverRows(views, threads, [&](int j, RowWork& w) {
            w.scratch.keepBlends = true;  // as in `objective`
            double sum = 0;
            for (const TrainingView& v : views) {
              sum += frameRowError(v, seenLayers, j, w, true);
              v.seen.boxTransposedRowInto(w.seen.data(), w.weights.data());
              for (size_t t = 0; t < frames.size(); ++t) {
                const Vec3f* m = w.frameMasks.data() + t * width;
                addProductsLanes(&w.residual[0].x, &m[0].x, &numerator[t].at(0, j).x, 3 * width);
                addProductsLanes(&w.weights[0].x, &m[0].x, &denominator[t].at(0, j).x, 3 * width);
              }
            }
            return sum;
          });
    } else if (maskIsRear) {
      // The mask (rear) update by blocks of mask rows, each block's sums gathered from the output
      // rows that meet its rows (SeenLayers::rearRowSources). The eyes at one distance see
      // every output row through the same mask rows with the same weights (their lines of
      // sight differ along x only), so they go as a group: for each output row the group's
      // shares of B^T t and B^T V along a mask row are added up eye by eye (each eye's view of
      // the row made once, its mask blend shared), then added to each mask row it meets times
      // that row's vertical weight, once for the whole group. Every mask row receives them by
      // group, then output row, in order, whatever the blocks: the same sums for any thread
      // count. Blocks of up to 32 rows (an output row meets about two mask rows, mostly of one
      // block: its views are made again for each block it meets); blocks in parallel write
      // disjoint rows, and no full-size temporaries.
      const int width = views.front().seen.width(), rearRows = seenLayers.front().mask.height();
      // A pupil's sights (SeenLayers::sights) meet the mask rows each with their own weights:
      // an output row's shares are made per sight, from the view made once.
      const size_t sights = size_t(views.front().seen.sights());
      struct Share {
        int outputRow, maskRow;
        float weight;
        int sight;
      };
      const size_t maskWidth = size_t(seenLayers.front().mask.width());
      const size_t shareSize = 2 * frames.size() * maskWidth;  // one sight's
      parallelFor(rearRows, threads, 32, [&](int64_t begin, int64_t end) {
        RowWork w(width);
        w.scratch.keepBlends = true;  // the layers stay fixed through the pass
        std::vector<Share> shares;
        std::vector<Vec3f> alongRow;
        const auto sameSources = [&](const TrainingView& a, const TrainingView& b) {
          for (int64_t r = begin; r != end; ++r)
            if (a.seen.rearRowSources(int(r)) != b.seen.rearRowSources(int(r))) return false;
          return true;
        };
        for (size_t first = 0, last = 0; first < views.size(); first = last) {
          last = first + 1;
          while (last < views.size() && sameSources(views[first], views[last])) ++last;
          // The group's (output row, mask row) pairs by output row, each output row's mask rows
          // in row order.
          shares.clear();
          for (int64_t r = begin; r != end; ++r)
            for (const auto& [j, weight, sight] : views[first].seen.rearRowSources(int(r)))
              shares.push_back({j, int(r), weight, sight});
          std::stable_sort(shares.begin(), shares.end(), [](const Share& a, const Share& b) {
            return a.outputRow < b.outputRow;
          });
          for (size_t k = 0; k < shares.size(); ++k) {
            const int j = shares[k].outputRow;
            if (k == 0 || shares[k - 1].outputRow != j) {
              // Output row j's shares of B^T t and B^T V along a mask row, per sight and
              // frame, summed over the group's eyes.
              alongRow.assign(sights * shareSize, Vec3f(0.0f));
              for (size_t e = first; e < last; ++e) {
                const TrainingView& v = views[e];
                averageViewRow(v, seenLayers, j, w);
                v.boxedTargetRow(j, w.residual.data(), w.other.data());
                v.seen.boxTransposedRowInto(w.seen.data(), w.weights.data());
                for (size_t sight = 0; sight < sights; ++sight)
                  for (size_t t = 0; t < frames.size(); ++t) {
                    const Image& front = seenLayers[t].image;
                    Vec3f* into = &alongRow[sight * shareSize + 2 * t * maskWidth];
                    v.seen.addRearGradientFromRow(w.residual.data(), front, j, 1.0f, into,
                                                  int(sight));
                    v.seen.addRearGradientFromRow(w.weights.data(), front, j, 1.0f,
                                                  into + maskWidth, int(sight));
                  }
              }
            }
            const int r = shares[k].maskRow;
            const float weight = shares[k].weight;
            const Vec3f* sightShares = &alongRow[size_t(shares[k].sight) * shareSize];
            for (size_t t = 0; t < frames.size(); ++t) {
              float* num = &numerator[t].at(0, r).x;
              float* den = &denominator[t].at(0, r).x;
              const float* numShare = &sightShares[2 * t * maskWidth].x;
              const float* denShare = &sightShares[(2 * t + 1) * maskWidth].x;
              addScaledLanes(numShare, weight, num, 3 * maskWidth);
              addScaledLanes(denShare, weight, den, 3 * maskWidth);
            }
          }
        }
      });
    } else {
      for (const TrainingView& v : views) {
        const Image seen = averageView(v, seenLayers, threads);
        Image decoded;
        const Image& target = v.linearTarget(decoded, threads);
        for (size_t t = 0; t < frames.size(); ++t) {
          const LayerFrame& f = seenLayers[t];
          const Image& other = updateImages ? f.mask : f.image;
          addLayerGradient(v, target, other, numerator[t], updateImages, threads);
          addLayerGradient(v, seen, other, denominator[t], updateImages, threads);
        }
      }
    }
    const bool rearUpdated = updateImages != maskIsRear;
    for (size_t t = 0; t < frames.size(); ++t) {
      if (rearUpdated && diffuser.active()) {
        numerator[t] = diffuser.applyTransposed(numerator[t], threads);
        denominator[t] = diffuser.applyTransposed(denominator[t], threads);
      }
      Image& x = updateImages ? frames[t].image : frames[t].mask;
      for (size_t i = 0; i < x.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c) {
          const float num = std::max(numerator[t].pixels()[i][c], 0.0f);
          const float den = denominator[t].pixels()[i][c];
          // A pixel no eye sees (den = 0) keeps its value.
          if (den > kTiny) {
            float& v = x.pixels()[i][c];
            v = overRelaxedUpdate(v, v * (num / den));
          }
        }
      clampToUnit(x);
    }
    return before;
  };
  // With the image in front the image update's pass also evaluates E at the layers it starts
  // from, the objective the previous iteration left: only the last needs a pass of its own.
  for (int it = 0; it < iterations; ++it) {
    const double before = update(true);
    if (it == 0 && startInFirstUpdate) local.objective.push_back(before);
    if (it > 0) {
      if (std::isnan(before)) {
        local.objective.push_back(objective());
        ++local.passes;
      } else {
        local.objective.push_back(before);
      }
      ++local.iterations;
      if (progress) progress(local.iterations, iterations, local.objective.back());
    }
    update(false);
    local.passes += 2;
  }
  if (iterations > 0) {
    local.objective.push_back(objective());
    ++local.passes;
    ++local.iterations;
    if (progress) progress(local.iterations, iterations, local.objective.back());
  }
  if (report) *report = local;
  return frames;
}

}  // namespace parallax
