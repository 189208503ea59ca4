// optimizeImageLayer (image_layer_solver.h): the passes over every training eye, the descent
// and the rows solved on their own.
#include "parallax/layers/image_layer_solver.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <stdexcept>

#include "parallax/core/lane_kernel.h"
#include "parallax/core/parallel.h"
#include "parallax/image/srgb_arithmetic.h"
#include "parallax/layers/layer_numerics.h"

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

using namespace layer_numerics;
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

}  // namespace parallax
