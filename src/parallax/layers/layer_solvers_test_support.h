// Shared by the layer solvers' tests: tiny light fields (displays of a few pixels and views, their
// training views from random layers, through a diffuser, colour filters or a pupil), a dense
// least-squares solution and the light field's coefficients written out (the second code paths),
// and the checks every solver passes (never increasing, in the unit box).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "parallax/core/random.h"
#include "parallax/layers/image_layer_solver.h"
#include "parallax/layers/layer_factorization.h"
#include "parallax/layers/layer_problem.h"

namespace parallax::layer_test {

inline DisplayDesign tinyDisplay(LayerOrder order) {
  DisplaySpec s = defaultDisplaySpec();
  s.order = order;
  s.imagePanel.width = s.maskPanel.width = 27;
  s.imagePanel.height = s.maskPanel.height = 2;
  s.views = 3.0;
  s.imagePanel.pitchMm = s.maskPanel.pitchMm = 1.0;
  return designDisplay(s);
}

inline Image randomImage(int width, int height, uint64_t seed, float lo = 0.0f, float hi = 1.0f) {
  Rng rng(seed);
  Image image(width, height);
  for (Vec3f& p : image.pixels())
    for (int c = 0; c < 3; ++c) p[c] = lo + (hi - lo) * rng.uniform();
  return image;
}

inline std::vector<Vec3d> eyesAcross(const DisplayDesign& d) {
  std::vector<Vec3d> eyes;
  for (double f : {0.9, 1.0, 1.15})
    for (int k = 0; k < 7; ++k)
      eyes.push_back({(-0.45 + 0.15 * k) * d.viewZoneWidthMm * f, 0, d.viewDistanceMm * f});
  return eyes;
}

// Views of the layers `truth` from every eye, plus noise of `noise` amplitude.
inline std::vector<TrainingView> viewsOf(const DisplayDesign& d, const Image& image,
                                         const Image& mask, float noise) {
  std::vector<TrainingView> views;
  Rng rng(11);
  for (const Vec3d& eye : eyesAcross(d)) {
    SeenLayers seen(d, eye);
    Image target = seen.imageInFront() ? seen.view(image, mask) : seen.view(mask, image);
    for (Vec3f& p : target.pixels())
      for (int c = 0; c < 3; ++c) p[c] += noise * (rng.uniform() - 0.5f);
    views.push_back({std::move(seen), std::move(target)});
  }
  return views;
}

inline bool inUnitBox(const Image& image) {
  for (const Vec3f& p : image.pixels())
    for (int c = 0; c < 3; ++c)
      if (!(p[c] >= 0.0f && p[c] <= 1.0f)) return false;
  return true;
}

inline void expectNonIncreasing(const std::vector<double>& objective) {
  for (size_t i = 1; i < objective.size(); ++i)
    EXPECT_LE(objective[i], objective[i - 1] * (1 + 1e-6)) << "iteration " << i;
}

// Solves the dense normal equations (A^T A + tiny ridge) x = A^T t for one channel by Cholesky,
// with A probed column by column from the operator (the image layer's unit images).
// The squared slope of the sRGB encoding at x (IEC 61966-2-1), computed directly.
inline double encodingWeight(double x) {
  x = std::clamp(x, 0.0, 1.0);
  const double slope = x <= 0.0031308 ? 12.92 : 1.055 / 2.4 * std::pow(x, 1.0 / 2.4 - 1.0);
  return slope * slope;
}

inline std::vector<double> denseLeastSquares(const std::vector<TrainingView>& views,
                                             const Image& mask, int channel,
                                             const RearDiffuser& diffuser = {}) {
  const int w = mask.width(), h = mask.height(), n = w * h;
  std::vector<std::vector<double>> columns(static_cast<size_t>(n));
  std::vector<double> targets, weights;
  for (const TrainingView& v : views)
    for (const Vec3f& p : v.target.pixels()) {
      targets.push_back(p[channel]);
      weights.push_back(v.encodingScale > 0 ? encodingWeight(p[channel] / v.encodingScale) : 1.0);
    }
  for (int j = 0; j < n; ++j) {
    Image unit(w, h);
    unit.pixels()[size_t(j)][channel] = 1.0f;
    for (const TrainingView& v : views) {
      // Through the diffuser the rear layer is seen blurred: the mask, or the image's unit.
      const Image seen = v.seen.imageInFront() ? v.seen.view(unit, diffuser.apply(mask))
                                               : v.seen.view(mask, diffuser.apply(unit));
      for (const Vec3f& p : seen.pixels()) columns[size_t(j)].push_back(p[channel]);
    }
  }
  std::vector<double> ata(size_t(n) * size_t(n)), atb(static_cast<size_t>(n));
  double trace = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      double s = 0;
      for (size_t k = 0; k < targets.size(); ++k)
        s += columns[size_t(i)][k] * columns[size_t(j)][k];
      ata[size_t(i) * size_t(n) + size_t(j)] = s;
    }
    for (size_t k = 0; k < targets.size(); ++k)
      atb[size_t(i)] += columns[size_t(i)][k] * targets[k];
    trace += ata[size_t(i) * size_t(n) + size_t(i)];
  }
  for (int i = 0; i < n; ++i) ata[size_t(i) * size_t(n) + size_t(i)] += 1e-10 * trace / n;
  // Cholesky: ata = L L^T, then two triangular solves.
  std::vector<double> l(ata.size());
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) {
      double s = ata[size_t(i) * size_t(n) + size_t(j)];
      for (int k = 0; k < j; ++k)
        s -= l[size_t(i) * size_t(n) + size_t(k)] * l[size_t(j) * size_t(n) + size_t(k)];
      l[size_t(i) * size_t(n) + size_t(j)] =
          i == j ? std::sqrt(std::max(s, 1e-300)) : s / l[size_t(j) * size_t(n) + size_t(j)];
    }
  std::vector<double> y(static_cast<size_t>(n)), x(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    double s = atb[size_t(i)];
    for (int k = 0; k < i; ++k) s -= l[size_t(i) * size_t(n) + size_t(k)] * y[size_t(k)];
    y[size_t(i)] = s / l[size_t(i) * size_t(n) + size_t(i)];
  }
  for (int i = n - 1; i >= 0; --i) {
    double s = y[size_t(i)];
    for (int k = i + 1; k < n; ++k) s -= l[size_t(k) * size_t(n) + size_t(i)] * x[size_t(k)];
    x[size_t(i)] = s / l[size_t(i) * size_t(n) + size_t(i)];
  }
  return x;
}

// The light field written out: view pixel o of eye e is sum_k c_k front[f_k] rear[r_k], probed
// from the operator one (front pixel, rear pixel) pair at a time.
struct Coefficient {
  size_t eye, pixel;
  int front, rear;
  double weight;
};

inline std::vector<Coefficient> probeLightField(const std::vector<TrainingView>& views, int w,
                                                int h) {
  std::vector<Coefficient> out;
  const int n = w * h;
  for (size_t e = 0; e < views.size(); ++e)
    for (int f = 0; f < n; ++f)
      for (int r = 0; r < n; ++r) {
        Image front(w, h), rear(w, h);
        front.pixels()[size_t(f)] = Vec3f(1.0f);
        rear.pixels()[size_t(r)] = Vec3f(1.0f);
        const Image v = views[e].seen.view(front, rear);
        for (size_t o = 0; o < v.pixels().size(); ++o)
          if (v.pixels()[o].x != 0.0f) out.push_back({e, o, f, r, v.pixels()[o].x});
      }
  return out;
}

// A 45 x 7 panel of 1 mm pixels and 5 views, the image in front of the barrier.
inline DisplayDesign smallImageInFront() {
  DisplaySpec spec = defaultDisplaySpec();
  spec.order = LayerOrder::BarrierBack;
  spec.imagePanel.width = spec.maskPanel.width = 45;
  spec.imagePanel.height = spec.maskPanel.height = 7;
  spec.views = 5.0;
  spec.imagePanel.pitchMm = spec.maskPanel.pitchMm = 1.0;
  return designDisplay(spec);
}

// Float linear-light targets of a random image behind a grey mask, with noise: what the 16-bit
// and B^T t forms of the targets are checked against.
inline std::vector<TrainingView> noisyLinearViews(const DisplayDesign& d) {
  return viewsOf(d, randomImage(27, 2, 12), Image(27, 2, Vec3f(0.6f)), 0.01f);
}

// factorizeLayers from the same random start of `rank` frames on two sets of the same views
// kept differently: the same objectives (within 1e-4 of the first) and layers (within 1e-3), and
// the objective at least halved.
inline void expectSameFactorization(const std::vector<TrainingView>& a,
                                    const std::vector<TrainingView>& b, int rank,
                                    const RearDiffuser& diffuser = {}) {
  std::vector<LayerFrame> start;
  for (int t = 0; t < rank; ++t)
    start.push_back(
        {randomImage(27, 2, 20 + t, 0.1f, 0.9f), randomImage(27, 2, 30 + t, 0.1f, 0.9f)});
  SolveReport ra, rb;
  const std::vector<LayerFrame> x = factorizeLayers(a, start, 12, 2, &ra, {}, diffuser);
  const std::vector<LayerFrame> y = factorizeLayers(b, start, 12, 2, &rb, {}, diffuser);
  ASSERT_EQ(ra.objective.size(), rb.objective.size());
  EXPECT_LT(rb.objective.back(), 0.5 * rb.objective.front());
  for (size_t i = 0; i < ra.objective.size(); ++i)
    EXPECT_NEAR(ra.objective[i], rb.objective[i], 1e-4 * ra.objective[0]) << i;
  for (size_t t = 0; t < x.size(); ++t)
    for (size_t i = 0; i < x[t].image.pixels().size(); ++i)
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(x[t].image.pixels()[i][c], y[t].image.pixels()[i][c], 1e-3f);
        EXPECT_NEAR(x[t].mask.pixels()[i][c], y[t].mask.pixels()[i][c], 1e-3f);
      }
}

// Targets seen through a diffuser (the rear layer blurred, sim/diffuser.h) from layers that can
// show them exactly: layers solved for the diffuser reach them, layers solved without it do
// not; in either layer order (the mask blurred, or the image) and for NMF's both layers.
inline std::vector<TrainingView> viewsThroughDiffuser(const DisplayDesign& d, const Image& image,
                                                      const Image& mask,
                                                      const RearDiffuser& diffuser) {
  std::vector<TrainingView> views;
  for (const Vec3d& eye : eyesAcross(d)) {
    SeenLayers seen(d, eye);
    Image target = seen.imageInFront() ? seen.view(image, diffuser.apply(mask))
                                       : seen.view(mask, diffuser.apply(image));
    views.push_back({std::move(seen), std::move(target)});
  }
  return views;
}

// optimizeImageLayer solved for `views` (through `diffuser`) from grey: it reaches their
// targets, where the layer solved for `unawareViews` (the same targets held by eyes that miss an
// optic, through `unawareDiffuser`) and seen by `views` falls at least 3x short; and the rows
// solved separately agree with the whole-image passes.
inline void expectSolvedForTheOptics(const std::vector<TrainingView>& views,
                                     const std::vector<TrainingView>& unawareViews,
                                     const Image& mask, const RearDiffuser& diffuser,
                                     const RearDiffuser& unawareDiffuser) {
  const Image start(mask.width(), mask.height(), Vec3f(0.5f));
  SolveReport aware;
  const Image solved = optimizeImageLayer(views, start, mask, 300, 1, &aware, {}, diffuser);
  EXPECT_TRUE(inUnitBox(solved));
  expectNonIncreasing(aware.objective);
  const double eAware = layerObjective(views, {{solved, mask}}, 1, diffuser);
  EXPECT_NEAR(eAware, aware.objective.back(), 1e-9 + 1e-6 * eAware);
  EXPECT_LT(eAware, 1e-3 * aware.objective.front());
  const Image unaware =
      optimizeImageLayer(unawareViews, start, mask, 300, 1, nullptr, {}, unawareDiffuser);
  const double eUnaware = layerObjective(views, {{unaware, mask}}, 1, diffuser);
  EXPECT_GT(eUnaware, 3.0 * eAware) << eUnaware << " " << eAware;
  const Image byEye =
      detail::optimizeImageLayerByEye(views, start, mask, 300, 1, nullptr, diffuser);
  for (size_t i = 0; i < solved.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(byEye.pixels()[i][c], solved.pixels()[i][c], 1e-4f);
}

// Targets seen through the panels' colour filters (SeenOptics::colourFilters), and a diffuser
// when `diffuser` is active (striped: it blurs the light the rear stripes pass), from layers that
// can show them exactly, held by eyes that see through the filters (`filters`) or not: layers
// solved through them reach the targets (seen through them), layers solved without do not; in
// either layer order, with a grey mask (no grey seen masks through filters) and for NMF's both
// layers, and the rows solved separately agree with the whole-image passes.
inline std::vector<TrainingView> viewsThroughFilters(const DisplayDesign& d, const Image& image,
                                                     const Image& mask, bool filters,
                                                     const RearDiffuser& diffuser) {
  std::vector<TrainingView> views;
  for (const Vec3d& eye : eyesAcross(d)) {
    const SeenLayers through(d, eye,
                             {.colourFilters = true, .rearStripeCells = diffuser.striped()});
    Image target = through.imageInFront() ? through.view(image, diffuser.apply(mask))
                                          : through.view(mask, diffuser.apply(image));
    views.push_back(
        {SeenLayers(d, eye,
                    {.colourFilters = filters, .rearStripeCells = filters && diffuser.striped()}),
         std::move(target)});
  }
  return views;
}

// The diffusers of these tests: none, and 0.8 pixels through the rear's RGB stripes; and the
// same blur as a solver that ignores the filters takes it.
inline std::vector<RearDiffuser> stripedDiffusers() {
  return {RearDiffuser{}, RearDiffuser{0.8, 1.0, SubpixelOrder::RGB}};
}

inline RearDiffuser withoutStripes(const RearDiffuser& diffuser) {
  return {diffuser.sigmaMm, diffuser.pitchMm};
}

// Eyes with a pupil (SeenOptics::pupilDiameterMm): targets seen as the average over a wide
// pupil's points (5 of 60 mm: a tenth of a pixel's shift on the rear layer), from layers that
// can show them exactly, held by eyes with that pupil or pinhole eyes (`pupilMm` 0): layers
// solved for the pupil reach them, layers solved for pinhole eyes do not; in either layer order
// (the image behind: its gradient gathers every sight's) and for NMF's both layers, whose mask
// update goes by sights, the same for any thread count.
inline std::vector<TrainingView> viewsThroughPupil(const DisplayDesign& d, const Image& image,
                                                   const Image& mask, double pupilMm) {
  std::vector<TrainingView> views;
  for (const Vec3d& eye : eyesAcross(d)) {
    const SeenLayers through(d, eye, {.pupilDiameterMm = 60, .pupilSamples = 5});
    Image target = through.imageInFront() ? through.view(image, mask) : through.view(mask, image);
    views.push_back(
        {SeenLayers(d, eye, {.pupilDiameterMm = pupilMm, .pupilSamples = 5}), std::move(target)});
  }
  return views;
}

}  // namespace parallax::layer_test
