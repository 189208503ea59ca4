// factorizeLayers (layer_factorization.h).
#include "parallax/layers/layer_factorization.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "parallax/core/lane_kernel.h"
#include "parallax/core/parallel.h"
#include "parallax/layers/layer_numerics.h"

namespace parallax {

namespace {

using namespace layer_numerics;

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

}  // namespace

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

namespace {

// One frame set's sums of an update: numerator sum_e A^T t_e and denominator sum_e A^T V_e for
// each frame's layer being updated (A the view's derivative with respect to that layer, the
// other fixed; the 1/T of the average cancels in their ratio), made for the layer as the eyes
// see it (the seen rear layer's size).
struct UpdateSums {
  std::vector<Image> numerator, denominator;
};

// factorizeLayers' passes over the training eyes at the current frames. With the image in front
// the objective and the image's update run row by row over every eye (as optimizeImageLayer's
// passes: row buffers only, the sums per row added in row order); the mask's update gathers rear
// rows from several output rows (updateRearMasksByBlocks); with the barrier in front both go
// eye by eye over whole images.
class Factorization {
 public:
  Factorization(const std::vector<TrainingView>& views, std::vector<LayerFrame>& frames,
                int threads, const RearDiffuser& diffuser)
      : views_(views),
        frames_(frames),
        threads_(threads),
        diffuser_(diffuser),
        maskIsRear_(views.front().seen.imageInFront()) {}

  // E / (pixels x channels x eyes) at the current frames.
  double objective() const {
    if (!maskIsRear_) return layerObjective(views_, frames_, threads_, diffuser_);
    std::vector<LayerFrame> holder;
    const std::vector<LayerFrame>& seenLayers =
        seenFrames(views_, frames_, diffuser_, threads_, holder);
    return normaliser(views_) * sumOverRows(views_, threads_, [&](int j, RowWork& w) {
             // The layers stay fixed through the pass: the eyes that see row j's mask through
             // the same mask rows (one distance) share its vertical blend.
             w.scratch.keepBlends = true;
             double sum = 0;
             for (const TrainingView& v : views_) sum += frameRowError(v, seenLayers, j, w, false);
             return sum;
           });
  }

  // One multiplicative update of every frame's image (updateImages) or mask. Through a
  // diffuser the views see G rear: the front's A holds G rear, and the rear's A is P_rear G,
  // so its sums pass through G^T = G (S^T G through the rear's colour filters: non-negative,
  // so the updates stay multiplicative and never increase E). Returns E at the layers it
  // started from where its pass made it (the image's update with the image in front), else NaN.
  double update(bool updateImages) {
    std::vector<LayerFrame> holder;
    const std::vector<LayerFrame>& seenLayers =
        seenFrames(views_, frames_, diffuser_, threads_, holder);
    UpdateSums sums;
    for (const LayerFrame& f : seenLayers) {
      const Image& x = updateImages ? f.image : f.mask;
      sums.numerator.emplace_back(x.width(), x.height());
      sums.denominator.emplace_back(x.width(), x.height());
    }
    double before = std::numeric_limits<double>::quiet_NaN();
    if (updateImages && maskIsRear_)
      before = imageSumsByRows(seenLayers, sums);
    else if (maskIsRear_)
      rearMaskSumsByBlocks(seenLayers, sums);
    else
      sumsByEyes(seenLayers, updateImages, sums);
    applyUpdate(updateImages, sums);
    return before;
  }

 private:
  // The image's sums with the image in front, row by row over every eye: each frame's mask as
  // the eye sees it through the row (made once for the view and both sums), the average view
  // V, E at these layers (returned: the objective the previous iteration left), and B^T t and
  // B^T V, which every frame's sums share.
  double imageSumsByRows(const std::vector<LayerFrame>& seenLayers, UpdateSums& sums) const {
    const size_t width = size_t(views_.front().seen.width());
    return normaliser(views_) * sumOverRows(views_, threads_, [&](int j, RowWork& w) {
             w.scratch.keepBlends = true;  // as in `objective`
             double sum = 0;
             for (const TrainingView& v : views_) {
               sum += frameRowError(v, seenLayers, j, w, true);
               v.seen.boxTransposedRowInto(w.seen.data(), w.weights.data());
               for (size_t t = 0; t < frames_.size(); ++t) {
                 const Vec3f* m = w.frameMasks.data() + t * width;
                 addProductsLanes(&w.residual[0].x, &m[0].x, &sums.numerator[t].at(0, j).x,
                                  3 * width);
                 addProductsLanes(&w.weights[0].x, &m[0].x, &sums.denominator[t].at(0, j).x,
                                  3 * width);
               }
             }
             return sum;
           });
  }

  // An (output row, mask row) pair of a group of eyes: the output row's share of B^T t and
  // B^T V along a mask row goes to that mask row times its vertical weight, for one of the
  // pupil's sights (SeenLayers::sights: each meets the mask rows with its own weights).
  struct Share {
    int outputRow, maskRow;
    float weight;
    int sight;
  };

  // The mask's (rear) sums with the image in front, by blocks of mask rows, each block's sums
  // gathered from the output rows that meet its rows (SeenLayers::rearRowSources). The eyes at
  // one distance see every output row through the same mask rows with the same weights (their
  // lines of sight differ along x only), so they go as a group (groupShares). Every mask row
  // receives them by group, then output row, in order, whatever the blocks: the same sums for
  // any thread count. Blocks of up to 32 rows (an output row meets about two mask rows, mostly
  // of one block: its views are made again for each block it meets); blocks in parallel write
  // disjoint rows, and no full-size temporaries.
  void rearMaskSumsByBlocks(const std::vector<LayerFrame>& seenLayers, UpdateSums& sums) const {
    const int width = views_.front().seen.width(), rearRows = seenLayers.front().mask.height();
    parallelFor(rearRows, threads_, 32, [&](int64_t begin, int64_t end) {
      RowWork w(width);
      w.scratch.keepBlends = true;  // the layers stay fixed through the pass
      std::vector<Share> shares;
      std::vector<Vec3f> alongRow;
      const auto sameSources = [&](const TrainingView& a, const TrainingView& b) {
        for (int64_t r = begin; r != end; ++r)
          if (a.seen.rearRowSources(int(r)) != b.seen.rearRowSources(int(r))) return false;
        return true;
      };
      for (size_t first = 0, last = 0; first < views_.size(); first = last) {
        last = first + 1;
        while (last < views_.size() && sameSources(views_[first], views_[last])) ++last;
        // The group's (output row, mask row) pairs by output row, each output row's mask rows
        // in row order.
        shares.clear();
        for (int64_t r = begin; r != end; ++r)
          for (const auto& [j, weight, sight] : views_[first].seen.rearRowSources(int(r)))
            shares.push_back({j, int(r), weight, sight});
        std::stable_sort(shares.begin(), shares.end(),
                         [](const Share& a, const Share& b) { return a.outputRow < b.outputRow; });
        groupShares(seenLayers, first, last, shares, w, alongRow, sums);
      }
    });
  }

  // One group's shares (eyes first .. last - 1, `shares` by output row) added to the mask rows'
  // sums: for each output row the group's shares of B^T t and B^T V along a mask row, per
  // sight and frame, are added up eye by eye (each eye's view of the row made once, its mask
  // blend shared), then added to each mask row it meets times that row's vertical weight, once
  // for the whole group.
  void groupShares(const std::vector<LayerFrame>& seenLayers, size_t first, size_t last,
                   const std::vector<Share>& shares, RowWork& w, std::vector<Vec3f>& alongRow,
                   UpdateSums& sums) const {
    const size_t sights = size_t(views_.front().seen.sights());
    const size_t maskWidth = size_t(seenLayers.front().mask.width());
    const size_t shareSize = 2 * frames_.size() * maskWidth;  // one sight's
    for (size_t k = 0; k < shares.size(); ++k) {
      const int j = shares[k].outputRow;
      if (k == 0 || shares[k - 1].outputRow != j) {
        alongRow.assign(sights * shareSize, Vec3f(0.0f));
        for (size_t e = first; e < last; ++e) {
          const TrainingView& v = views_[e];
          averageViewRow(v, seenLayers, j, w);
          v.boxedTargetRow(j, w.residual.data(), w.other.data());
          v.seen.boxTransposedRowInto(w.seen.data(), w.weights.data());
          for (size_t sight = 0; sight < sights; ++sight)
            for (size_t t = 0; t < frames_.size(); ++t) {
              const Image& front = seenLayers[t].image;
              Vec3f* into = &alongRow[sight * shareSize + 2 * t * maskWidth];
              v.seen.addRearGradientFromRow(w.residual.data(), front, j, 1.0f, into, int(sight));
              v.seen.addRearGradientFromRow(w.weights.data(), front, j, 1.0f, into + maskWidth,
                                            int(sight));
            }
        }
      }
      const int r = shares[k].maskRow;
      const float weight = shares[k].weight;
      const Vec3f* sightShares = &alongRow[size_t(shares[k].sight) * shareSize];
      for (size_t t = 0; t < frames_.size(); ++t) {
        float* num = &sums.numerator[t].at(0, r).x;
        float* den = &sums.denominator[t].at(0, r).x;
        const float* numShare = &sightShares[2 * t * maskWidth].x;
        const float* denShare = &sightShares[(2 * t + 1) * maskWidth].x;
        addScaledLanes(numShare, weight, num, 3 * maskWidth);
        addScaledLanes(denShare, weight, den, 3 * maskWidth);
      }
    }
  }

  // Either layer's sums with the barrier in front: eye by eye over whole images.
  void sumsByEyes(const std::vector<LayerFrame>& seenLayers, bool updateImages,
                  UpdateSums& sums) const {
    for (const TrainingView& v : views_) {
      const Image seen = averageView(v, seenLayers, threads_);
      Image decoded;
      const Image& target = v.linearTarget(decoded, threads_);
      for (size_t t = 0; t < frames_.size(); ++t) {
        const LayerFrame& f = seenLayers[t];
        const Image& other = updateImages ? f.mask : f.image;
        addLayerGradient(v, target, other, sums.numerator[t], updateImages, threads_);
        addLayerGradient(v, seen, other, sums.denominator[t], updateImages, threads_);
      }
    }
  }

  // x <- overRelaxedUpdate(x, x num / den), clamped to [0, 1], for every frame's layer; the
  // rear layer's sums first through the diffuser's transpose.
  void applyUpdate(bool updateImages, UpdateSums& sums) {
    constexpr float kTiny = 1e-12f;
    const bool rearUpdated = updateImages != maskIsRear_;
    for (size_t t = 0; t < frames_.size(); ++t) {
      if (rearUpdated && diffuser_.active()) {
        sums.numerator[t] = diffuser_.applyTransposed(sums.numerator[t], threads_);
        sums.denominator[t] = diffuser_.applyTransposed(sums.denominator[t], threads_);
      }
      Image& x = updateImages ? frames_[t].image : frames_[t].mask;
      for (size_t i = 0; i < x.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c) {
          const float num = std::max(sums.numerator[t].pixels()[i][c], 0.0f);
          const float den = sums.denominator[t].pixels()[i][c];
          // A pixel no eye sees (den = 0) keeps its value.
          if (den > kTiny) {
            float& v = x.pixels()[i][c];
            v = overRelaxedUpdate(v, v * (num / den));
          }
        }
      clampToUnit(x);
    }
  }

  const std::vector<TrainingView>& views_;
  std::vector<LayerFrame>& frames_;
  int threads_;
  const RearDiffuser& diffuser_;
  bool maskIsRear_;
};

}  // namespace

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
  Factorization passes(views, frames, threads, diffuser);
  SolveReport local;
  // With the image in front the image update's pass also evaluates E at the layers it starts
  // from (the start's, then the objective the previous iteration left): only the last needs a
  // pass of its own. Otherwise the start's E takes one too.
  const bool startInFirstUpdate = maskIsRear && iterations > 0;
  if (!startInFirstUpdate) {
    local.objective.push_back(passes.objective());
    local.passes = 1;
  }
  for (int it = 0; it < iterations; ++it) {
    const double before = passes.update(true);
    if (it == 0 && startInFirstUpdate) local.objective.push_back(before);
    if (it > 0) {
      if (std::isnan(before)) {
        local.objective.push_back(passes.objective());
        ++local.passes;
      } else {
        local.objective.push_back(before);
      }
      ++local.iterations;
      if (progress) progress(local.iterations, iterations, local.objective.back());
    }
    passes.update(false);
    local.passes += 2;
  }
  if (iterations > 0) {
    local.objective.push_back(passes.objective());
    ++local.passes;
    ++local.iterations;
    if (progress) progress(local.iterations, iterations, local.objective.back());
  }
  if (report) *report = local;
  return frames;
}

}  // namespace parallax
