// The solvers on tiny light fields: against a dense least-squares solution and a dense
// multiplicative-update solver written out on the explicit light-field coefficients (second
// code paths), never increasing their objective, and keeping layers in [0, 1].
#include "parallax/layers/image_layer_solver.h"
#include "parallax/layers/layer_factorization.h"
#include "parallax/layers/layer_problem.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "parallax/core/random.h"
#include "parallax/display/display_model.h"

namespace parallax {
namespace {

DisplayDesign tinyDisplay(LayerOrder order) {
  DisplaySpec s = defaultDisplaySpec();
  s.order = order;
  s.imagePanel.width = s.maskPanel.width = 27;
  s.imagePanel.height = s.maskPanel.height = 2;
  s.views = 3.0;
  s.imagePanel.pitchMm = s.maskPanel.pitchMm = 1.0;
  return designDisplay(s);
}

Image randomImage(int width, int height, uint64_t seed, float lo = 0.0f, float hi = 1.0f) {
  Rng rng(seed);
  Image image(width, height);
  for (Vec3f& p : image.pixels())
    for (int c = 0; c < 3; ++c) p[c] = lo + (hi - lo) * rng.uniform();
  return image;
}

std::vector<Vec3d> eyesAcross(const DisplayDesign& d) {
  std::vector<Vec3d> eyes;
  for (double f : {0.9, 1.0, 1.15})
    for (int k = 0; k < 7; ++k)
      eyes.push_back({(-0.45 + 0.15 * k) * d.viewZoneWidthMm * f, 0, d.viewDistanceMm * f});
  return eyes;
}

// Views of the layers `truth` from every eye, plus noise of `noise` amplitude.
std::vector<TrainingView> viewsOf(const DisplayDesign& d, const Image& image, const Image& mask,
                                  float noise) {
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

bool inUnitBox(const Image& image) {
  for (const Vec3f& p : image.pixels())
    for (int c = 0; c < 3; ++c)
      if (!(p[c] >= 0.0f && p[c] <= 1.0f)) return false;
  return true;
}

void expectNonIncreasing(const std::vector<double>& objective) {
  for (size_t i = 1; i < objective.size(); ++i)
    EXPECT_LE(objective[i], objective[i - 1] * (1 + 1e-6)) << "iteration " << i;
}

// Solves the dense normal equations (A^T A + tiny ridge) x = A^T t for one channel by Cholesky,
// with A probed column by column from the operator (the image layer's unit images).
// The squared slope of the sRGB encoding at x (IEC 61966-2-1), computed directly.
double encodingWeight(double x) {
  x = std::clamp(x, 0.0, 1.0);
  const double slope = x <= 0.0031308 ? 12.92 : 1.055 / 2.4 * std::pow(x, 1.0 / 2.4 - 1.0);
  return slope * slope;
}

std::vector<double> denseLeastSquares(const std::vector<TrainingView>& views, const Image& mask,
                                      int channel, const RearDiffuser& diffuser = {}) {
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

TEST(OptimizeImageLayer, ReachesTheDenseLeastSquaresMinimum) {
  for (const LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront})
    for (const float encodingScale : {0.0f, 0.12f}) {
      SCOPED_TRACE(encodingScale);
      const DisplayDesign d = tinyDisplay(order);
      const Image mask = maskLayerImage(d);
      const Image truth = randomImage(27, 2, 5, 0.3f, 0.7f);
      std::vector<TrainingView> views = viewsOf(d, truth, mask, 0.002f);
      for (TrainingView& v : views) v.encodingScale = encodingScale;
      SolveReport report;
      const Image start(27, 2, Vec3f(0.5f));
      const Image solved = optimizeImageLayer(views, start, mask, 400, 1, &report);
      EXPECT_TRUE(inUnitBox(solved));
      expectNonIncreasing(report.objective);
      EXPECT_LT(report.objective.back(), 0.05 * report.objective.front());
      // The dense solution, where it lies inside [0, 1] (the box constraint then does not bind),
      // has the same objective; the solver's cannot be lower.
      Image dense(27, 2);
      bool inside = true;
      for (int c = 0; c < 3; ++c) {
        const std::vector<double> x = denseLeastSquares(views, mask, c);
        for (size_t i = 0; i < x.size(); ++i) {
          dense.pixels()[i][c] = float(x[i]);
          inside &= x[i] >= 0 && x[i] <= 1;
        }
      }
      const double eDense = layerObjective(views, {{dense, mask}});
      const double eSolved = layerObjective(views, {{solved, mask}});
      // The solver weighs with a table of the encoding's slope, the dense solution with the
      // formula: their minima may differ by the table's error.
      const double tolerance = encodingScale > 0 ? 1e-2 : 1e-3;
      EXPECT_GE(eSolved, eDense * (1 - tolerance) - 1e-12);
      std::fprintf(stderr, "inside=%d eSolved=%g eDense=%g\n", int(inside), eSolved, eDense);
      if (inside) {
        EXPECT_NEAR(eSolved, eDense, 0.02 * eDense + 1e-10);
      }
    }
}

// The light field written out: view pixel o of eye e is sum_k c_k front[f_k] rear[r_k], probed
// from the operator one (front pixel, rear pixel) pair at a time.
struct Coefficient {
  size_t eye, pixel;
  int front, rear;
  double weight;
};

std::vector<Coefficient> probeLightField(const std::vector<TrainingView>& views, int w, int h) {
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

TEST(FactorizeLayers, NeverIncreasesAndStaysInTheUnitBoxAtAnyRank) {
  for (const LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
    const DisplayDesign d = tinyDisplay(order);
    // Targets brighter than slits can show: the layers must open up.
    const Image image = randomImage(27, 2, 12, 0.0f, 1.0f);
    const std::vector<TrainingView> views = viewsOf(d, image, Image(27, 2, Vec3f(0.6f)), 0.01f);
    double last = 0;
    for (const int rank : {1, 2, 3}) {
      std::vector<LayerFrame> start;
      for (int t = 0; t < rank; ++t)
        start.push_back(
            {randomImage(27, 2, 20 + t, 0.1f, 0.9f), randomImage(27, 2, 30 + t, 0.1f, 0.9f)});
      SolveReport report;
      // The progress callback sees every iteration, in order, with the report's objective.
      std::vector<double> told;
      const std::vector<LayerFrame> frames =
          factorizeLayers(views, start, 25, 2, &report, [&](int done, int total, double objective) {
            EXPECT_EQ(done, int(told.size()) + 1);
            EXPECT_EQ(total, 25);
            told.push_back(objective);
          });
      ASSERT_EQ(frames.size(), size_t(rank));
      EXPECT_EQ(told, std::vector<double>(report.objective.begin() + 1, report.objective.end()));
      for (const LayerFrame& f : frames) {
        EXPECT_TRUE(inUnitBox(f.image));
        EXPECT_TRUE(inUnitBox(f.mask));
      }
      expectNonIncreasing(report.objective);
      EXPECT_LT(report.objective.back(), 0.5 * report.objective.front()) << "rank " << rank;
      EXPECT_NEAR(report.objective.back(), layerObjective(views, frames), 1e-12);
      last = report.objective.back();
    }
    EXPECT_GT(last, 0.0);
  }
}

TEST(OptimizeImageLayer, SameLayersForAnyThreadCount) {
  const DisplayDesign d = tinyDisplay(LayerOrder::BarrierBack);
  const Image mask = maskLayerImage(d);
  const std::vector<TrainingView> views = viewsOf(d, randomImage(27, 2, 3), mask, 0.01f);
  const Image a = optimizeImageLayer(views, Image(27, 2, Vec3f(0.5f)), mask, 10, 1);
  const Image b = optimizeImageLayer(views, Image(27, 2, Vec3f(0.5f)), mask, 10, 2);
  EXPECT_EQ(a.pixels(), b.pixels());
}

// A 45 x 7 panel of 1 mm pixels and 5 views, the image in front of the barrier.
DisplayDesign smallImageInFront() {
  DisplaySpec spec = defaultDisplaySpec();
  spec.order = LayerOrder::BarrierBack;
  spec.imagePanel.width = spec.maskPanel.width = 45;
  spec.imagePanel.height = spec.maskPanel.height = 7;
  spec.views = 5.0;
  spec.imagePanel.pitchMm = spec.maskPanel.pitchMm = 1.0;
  return designDisplay(spec);
}

// The rows solved separately (the image in front: row j of every eye's view depends on the
// image's row j only, so each row is solved on its own, with its own steps) against the
// whole-image solver (the operators eye by eye over whole images, one step for all rows). On a
// problem whose rows other than j are solved already (their targets are the views of the start,
// so their residuals, directions and steps are 0) the whole-image solve is row j's own, and row j
// of the separate solve of the whole problem must be it: the same values, and the objectives
// add up row by row. In linear light and on sRGB values, with a grey mask (its views kept for
// the whole solve) and a tinted one (seen row by row), on a panel tall enough that rows have
// several vertical pieces.
TEST(OptimizeImageLayer, RowsSolvedSeparatelyAreEachRowsOwnWholeImageSolve) {
  const DisplayDesign d = smallImageInFront();
  const Image grey = maskLayerImage(d);
  Image tinted = grey;
  for (Vec3f& p : tinted.pixels()) p = p * Vec3f(1.0f, 0.8f, 0.6f);
  ASSERT_TRUE(std::all_of(grey.pixels().begin(), grey.pixels().end(),
                          [](const Vec3f& p) { return p.x == p.y && p.y == p.z; }));
  ASSERT_NE(grey.pixels(), tinted.pixels());
  const Image start(45, 7, Vec3f(0.4f));
  for (const auto& [mask, scale] : {std::pair{grey, 0.0f}, std::pair{grey, 0.8f},
                                    std::pair{tinted, 0.0f}, std::pair{tinted, 0.8f}}) {
    SCOPED_TRACE(scale);
    std::vector<TrainingView> views = viewsOf(d, randomImage(45, 7, 5), mask, 0.02f);
    for (TrainingView& v : views) v.encodingScale = scale;
    SolveReport separately;
    const Image a = optimizeImageLayer(views, start, mask, 6, 2, &separately);
    EXPECT_GT(separately.iterations, 2);
    expectNonIncreasing(separately.objective);
    double rowsAlone = 0;
    for (int j = 0; j < 7; ++j) {
      SCOPED_TRACE(j);
      std::vector<TrainingView> onlyRowJ = views;
      for (TrainingView& v : onlyRowJ) {
        const Image startSeen = v.seen.view(start, mask);
        for (int y = 0; y < 7; ++y)
          for (int x = 0; y != j && x < 45; ++x) v.target.at(x, y) = startSeen.at(x, y);
      }
      SolveReport whole;
      const Image b = detail::optimizeImageLayerByEye(onlyRowJ, start, mask, 6, 2, &whole);
      rowsAlone += whole.objective.back();
      for (int y = 0; y < 7; ++y)
        for (int x = 0; x < 45; ++x)
          for (int c = 0; c < 3; ++c) {
            if (y != j) {
              ASSERT_EQ(b.at(x, y)[c], start.at(x, y)[c]);
              continue;
            }
            EXPECT_NEAR(a.at(x, y)[c], b.at(x, y)[c], 1e-5f) << x;
          }
    }
    EXPECT_NEAR(separately.objective.back(), rowsAlone, 1e-6 * separately.objective.front());
    EXPECT_LT(separately.objective.back(), 0.5 * separately.objective.front());
  }
}

// The targets a band of rows at a time (optimizeImageLayerByBands): the same layers, objectives
// and passes as the solve on the whole targets, with bands of 1, 3 and 7 rows (the last band a
// part), a grey and a tinted mask, and through a diffuser; it refuses what it cannot solve by
// bands (the barrier in front, linear-light errors) and a band of other rows.
TEST(OptimizeImageLayer, TargetsByBandsSolveAsTheWholeTargets) {
  const DisplayDesign d = smallImageInFront();
  const Image grey = maskLayerImage(d);
  Image tinted = grey;
  for (Vec3f& p : tinted.pixels()) p = p * Vec3f(1.0f, 0.8f, 0.6f);
  const Image start(45, 7, Vec3f(0.4f));
  for (const auto& [mask, sigma] :
       {std::pair{grey, 0.0}, std::pair{tinted, 0.0}, std::pair{grey, 0.7}}) {
    const RearDiffuser diffuser{sigma, 1.0};
    std::vector<TrainingView> whole = viewsOf(d, randomImage(45, 7, 5), mask, 0.02f);
    for (TrainingView& v : whole) {
      v.encodingScale = 0.8f;
      v.encodeTarget(1);
    }
    SolveReport expected;
    const Image a = optimizeImageLayer(whole, start, mask, 6, 2, &expected, {}, diffuser);
    for (const int bandRows : {1, 3, 7}) {
      SCOPED_TRACE(bandRows);
      std::vector<TrainingView> views = whole;
      int bandsMade = 0;
      const BandTargets rowsOfWhole = [&](int firstRow, int rows, std::vector<TrainingView>& into) {
        ++bandsMade;
        for (size_t e = 0; e < into.size(); ++e) {
          const auto from = whole[e].encodedTarget.begin() + 3 * 45 * firstRow;
          into[e].encodedTarget.assign(from, from + 3 * 45 * rows);
          into[e].firstTargetRow = firstRow;
        }
      };
      SolveReport byBands;
      int told = 0;
      const Image b = optimizeImageLayerByBands(
          views, rowsOfWhole, bandRows, start, mask, 6, 2, &byBands,
          [&](int done, int total, double) {
            told = std::max(told, done);
            EXPECT_EQ(total, 7);
          },
          diffuser);
      EXPECT_EQ(bandsMade, (7 + bandRows - 1) / bandRows);
      EXPECT_EQ(told, 7);
      EXPECT_EQ(a.pixels(), b.pixels());
      EXPECT_EQ(expected.objective, byBands.objective);
      EXPECT_EQ(expected.iterations, byBands.iterations);
      EXPECT_EQ(expected.passes, byBands.passes);
    }
  }
  std::vector<TrainingView> views = viewsOf(d, randomImage(45, 7, 5), grey, 0.02f);
  const BandTargets shifted = [](int firstRow, int rows, std::vector<TrainingView>& into) {
    for (TrainingView& v : into) {
      v.encodedTarget.assign(3 * 45 * size_t(rows), 0);
      v.firstTargetRow = firstRow + 1;
    }
  };
  for (TrainingView& v : views) v.encodingScale = 0.8f;
  EXPECT_THROW(optimizeImageLayerByBands(views, shifted, 3, start, grey, 2), std::invalid_argument);
  for (TrainingView& v : views) v.encodingScale = 0.0f;
  EXPECT_THROW(optimizeImageLayerByBands(views, shifted, 3, start, grey, 2), std::invalid_argument);
}

// The arithmetic sRGB encoding against IEC 61966-2-1's formula in double, over [0, 1] (both
// segments), below 0 and above 1 (clamped: slope 0).
TEST(SrgbEncode, IsTheStandardsFormula) {
  double worstValue = 0, worstSlope = 0;
  for (int i = -100; i <= 120000; ++i) {
    const float x = float(i) / 100000.0f;
    float encoded = 0, slope = 0;
    detail::srgbEncode(x, encoded, slope);
    const double c = std::clamp(double(x), 0.0, 1.0);
    const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
    const double ds = x > 1.0f         ? 0.0
                      : c <= 0.0031308 ? 12.92
                                       : 1.055 / 2.4 * std::pow(c, 1 / 2.4 - 1);
    worstValue = std::max(worstValue, std::abs(encoded - s));
    worstSlope = std::max(worstSlope, std::abs(slope - ds) / std::max(1.0, ds));
  }
  EXPECT_LT(worstValue, 3e-7);
  EXPECT_LT(worstSlope, 1e-6);
}

// TrainingView::encodeTarget's codes are round(65535 S(t / c)), S the standard's formula in
// double: exactly wherever 65535 S lies more than 0.025 from a half (the float encoding is
// within 3e-7 of S, 0.02 of a code), and within one code nearer a half. A fine sweep
// over [0, 1.2] (both segments of S, the clamp above 1) and values whose 65535 S is a half.
TEST(TrainingView, EncodedTargetIsTheRoundedEncoding) {
  std::vector<float> values;
  for (int i = 0; i <= 240000; ++i) values.push_back(float(i) / 200000.0f);
  for (int code = 0; code < 65535; code += 97) {
    const double s = (code + 0.5) / 65535.0;  // S^-1 of it, in S's power segment or linear one
    values.push_back(float(s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4)));
  }
  while (values.size() % 3 != 0) values.push_back(0.5f);
  const int width = int(values.size() / 3);
  const DisplayDesign d = smallImageInFront();
  TrainingView view{SeenLayers(d, eyesAcross(d).front()), Image(width, 1)};
  for (int x = 0; x < width; ++x)
    for (int c = 0; c < 3; ++c) view.target.at(x, 0)[c] = 0.8f * values[size_t(3 * x + c)];
  view.encodingScale = 0.8f;
  const Image target = view.target;
  view.encodeTarget(2);
  ASSERT_EQ(view.encodedTarget.size(), 3 * size_t(width));
  int exactOnes = 0;
  for (int x = 0; x < width; ++x)
    for (int c = 0; c < 3; ++c) {
      const double t = std::clamp(double(target.at(x, 0)[c] * (1.0f / 0.8f)), 0.0, 1.0);
      const double scaled =
          65535.0 * (t <= 0.0031308 ? 12.92 * t : 1.055 * std::pow(t, 1 / 2.4) - 0.055);
      const long exact = std::lround(scaled), code = long(view.encodedTarget[size_t(3 * x + c)]);
      const bool nearHalf = std::abs(scaled - std::floor(scaled) - 0.5) <= 0.025;
      if (nearHalf) {
        EXPECT_LE(std::abs(code - exact), 1) << scaled;
      } else {
        EXPECT_EQ(code, exact) << scaled;
        exactOnes += 1;
      }
    }
  EXPECT_GT(exactOnes, 3 * width * 9 / 10);  // most values are far from a half
}

// Targets kept encoded (TrainingView::encodeTarget: S(t / c) in 16 bits) give the solve of the
// float targets: the same objectives to the encoding's rounding and the same layers.
TEST(OptimizeImageLayer, EncodedTargetsSolveAsTheFloatTargets) {
  const DisplayDesign d = smallImageInFront();
  const Image mask = maskLayerImage(d);
  std::vector<TrainingView> floats = viewsOf(d, randomImage(45, 7, 5), mask, 0.02f);
  for (TrainingView& v : floats) v.encodingScale = 0.8f;
  std::vector<TrainingView> encoded = floats;
  for (TrainingView& v : encoded) v.encodeTarget();
  SolveReport a, b;
  const Image x = optimizeImageLayer(floats, Image(45, 7, Vec3f(0.4f)), mask, 6, 2, &a);
  const Image y = optimizeImageLayer(encoded, Image(45, 7, Vec3f(0.4f)), mask, 6, 2, &b);
  ASSERT_EQ(a.iterations, b.iterations);
  EXPECT_GT(a.iterations, 2);
  // |S(t) - round(S(t))| <= 1/131070: the objective moves by at most that times the errors.
  for (size_t i = 0; i < a.objective.size(); ++i)
    EXPECT_NEAR(a.objective[i], b.objective[i], 1e-4 * a.objective[0]) << i;
  EXPECT_LT(b.objective.back(), 0.5 * b.objective.front());
  for (size_t i = 0; i < x.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(x.pixels()[i][c], y.pixels()[i][c], 2e-3f) << i;
  EXPECT_NEAR(layerObjective(floats, {{x, mask}}), layerObjective(encoded, {{x, mask}}),
              1e-4 * a.objective[0]);
}

// Float linear-light targets of a random image behind a grey mask, with noise: what the 16-bit
// and B^T t forms of the targets are checked against.
std::vector<TrainingView> noisyLinearViews(const DisplayDesign& d) {
  return viewsOf(d, randomImage(27, 2, 12), Image(27, 2, Vec3f(0.6f)), 0.01f);
}

// factorizeLayers from the same random start of `rank` frames on two sets of the same views
// kept differently: the same objectives (within 1e-4 of the first) and layers (within 1e-3), and
// the objective at least halved.
void expectSameFactorization(const std::vector<TrainingView>& a, const std::vector<TrainingView>& b,
                             int rank, const RearDiffuser& diffuser = {}) {
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

// Linear-light targets kept in 16 bits (TrainingView::encodeTarget with encodingScale 0:
// round(t / u), u = the largest value / 65535) are within u / 2 of the floats (and the float
// arithmetic's rounding), and give the
// solve of the float targets: the multiplicative updates at every rank in both layer orders
// (the row passes with the image in front, the whole-image ones behind it) and the linear
// image-layer solve; the objectives move by at most the rounding times the errors.
TEST(FactorizeLayers, TargetsInSixteenBitsSolveAsTheFloatTargets) {
  for (const LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
    SCOPED_TRACE(int(order));
    const DisplayDesign d = tinyDisplay(order);
    const std::vector<TrainingView> floats = noisyLinearViews(d);
    std::vector<TrainingView> coded = floats;
    for (TrainingView& v : coded) v.encodeTarget(2);
    for (size_t e = 0; e < floats.size(); ++e) {
      const TrainingView& v = coded[e];
      ASSERT_TRUE(v.target.empty());
      float largest = 0;
      for (const Vec3f& p : floats[e].target.pixels()) largest = std::max({largest, p.x, p.y, p.z});
      EXPECT_FLOAT_EQ(v.linearUnit, largest / 65535.0f);
      Image holder;
      const Image& decoded = v.linearTarget(holder, 2);
      for (size_t i = 0; i < decoded.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(decoded.pixels()[i][c], floats[e].target.pixels()[i][c],
                      0.51f * v.linearUnit);
    }
    for (const int rank : {1, 2}) expectSameFactorization(floats, coded, rank);
    const Image mask = maskLayerImage(d);
    SolveReport a, b;
    const Image x = optimizeImageLayer(floats, Image(27, 2, Vec3f(0.4f)), mask, 6, 2, &a);
    const Image y = optimizeImageLayer(coded, Image(27, 2, Vec3f(0.4f)), mask, 6, 2, &b);
    // (Each row stops where its step no longer lowers E: near a row's minimum that may come an
    // iteration sooner or later with the one or the other target.)
    for (size_t i = 0; i < std::min(a.objective.size(), b.objective.size()); ++i)
      EXPECT_NEAR(a.objective[i], b.objective[i], 1e-4 * a.objective[0]) << i;
    EXPECT_NEAR(a.objective.back(), b.objective.back(), 1e-4 * a.objective[0]);
    for (size_t i = 0; i < x.pixels().size(); ++i)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(x.pixels()[i][c], y.pixels()[i][c], 1e-3f);
  }
}

// Targets kept as B^T t (TrainingView::encodeBoxedTarget, nmf with the image in front): the
// codes are within u / 2 of B^T t made by the whole-image operator (SeenLayers::boxTransposed,
// a second code path), the row squares are |t_j|^2, and the multiplicative updates give the
// float targets' layers and objectives (E from <P, B^T t> and |t|^2 instead of from V - t), with
// and without a diffuser, at ranks 1 and 2. Solves that read t itself refuse them.
TEST(FactorizeLayers, BoxedTargetsSolveAsTheFloatTargets) {
  const DisplayDesign d = tinyDisplay(LayerOrder::BarrierBack);
  const std::vector<TrainingView> floats = noisyLinearViews(d);
  std::vector<TrainingView> boxed = floats;
  for (TrainingView& v : boxed) v.encodeBoxedTarget(2);
  for (size_t e = 0; e < floats.size(); ++e) {
    const TrainingView& v = boxed[e];
    ASSERT_TRUE(v.boxedTarget);
    const Image expected = v.seen.boxTransposed(floats[e].target, 1);
    std::vector<Vec3f> row(27), scratch(27);
    for (int j = 0; j < 2; ++j) {
      v.boxedTargetRow(j, row.data(), scratch.data());
      double squares = 0;
      for (int i = 0; i < 27; ++i)
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(row[size_t(i)][c], expected.at(i, j)[c], 0.51f * v.rowUnits[size_t(j)]);
          squares += double(floats[e].target.at(i, j)[c]) * floats[e].target.at(i, j)[c];
        }
      EXPECT_NEAR(v.rowTargetSquares[size_t(j)], squares, 1e-6 * squares);
    }
    EXPECT_THROW(v.linearTargetRow(0, row.data()), std::logic_error);
  }
  for (const double sigmaMm : {0.0, 0.4})
    for (const int rank : {1, 2}) {
      SCOPED_TRACE(rank);
      expectSameFactorization(floats, boxed, rank, {sigmaMm, d.spec.maskPanel.pitchMm});
    }
  EXPECT_THROW(optimizeImageLayer(boxed, Image(27, 2, Vec3f(0.4f)), maskLayerImage(d), 2, 2),
               std::invalid_argument);
  EXPECT_THROW(layerObjective(boxed, {{Image(27, 2, Vec3f(0.4f)), maskLayerImage(d)}}),
               std::invalid_argument);
  // With the barrier in front the updates read t through the whole-image operators.
  const DisplayDesign front = tinyDisplay(LayerOrder::BarrierFront);
  std::vector<TrainingView> frontBoxed = noisyLinearViews(front);
  for (TrainingView& v : frontBoxed) v.encodeBoxedTarget(2);
  EXPECT_THROW(factorizeLayers(frontBoxed, {{Image(27, 2, Vec3f(0.4f)), maskLayerImage(front)}}, 2),
               std::invalid_argument);
  // Only linear-light targets are kept so.
  std::vector<TrainingView> srgb = floats;
  srgb.front().encodingScale = 0.5f;
  EXPECT_THROW(srgb.front().encodeBoxedTarget(), std::logic_error);
}

// Targets seen through a diffuser (the rear layer blurred, sim/diffuser.h) from layers that can
// show them exactly: layers solved for the diffuser reach them, layers solved without it do
// not; in either layer order (the mask blurred, or the image) and for NMF's both layers.
std::vector<TrainingView> viewsThroughDiffuser(const DisplayDesign& d, const Image& image,
                                               const Image& mask, const RearDiffuser& diffuser) {
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
void expectSolvedForTheOptics(const std::vector<TrainingView>& views,
                              const std::vector<TrainingView>& unawareViews, const Image& mask,
                              const RearDiffuser& diffuser, const RearDiffuser& unawareDiffuser) {
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

TEST(OptimizeImageLayer, SolvesForTheDiffuser) {
  for (const LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
    SCOPED_TRACE(int(order));
    const DisplayDesign d = tinyDisplay(order);
    const RearDiffuser diffuser{0.8, 1.0};  // 0.8 pixels
    const Image mask = maskLayerImage(d);
    const Image truth = randomImage(27, 2, 9, 0.3f, 0.7f);
    const std::vector<TrainingView> views = viewsThroughDiffuser(d, truth, mask, diffuser);
    // Solved as if there were no diffuser, then seen through it.
    expectSolvedForTheOptics(views, views, mask, diffuser, {});
  }
}

// Targets seen through the panels' colour filters (SeenOptics::colourFilters), and a diffuser
// when `diffuser` is active (striped: it blurs the light the rear stripes pass), from layers that
// can show them exactly, held by eyes that see through the filters (`filters`) or not: layers
// solved through them reach the targets (seen through them), layers solved without do not; in
// either layer order, with a grey mask (no grey seen masks through filters) and for NMF's both
// layers, and the rows solved separately agree with the whole-image passes.
std::vector<TrainingView> viewsThroughFilters(const DisplayDesign& d, const Image& image,
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
std::vector<RearDiffuser> stripedDiffusers() {
  return {RearDiffuser{}, RearDiffuser{0.8, 1.0, SubpixelOrder::RGB}};
}
RearDiffuser withoutStripes(const RearDiffuser& diffuser) {
  return {diffuser.sigmaMm, diffuser.pitchMm};
}

// Two rows (each eye's mask seen in colour kept for the solve) and 70 (more than a band's rows:
// seen again each pass).
TEST(OptimizeImageLayer, SolvesForTheColourFilters) {
  for (const int rows : {2, kTargetBandRows + 6})
    for (const RearDiffuser& diffuser : stripedDiffusers())
      for (const LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
        SCOPED_TRACE(int(order) + 10 * diffuser.active() + 100 * rows);
        DisplaySpec spec = tinyDisplay(order).spec;
        spec.imagePanel.height = spec.maskPanel.height = rows;
        const DisplayDesign d = designDisplay(spec);
        const Image mask = maskLayerImage(d);
        const Image truth = randomImage(27, rows, 19, 0.3f, 0.7f);
        expectSolvedForTheOptics(viewsThroughFilters(d, truth, mask, true, diffuser),
                                 viewsThroughFilters(d, truth, mask, false, diffuser), mask,
                                 diffuser, withoutStripes(diffuser));
      }
}

TEST(FactorizeLayers, SolvesForTheColourFilters) {
  for (const RearDiffuser& diffuser : stripedDiffusers()) {
    SCOPED_TRACE(diffuser.active());
    const DisplayDesign d = tinyDisplay(LayerOrder::BarrierBack);
    const Image image = randomImage(27, 2, 24, 0.2f, 0.9f);
    const Image mask = randomImage(27, 2, 26, 0.2f, 1.0f);
    const std::vector<TrainingView> views = viewsThroughFilters(d, image, mask, true, diffuser);
    const std::vector<LayerFrame> start{{Image(27, 2, Vec3f(0.5f)), Image(27, 2, Vec3f(0.5f))}};
    SolveReport aware;
    const std::vector<LayerFrame> solved =
        factorizeLayers(views, start, 200, 1, &aware, {}, diffuser);
    expectNonIncreasing(aware.objective);
    EXPECT_TRUE(inUnitBox(solved[0].image) && inUnitBox(solved[0].mask));
    const double eAware = layerObjective(views, solved, 1, diffuser);
    EXPECT_NEAR(eAware, aware.objective.back(), 1e-9 + 1e-6 * eAware);
    const std::vector<LayerFrame> unaware =
        factorizeLayers(viewsThroughFilters(d, image, mask, false, diffuser), start, 200, 1,
                        nullptr, {}, withoutStripes(diffuser));
    const double eUnaware = layerObjective(views, unaware, 1, diffuser);
    EXPECT_LT(2.0 * eAware, eUnaware) << eAware << " " << eUnaware;
    EXPECT_LT(eAware, 0.1 * aware.objective.front());
  }
}

// Eyes with a pupil (SeenOptics::pupilDiameterMm): targets seen as the average over a wide
// pupil's points (5 of 60 mm: a tenth of a pixel's shift on the rear layer), from layers that
// can show them exactly, held by eyes with that pupil or pinhole eyes (`pupilMm` 0): layers
// solved for the pupil reach them, layers solved for pinhole eyes do not; in either layer order
// (the image behind: its gradient gathers every sight's) and for NMF's both layers, whose mask
// update goes by sights, the same for any thread count.
std::vector<TrainingView> viewsThroughPupil(const DisplayDesign& d, const Image& image,
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

TEST(OptimizeImageLayer, SolvesForThePupil) {
  for (const LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
    SCOPED_TRACE(int(order));
    const DisplayDesign d = tinyDisplay(order);
    const Image mask = maskLayerImage(d);
    const Image truth = randomImage(27, 2, 29, 0.3f, 0.7f);
    const std::vector<TrainingView> views = viewsThroughPupil(d, truth, mask, 60);
    ASSERT_EQ(views.front().seen.sights(), 5);
    expectSolvedForTheOptics(views, viewsThroughPupil(d, truth, mask, 0), mask, {}, {});
  }
}

TEST(FactorizeLayers, SolvesForThePupil) {
  const DisplayDesign d = tinyDisplay(LayerOrder::BarrierBack);
  const Image image = randomImage(27, 2, 34, 0.2f, 0.9f), mask = randomImage(27, 2, 36, 0.2f, 1.0f);
  const std::vector<TrainingView> views = viewsThroughPupil(d, image, mask, 60);
  const auto boxed = [](std::vector<TrainingView> v) {  // as render's nmf holds them
    for (TrainingView& one : v) one.encodeBoxedTarget(1);
    return v;
  };
  const std::vector<LayerFrame> start{{Image(27, 2, Vec3f(0.5f)), Image(27, 2, Vec3f(0.5f))}};
  SolveReport aware;
  const std::vector<LayerFrame> solved = factorizeLayers(boxed(views), start, 200, 1, &aware);
  expectNonIncreasing(aware.objective);
  const double eAware = layerObjective(views, solved, 1);
  EXPECT_NEAR(eAware, aware.objective.back(), 1e-6 + 1e-3 * eAware);  // the targets' rounding
  EXPECT_LT(eAware, 0.1 * aware.objective.front());
  const std::vector<LayerFrame> two = factorizeLayers(boxed(views), start, 200, 2);
  EXPECT_EQ(two[0].image.pixels(), solved[0].image.pixels());
  EXPECT_EQ(two[0].mask.pixels(), solved[0].mask.pixels());
  const std::vector<LayerFrame> unaware =
      factorizeLayers(boxed(viewsThroughPupil(d, image, mask, 0)), start, 200, 1);
  const double eUnaware = layerObjective(views, unaware, 1);
  EXPECT_LT(2.0 * eAware, eUnaware) << eAware << " " << eUnaware;
}

// The mask update goes by blocks of mask rows (their split depends on the thread count) and by
// groups of eyes that see the rows through the same mask rows (one distance and height): the
// same layers bit for bit for 1, 2 and 3 threads on a panel of 100 rows (blocks of 17-32), and
// the same layers within float rounding when the eyes come in an order where no two neighbours
// share their mask rows (every group one eye: the sums in another order), with boxed targets
// at rank 2, an eye above the others among them.
TEST(FactorizeLayers, SameLayersForAnyThreadCountAndEyeOrder) {
  DisplaySpec spec = tinyDisplay(LayerOrder::BarrierBack).spec;
  spec.imagePanel.height = spec.maskPanel.height = 100;
  const DisplayDesign d = designDisplay(spec);
  const Image image = randomImage(27, 100, 41, 0.1f, 0.9f), mask = randomImage(27, 100, 42);
  std::vector<Vec3d> eyes = eyesAcross(d);
  eyes.insert(eyes.begin() + 3, {0.1 * d.viewZoneWidthMm, 4.0, d.viewDistanceMm});
  std::vector<TrainingView> grouped;
  for (const Vec3d& eye : eyes) {
    SeenLayers seen(d, eye);
    Image target = seen.view(image, mask);
    grouped.push_back({std::move(seen), std::move(target)});
    grouped.back().encodeBoxedTarget(1);
  }
  std::vector<TrainingView> mixed;
  for (size_t k = 0; k < 8; ++k)  // 22 eyes: 0, 8, 16, 1, 9, 17, ...: no neighbours share rows
    for (size_t e = k; e < grouped.size(); e += 8) mixed.push_back(grouped[e]);
  ASSERT_EQ(mixed.size(), grouped.size());
  std::vector<LayerFrame> start;
  for (int t = 0; t < 2; ++t)
    start.push_back(
        {randomImage(27, 100, 50 + t, 0.2f, 0.8f), randomImage(27, 100, 60 + t, 0.2f, 0.8f)});
  const std::vector<LayerFrame> one = factorizeLayers(grouped, start, 3, 1);
  for (const int threads : {2, 3}) {
    const std::vector<LayerFrame> many = factorizeLayers(grouped, start, 3, threads);
    for (size_t t = 0; t < 2; ++t) {
      EXPECT_EQ(one[t].image.pixels(), many[t].image.pixels()) << threads;
      EXPECT_EQ(one[t].mask.pixels(), many[t].mask.pixels()) << threads;
    }
  }
  const std::vector<LayerFrame> other = factorizeLayers(mixed, start, 3, 2);
  for (size_t t = 0; t < 2; ++t)
    for (size_t i = 0; i < one[t].mask.pixels().size(); ++i)
      for (int c = 0; c < 3; ++c) {
        ASSERT_NEAR(one[t].mask.pixels()[i][c], other[t].mask.pixels()[i][c], 1e-4f) << i;
        ASSERT_NEAR(one[t].image.pixels()[i][c], other[t].image.pixels()[i][c], 1e-4f) << i;
      }
}

TEST(FactorizeLayers, SolvesForTheDiffuser) {
  const DisplayDesign d = tinyDisplay(LayerOrder::BarrierBack);
  const RearDiffuser diffuser{0.8, 1.0};
  const Image image = randomImage(27, 2, 4, 0.2f, 0.9f), mask = randomImage(27, 2, 6, 0.2f, 1.0f);
  const std::vector<TrainingView> views = viewsThroughDiffuser(d, image, mask, diffuser);
  const std::vector<LayerFrame> start{{Image(27, 2, Vec3f(0.5f)), Image(27, 2, Vec3f(0.5f))}};
  SolveReport aware;
  const std::vector<LayerFrame> solved =
      factorizeLayers(views, start, 200, 1, &aware, {}, diffuser);
  expectNonIncreasing(aware.objective);
  EXPECT_TRUE(inUnitBox(solved[0].image) && inUnitBox(solved[0].mask));
  const double eAware = layerObjective(views, solved, 1, diffuser);
  EXPECT_NEAR(eAware, aware.objective.back(), 1e-9 + 1e-6 * eAware);
  const std::vector<LayerFrame> unaware = factorizeLayers(views, start, 200, 1);
  const double eUnaware = layerObjective(views, unaware, 1, diffuser);
  EXPECT_LT(eAware, eUnaware) << eAware << " " << eUnaware;
  EXPECT_LT(eAware, 0.1 * aware.objective.front());
}

// The (over-relaxed) multiplicative updates against dense ones on the probed light field,
// channel 0: front =
// image (barrier-back), rear = mask, seen as G rear through a diffuser (G probed from the blur
// one pixel at a time, the identity without one), so that the rear's sums pass through G^T; and
// by eyes with a pupil, whose sights the mask's sums gather one by one (the light field probed
// from their average view).
TEST(FactorizeLayers, MatchesDenseMultiplicativeUpdatesOnTheLightField) {
  for (const auto& [sigma, pupil] : {std::pair{0.0, 0.0}, {1.1, 0.0}, {0.0, 60.0}}) {
    SCOPED_TRACE(sigma + 100 * pupil);
    const DisplayDesign d = tinyDisplay(LayerOrder::BarrierBack);
    const int w = 27, h = 1;
    DisplaySpec spec = d.spec;
    spec.imagePanel.height = spec.maskPanel.height = h;
    const DisplayDesign flat = designDisplay(spec);
    const RearDiffuser diffuser{sigma, 1.0};
    const Image truthImage = randomImage(w, h, 8, 0.2f, 0.9f);
    const Image truthMask = randomImage(w, h, 9, 0.2f, 0.9f);
    std::vector<TrainingView> views;
    for (const Vec3d& eye : eyesAcross(flat)) {
      SeenLayers seen(flat, eye, {.pupilDiameterMm = pupil, .pupilSamples = 5});
      Image target = seen.view(truthImage, diffuser.apply(truthMask));
      views.push_back({std::move(seen), std::move(target)});
    }
    const std::vector<Coefficient> field = probeLightField(views, w, h);
    ASSERT_FALSE(field.empty());
    std::vector<std::vector<double>> blur(size_t(w), std::vector<double>(size_t(w), 0.0));
    for (int q = 0; q < w; ++q) {
      Image one(w, h);
      one.at(q, 0) = Vec3f(1.0f);
      const Image column = diffuser.apply(one);
      for (int r = 0; r < w; ++r) blur[size_t(r)][size_t(q)] = column.at(r, 0).x;  // G[r][q]
    }
    std::vector<double> front(static_cast<size_t>(w), 0.5), rear(static_cast<size_t>(w), 0.5);
    const auto seenRear = [&] {
      std::vector<double> g(static_cast<size_t>(w), 0.0);
      for (int r = 0; r < w; ++r)
        for (int q = 0; q < w; ++q) g[size_t(r)] += blur[size_t(r)][size_t(q)] * rear[size_t(q)];
      return g;
    };
    const int iterations = 6;
    for (int it = 0; it < iterations; ++it) {
      for (int layer = 0; layer < 2; ++layer) {
        const std::vector<double> g = seenRear();
        std::vector<std::vector<double>> v(views.size(), std::vector<double>(size_t(w), 0.0));
        for (const Coefficient& c : field)
          v[c.eye][c.pixel] += c.weight * front[size_t(c.front)] * g[size_t(c.rear)];
        std::vector<double> num(static_cast<size_t>(w), 0.0), den(static_cast<size_t>(w), 0.0);
        for (const Coefficient& c : field) {
          const double t = views[c.eye].target.pixels()[c.pixel].x, seen = v[c.eye][c.pixel];
          if (layer == 0) {
            num[size_t(c.front)] += c.weight * g[size_t(c.rear)] * t;
            den[size_t(c.front)] += c.weight * g[size_t(c.rear)] * seen;
          } else {
            for (int q = 0; q < w; ++q) {
              const double a = c.weight * front[size_t(c.front)] * blur[size_t(c.rear)][size_t(q)];
              num[size_t(q)] += a * t, den[size_t(q)] += a * seen;
            }
          }
        }
        std::vector<double>& x = layer == 0 ? front : rear;
        // The over-relaxed update (layer_factorization.h), in double.
        const double omega = kNmfOverRelaxation, floor = kNmfShrinkFloor;
        for (int i = 0; i < w; ++i)
          if (den[size_t(i)] > 1e-12) {
            const double old = x[size_t(i)], plain = old * num[size_t(i)] / den[size_t(i)];
            const double over = std::max(old + omega * (plain - old), std::min(plain, floor * old));
            x[size_t(i)] = std::clamp(over, 0.0, 1.0);
          }
      }
    }
    SolveReport report;
    const std::vector<LayerFrame> solved =
        factorizeLayers(views, {{Image(w, h, Vec3f(0.5f)), Image(w, h, Vec3f(0.5f))}}, iterations,
                        1, &report, {}, diffuser);
    for (int i = 0; i < w; ++i) {
      EXPECT_NEAR(solved[0].image.at(i, 0).x, front[size_t(i)], 2e-3) << i;
      EXPECT_NEAR(solved[0].mask.at(i, 0).x, rear[size_t(i)], 2e-3) << i;
    }
    expectNonIncreasing(report.objective);
  }
}

// The dense least-squares solution of the operator through the diffuser (its columns probed one
// image pixel at a time, the blur included): where it lies inside [0, 1], the solver reaches
// its objective, in either layer order.
TEST(OptimizeImageLayer, ReachesTheDenseMinimumThroughTheDiffuser) {
  for (const LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
    SCOPED_TRACE(int(order));
    const DisplayDesign d = tinyDisplay(order);
    const RearDiffuser diffuser{0.6, 1.0};
    const Image mask = maskLayerImage(d);
    std::vector<TrainingView> views =
        viewsThroughDiffuser(d, randomImage(27, 2, 12, 0.4f, 0.6f), mask, diffuser);
    Rng rng(3);
    for (TrainingView& v : views)
      for (Vec3f& p : v.target.pixels())
        for (int c = 0; c < 3; ++c) p[c] += 0.003f * (rng.uniform() - 0.5f);
    SolveReport report;
    const Image solved =
        optimizeImageLayer(views, Image(27, 2, Vec3f(0.5f)), mask, 400, 1, &report, {}, diffuser);
    Image dense(27, 2);
    bool inside = true;
    for (int c = 0; c < 3; ++c) {
      const std::vector<double> x = denseLeastSquares(views, mask, c, diffuser);
      for (size_t i = 0; i < x.size(); ++i) {
        dense.pixels()[i][c] = float(x[i]);
        inside &= x[i] >= 0 && x[i] <= 1;
      }
    }
    ASSERT_TRUE(inside);
    const double eDense = layerObjective(views, {{dense, mask}}, 1, diffuser);
    const double eSolved = layerObjective(views, {{solved, mask}}, 1, diffuser);
    EXPECT_GE(eSolved, eDense * (1 - 1e-3) - 1e-12);
    EXPECT_NEAR(eSolved, eDense, 0.02 * eDense + 1e-10);
  }
}

// optimizeImageLayer's step on the plane of d and the previous step p against a brute-force
// search of the Gauss-Newton model m(a, b) = a gd + b gp + (a^2 dd + 2 a b dp + b^2 pp) / 2
// on a grid around it, the rows' sampling as a scaling of the p sums, and the fall-backs to
// steepest descent where the plane is degenerate.
TEST(OptimizeImageLayer, PlaneStepMinimisesTheModelOnThePlane) {
  using detail::Curvatures;
  using detail::planeStep;
  const auto model = [](double a, double b, double gd, double gp, const Curvatures& h) {
    return a * gd + b * gp + 0.5 * (a * a * h.dd + 2 * a * b * h.dp + b * b * h.pp);
  };
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    // A positive-definite curvature (dd pp > dp^2) and a slope along d that descends.
    Curvatures h;
    h.dd = 1.0 + 2.0 * (uniform(random) + 1.0);
    h.pp = 0.5 + (uniform(random) + 1.0);
    h.dp = 0.9 * uniform(random) * std::sqrt(h.dd * h.pp);
    const double gd = -0.2 - std::abs(uniform(random)), gp = uniform(random);
    const auto step = planeStep(gd, gp, h);
    const double best = model(step.a, step.b, gd, gp, h);
    EXPECT_LT(best, model(-gd / h.dd, 0.0, gd, gp, h) + 1e-12) << trial;
    for (int i = -20; i <= 20; ++i)
      for (int k = -20; k <= 20; ++k) {
        const double a = step.a + 0.05 * i, b = step.b + 0.05 * k;
        EXPECT_LE(best, model(a, b, gd, gp, h) + 1e-12) << trial << " " << a << " " << b;
      }
    // The same plane from a quarter of the rows: the sampled sums with p, scaled by dd's.
    Curvatures sampled = h;
    sampled.ddSampled = h.dd / 4, sampled.dp = h.dp / 4, sampled.pp = h.pp / 4;
    const auto fromSample = planeStep(gd, gp, sampled);
    EXPECT_NEAR(fromSample.a, step.a, 1e-9 * std::abs(step.a) + 1e-12);
    EXPECT_NEAR(fromSample.b, step.b, 1e-9 * std::abs(step.b) + 1e-12);
  }
  // No previous step, or one parallel to d: the exact step along d alone.
  for (const Curvatures& h : {Curvatures{2.0, 0.0, 0.0, 0.0}, Curvatures{2.0, 3.0, 4.5, 0.0}}) {
    const auto step = planeStep(-1.0, 0.5, h);
    EXPECT_DOUBLE_EQ(step.a, 0.5);
    EXPECT_EQ(step.b, 0.0);
  }
}

// The over-relaxed update keeps each coordinate of the multiplicative updates' quadratic bound
// (symmetric about the plain update m) no higher than at x: |y - m| <= |x - m| after the clamp
// to [0, 1], so E never increases; and a value the plain update keeps positive stays positive.
TEST(FactorizeLayers, OverRelaxedUpdateStaysWithinTheBound) {
  std::mt19937 random(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), ratio(0.0f, 3.0f);
  int longer = 0;
  for (int trial = 0; trial < 10000; ++trial) {
    const float x = unit(random), m = x * ratio(random);
    const float y = std::clamp(overRelaxedUpdate(x, m), 0.0f, 1.0f);
    const float target = std::clamp(m, 0.0f, 1.0f);
    EXPECT_LE(std::abs(y - m), std::abs(x - m) * (1 + 1e-6f) + 1e-7f) << x << " " << m;
    if (m > 0) {
      EXPECT_GT(y, 0.0f) << x << " " << m;
    }
    // Mostly further along than the plain update (clamped), never the other way.
    EXPECT_LE(std::abs(y - x) + 1e-7f, std::abs(target - x) + std::abs(y - target) + 1e-6f);
    longer += std::abs(y - x) > std::abs(target - x) * 1.5f;
  }
  EXPECT_GT(longer, 1000);
}

}  // namespace
}  // namespace parallax
