// Both layers factorised (factorizeLayers, nmf) on tiny light fields: against dense
// multiplicative updates written out on the explicit light-field coefficients (a second code
// path), never increasing the objective, in [0, 1] at any rank, whatever the thread count and
// eye order, and through each optic it is solved for.
#include "parallax/layers/layer_factorization.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "parallax/display/display_model.h"
#include "parallax/layers/layer_solvers_test_support.h"

namespace parallax {
namespace {

using namespace layer_test;

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
