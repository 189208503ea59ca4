// The image layer's solver (optimizeImageLayer) on tiny light fields: against a dense
// least-squares solution (a second code path), never increasing its objective, in [0, 1], row by
// row and band by band as on the whole image, and through each optic it is solved for.
#include "parallax/layers/image_layer_solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "parallax/display/display_model.h"
#include "parallax/layers/layer_solvers_test_support.h"

namespace parallax {
namespace {

using namespace layer_test;

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

TEST(OptimizeImageLayer, SameLayersForAnyThreadCount) {
  const DisplayDesign d = tinyDisplay(LayerOrder::BarrierBack);
  const Image mask = maskLayerImage(d);
  const std::vector<TrainingView> views = viewsOf(d, randomImage(27, 2, 3), mask, 0.01f);
  const Image a = optimizeImageLayer(views, Image(27, 2, Vec3f(0.5f)), mask, 10, 1);
  const Image b = optimizeImageLayer(views, Image(27, 2, Vec3f(0.5f)), mask, 10, 2);
  EXPECT_EQ(a.pixels(), b.pixels());
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

}  // namespace
}  // namespace parallax
