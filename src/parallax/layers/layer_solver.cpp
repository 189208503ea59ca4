#include "parallax/layers/layer_solver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "parallax/core/parallel.h"

namespace parallax {

namespace {

// The view of one image and mask pair, whichever layer is in front.
Image viewOf(const SeenLayers& seen, const Image& image, const Image& mask, int threads) {
  return seen.imageInFront() ? seen.view(image, mask, threads) : seen.view(mask, image, threads);
}

void clampToUnit(Image& image) {
  for (Vec3f& p : image.pixels())
    for (int c = 0; c < 3; ++c) p[c] = std::clamp(std::isfinite(p[c]) ? p[c] : 0.0f, 0.0f, 1.0f);
}

// The squared slope of the sRGB encoding at x in [0, 1] (IEC 61966-2-1), tabulated on a
// square-root scale (the slope changes fastest near black).
class EncodingWeights {
 public:
  EncodingWeights() {
    for (int i = 0; i < kSize; ++i) {
      const double r = double(i) / (kSize - 1), x = r * r;
      const double slope = x <= 0.0031308 ? 12.92 : 1.055 / 2.4 * std::pow(x, 1.0 / 2.4 - 1.0);
      table_[size_t(i)] = float(slope * slope);
    }
  }
  float operator()(float x) const {
    const float r = std::sqrt(std::clamp(x, 0.0f, 1.0f));
    return table_[size_t(std::lround(r * float(kSize - 1)))];
  }

 private:
  static constexpr int kSize = 4096;
  std::array<float, kSize> table_{};
};

const EncodingWeights& encodingWeights() {
  static const EncodingWeights weights;
  return weights;
}

// W x for one eye's view-sized image (x unchanged without weights).
Image weighted(const TrainingView& v, Image x) {
  if (!(v.encodingScale > 0)) return x;
  const EncodingWeights& w = encodingWeights();
  const float inv = 1.0f / v.encodingScale;
  for (size_t i = 0; i < x.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) x.pixels()[i][c] *= w(v.target.pixels()[i][c] * inv);
  return x;
}

// 1/2 |seen - target|_W^2 for one eye.
double halfWeightedSquares(const TrainingView& v, const Image& seen) {
  const EncodingWeights& w = encodingWeights();
  const bool weigh = v.encodingScale > 0;
  const float inv = weigh ? 1.0f / v.encodingScale : 0.0f;
  double sum = 0;
  for (size_t i = 0; i < seen.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const float t = v.target.pixels()[i][c];
      const double d = double(seen.pixels()[i][c]) - double(t);
      sum += 0.5 * d * d * (weigh ? double(w(t * inv)) : 1.0);
    }
  return sum;
}

// a += s * b, a -= b, <a, b>, |a|^2 over images of one size.
void addScaled(Image& a, const Image& b, float s) {
  for (size_t i = 0; i < a.pixels().size(); ++i) a.pixels()[i] += b.pixels()[i] * s;
}
double dot(const Image& a, const Image& b) {
  double sum = 0;
  for (size_t i = 0; i < a.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) sum += double(a.pixels()[i][c]) * double(b.pixels()[i][c]);
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

void checkViews(const std::vector<TrainingView>& views) {
  if (views.empty()) throw std::invalid_argument("layer solver: no training views");
  for (const TrainingView& v : views)
    if (v.target.width() != v.seen.width() || v.target.height() != v.seen.height())
      throw std::invalid_argument("layer solver: a target's size differs from its view");
}

// The image layer's gradient: the front or the rear gradient of each eye, with the mask fixed.
void addImageGradient(const TrainingView& v, const Image& residual, const Image& mask, Image& grad,
                      int threads) {
  if (v.seen.imageInFront())
    v.seen.addFrontGradient(residual, mask, grad, threads);
  else
    v.seen.addRearGradient(residual, mask, grad, threads);
}

void addMaskGradient(const TrainingView& v, const Image& residual, const Image& image, Image& grad,
                     int threads) {
  if (v.seen.imageInFront())
    v.seen.addRearGradient(residual, image, grad, threads);
  else
    v.seen.addFrontGradient(residual, image, grad, threads);
}

}  // namespace

double layerObjective(const std::vector<TrainingView>& views, const std::vector<LayerFrame>& frames,
                      int threads) {
  checkViews(views);
  double sum = 0;
  for (const TrainingView& v : views)
    sum += halfWeightedSquares(v, averageView(v, frames, threads));
  return sum * normaliser(views);
}

Image optimizeImageLayer(const std::vector<TrainingView>& views, Image image, const Image& mask,
                         int iterations, int threads, SolveReport* report) {
  checkViews(views);
  clampToUnit(image);
  const auto energy = [&](const Image& x) {
    double sum = 0;
    for (const TrainingView& v : views)
      sum += halfWeightedSquares(v, viewOf(v.seen, x, mask, threads));
    return sum * normaliser(views);
  };
  // A diagonal preconditioner: 1 / (sum_e A_e^T A_e 1), the curvature each pixel would have if
  // its neighbours moved with it (the scaling of SART and of the multiplicative updates). It
  // keeps pixels seen by many eyes from taking the step of pixels seen by few.
  Image precondition(image.width(), image.height());
  {
    const Image ones(image.width(), image.height(), Vec3f(1.0f));
    for (const TrainingView& v : views)
      addImageGradient(v, weighted(v, viewOf(v.seen, ones, mask, threads)), mask, precondition,
                       threads);
    for (Vec3f& p : precondition.pixels())
      for (int c = 0; c < 3; ++c) p[c] = p[c] > 0.0f ? 1.0f / p[c] : 0.0f;
  }
  double e = energy(image);
  SolveReport local;
  local.objective.push_back(e);
  for (int it = 0; it < iterations; ++it) {
    // Gradient of E (times 1 / norm): sum over eyes of A_e^T (V_e - t_e).
    Image grad(image.width(), image.height());
    for (const TrainingView& v : views) {
      Image residual = viewOf(v.seen, image, mask, threads);
      addScaled(residual, v.target, -1.0f);
      addImageGradient(v, weighted(v, std::move(residual)), mask, grad, threads);
    }
    // Projected, preconditioned direction: no move out of [0, 1] at a bound.
    Image d(image.width(), image.height());
    for (size_t i = 0; i < d.pixels().size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const float x = image.pixels()[i][c], g = grad.pixels()[i][c];
        const bool stuck = (x <= 0.0f && g > 0.0f) || (x >= 1.0f && g < 0.0f);
        d.pixels()[i][c] = stuck ? 0.0f : -g * precondition.pixels()[i][c];
      }
    // The exact step of the quadratic along d: -<g, d> / sum_e |A_e d|^2 (A_e linear in the
    // image with the mask fixed).
    const double slope = dot(grad, d);
    if (!(slope < 0)) break;
    double curvature = 0;
    for (const TrainingView& v : views) {
      const Image ad = viewOf(v.seen, d, mask, threads);
      curvature += dot(ad, weighted(v, ad));
    }
    if (!(curvature > 0)) break;
    double step = -slope / curvature;
    bool lowered = false;
    for (int halving = 0; halving < 8 && !lowered; ++halving, step *= 0.5) {
      Image next = image;
      addScaled(next, d, float(step));
      clampToUnit(next);
      const double eNext = energy(next);
      if (eNext < e) {
        image = std::move(next);
        e = eNext;
        lowered = true;
      }
    }
    if (!lowered) break;
    local.objective.push_back(e);
    ++local.iterations;
  }
  if (report) *report = local;
  return image;
}

std::vector<LayerFrame> factorizeLayers(const std::vector<TrainingView>& views,
                                        std::vector<LayerFrame> frames, int iterations, int threads,
                                        SolveReport* report) {
  checkViews(views);
  if (frames.empty()) throw std::invalid_argument("factorizeLayers: no frames");
  for (LayerFrame& f : frames) clampToUnit(f.image), clampToUnit(f.mask);
  SolveReport local;
  local.objective.push_back(layerObjective(views, frames, threads));
  constexpr float kTiny = 1e-12f;
  // One multiplicative update of every frame's image (updateImages) or mask: numerator
  // sum_e A^T t_e, denominator sum_e A^T V_e, where A is the view's derivative with respect to
  // that frame's layer (the other layer fixed); the 1/T of the average cancels in the ratio.
  const auto update = [&](bool updateImages) {
    std::vector<Image> numerator, denominator;
    for (const LayerFrame& f : frames) {
      const Image& x = updateImages ? f.image : f.mask;
      numerator.emplace_back(x.width(), x.height());
      denominator.emplace_back(x.width(), x.height());
    }
    for (const TrainingView& v : views) {
      const Image seen = weighted(v, averageView(v, frames, threads));
      const Image target = weighted(v, v.target);
      for (size_t t = 0; t < frames.size(); ++t) {
        const LayerFrame& f = frames[t];
        if (updateImages) {
          addImageGradient(v, target, f.mask, numerator[t], threads);
          addImageGradient(v, seen, f.mask, denominator[t], threads);
        } else {
          addMaskGradient(v, target, f.image, numerator[t], threads);
          addMaskGradient(v, seen, f.image, denominator[t], threads);
        }
      }
    }
    for (size_t t = 0; t < frames.size(); ++t) {
      Image& x = updateImages ? frames[t].image : frames[t].mask;
      for (size_t i = 0; i < x.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c) {
          const float num = std::max(numerator[t].pixels()[i][c], 0.0f);
          const float den = denominator[t].pixels()[i][c];
          // A pixel no eye sees (den = 0) keeps its value.
          if (den > kTiny) x.pixels()[i][c] *= num / den;
        }
      clampToUnit(x);
    }
  };
  for (int it = 0; it < iterations; ++it) {
    update(true);
    update(false);
    local.objective.push_back(layerObjective(views, frames, threads));
    ++local.iterations;
  }
  if (report) *report = local;
  return frames;
}

}  // namespace parallax
