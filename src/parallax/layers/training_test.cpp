// The training set: the dense eyes' layout, targets equal to the ideal views (a second call of
// quality's own idealView) times the scale, and the memory estimate equal to what is held.
#include "parallax/layers/training.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "parallax/core/parallel.h"
#include "parallax/quality/viewer_quality.h"

namespace parallax {
namespace {

DisplayDesign smallDisplay(int height = 12) {
  DisplaySpec s = defaultDisplaySpec();
  s.imagePanel.width = s.maskPanel.width = 72;
  s.imagePanel.height = s.maskPanel.height = height;
  return designDisplay(s);
}

TEST(Training, TargetsAreTheScaledIdealViewsOfTheDenseEyes) {
  const DisplayDesign d = smallDisplay();
  Scene scene = defaultScene();
  const Accelerator accel(scene);
  TrainingOptions options;
  options.eyesPerView = 2;
  options.distances = {0.9, 1.1};
  options.referenceSamplesPerPixel = 1;
  options.targetScale = 0.25;
  int calls = 0;
  const std::vector<TrainingView> views =
      trainingViews(scene, accel, d, options, [&calls](int, int) { ++calls; });
  const std::vector<DenseEye> eyes = denseEyes(d, 2, {0.9, 1.1});
  ASSERT_EQ(views.size(), eyes.size());
  EXPECT_EQ(calls, int(eyes.size()));
  // Linear light unless asked, kept in 16 bits (TrainingView::encodeTarget): within half a
  // unit (and the float arithmetic's rounding) of the scaled ideal views, the unit a 65535th
  // of the largest value.
  std::vector<Image> ideals;
  double held = 0;
  for (size_t i = 0; i < eyes.size(); ++i) {
    EXPECT_EQ(views[i].seen.eye().x, eyes[i].position.x);
    EXPECT_EQ(views[i].seen.eye().z, eyes[i].position.z);
    ideals.push_back(idealView(scene, accel, d, eyes[i].position, 72, 12, 1, 0, 0,
                               trainingEyeSeed(options.seed, i)));
    const Image& ideal = ideals.back();
    float largest = 0;
    for (const Vec3f& p : ideal.pixels()) largest = std::max({largest, p.x, p.y, p.z});
    EXPECT_EQ(views[i].encodingScale, 0.0f);
    EXPECT_TRUE(views[i].target.empty());
    EXPECT_FLOAT_EQ(views[i].linearUnit, 0.25f * largest / 65535.0f);
    Image holder;
    const Image& target = views[i].linearTarget(holder);
    for (size_t p = 0; p < ideal.pixels().size(); ++p)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(target.pixels()[p][c], 0.25f * ideal.pixels()[p][c],
                    0.51f * views[i].linearUnit);
    held += double(views[i].encodedTarget.size()) * sizeof(uint16_t);
  }
  EXPECT_EQ(trainingBytes(d, options), held);
  EXPECT_EQ(seenMaskBytes(d, options), held / 1.5);  // one float per pixel against 3 halfwords
  // sRGB errors: the same targets, encoded as S(t / c) (TrainingView::encodeTarget).
  options.srgbWeights = true;
  const std::vector<TrainingView> encoded = trainingViews(scene, accel, d, options);
  ASSERT_EQ(encoded.size(), views.size());
  held = 0;
  for (size_t i = 0; i < views.size(); ++i) {
    EXPECT_EQ(encoded[i].encodingScale, 0.25f);
    EXPECT_TRUE(encoded[i].target.empty());
    Image scaled = ideals[i];
    for (Vec3f& p : scaled.pixels()) p = p * 0.25f;
    TrainingView fromIdeal{views[i].seen, scaled, 0.25f};
    fromIdeal.encodeTarget();
    EXPECT_EQ(encoded[i].encodedTarget, fromIdeal.encodedTarget);
    held += double(encoded[i].encodedTarget.size()) * sizeof(uint16_t);
  }
  EXPECT_EQ(trainingBytes(d, options), held);
}

// The targets a band of rows at a time (IdealViewBands, for optimizeImageLayerByBands): every
// band's codes are the rows of trainingViews' whole targets (the same renders, box, scale and
// encoding), on a panel of three tile rows and a part; which solves go by bands, and what they
// hold.
TEST(Training, BandsOfTargetsAreTheWholeTargetsRows) {
  const DisplayDesign d = smallDisplay(53);
  Scene scene = defaultScene();
  const Accelerator accel(scene);
  TrainingOptions options;
  options.eyesPerView = 1, options.distances = {0.9, 1.1};
  options.referenceSamplesPerPixel = 4, options.targetScale = 0.3, options.srgbWeights = true;
  EXPECT_TRUE(solvesByBands(d, options, LayerMethod::OptimizedImage));
  EXPECT_FALSE(solvesByBands(d, options, LayerMethod::Nmf));
  const std::vector<TrainingView> whole = trainingViews(scene, accel, d, options);
  std::vector<TrainingView> bands = trainingEyes(d, options);
  ASSERT_EQ(bands.size(), whole.size());
  const IdealViewBands make(scene, accel, d, options);
  for (const int bandRows : {16, 32}) {
    for (int firstRow = 0; firstRow < 53; firstRow += bandRows) {
      const int rows = std::min(bandRows, 53 - firstRow);
      make(firstRow, rows, bands);
      for (size_t e = 0; e < whole.size(); ++e) {
        EXPECT_EQ(bands[e].seen.eye().x, whole[e].seen.eye().x);
        EXPECT_EQ(bands[e].encodingScale, whole[e].encodingScale);
        ASSERT_EQ(bands[e].firstTargetRow, firstRow);
        ASSERT_EQ(bands[e].encodedTarget.size(), 3 * 72 * size_t(rows));
        EXPECT_TRUE(std::equal(bands[e].encodedTarget.begin(), bands[e].encodedTarget.end(),
                               whole[e].encodedTarget.begin() + 3 * 72 * size_t(firstRow)))
            << e << " " << firstRow;
      }
    }
  }
  EXPECT_THROW(make(8, 16, bands), std::invalid_argument);  // not on a tile row
  // Held: one band's share of the whole targets and seen masks, and the bands' float renders.
  const double whole53 = trainingBytes(d, options) + seenMaskBytes(d, options);
  EXPECT_EQ(trainingHeldBytes(d, options, LayerMethod::Nmf), trainingBytes(d, options));
  EXPECT_NEAR(trainingHeldBytes(d, options, LayerMethod::OptimizedImage),
              whole53 + 2.0 * workerCount(0) * 72 * 53 * 12, 1.0);  // a band is all 53 rows
  const DisplayDesign t = smallDisplay(640);
  EXPECT_NEAR(trainingHeldBytes(t, options, LayerMethod::OptimizedImage),
              (trainingBytes(t, options) + seenMaskBytes(t, options)) / 10.0 +
                  2.0 * workerCount(0) * 72 * 64 * 12,
              1.0);
}

// nmf's boxed targets (the image in front) are made a band of kTargetBandRows rows at a time
// (IdealViewBands::wholeBoxedTargets): the same codes, row units and row squares as the whole
// ideal views (quality's idealView, a second render path) scaled and encoded whole
// (TrainingView::encodeBoxedTarget), on a panel of two whole bands and a part; every row's codes
// are within half its unit of B^T t in floats.
TEST(Training, BoxedTargetsByBandsAreTheWholeViewsBoxed) {
  const int rows = 2 * kTargetBandRows + 22;
  const DisplayDesign d = smallDisplay(rows);
  Scene scene = defaultScene();
  const Accelerator accel(scene);
  TrainingOptions options;
  options.eyesPerView = 1, options.distances = {0.9, 1.1};
  options.referenceSamplesPerPixel = 2, options.targetScale = 0.3, options.boxedTargets = true;
  options.seed = 5;
  int calls = 0, lastDone = 0, lastTotal = 0;
  const std::vector<TrainingView> bands =
      trainingViews(scene, accel, d, options,
                    [&](int done, int total) { ++calls, lastDone = done, lastTotal = total; });
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(lastDone, 3);
  EXPECT_EQ(lastTotal, 3);
  const std::vector<DenseEye> eyes = denseEyes(d, 1, {0.9, 1.1});
  ASSERT_EQ(bands.size(), eyes.size());
  for (size_t e = 0; e < eyes.size(); ++e) {
    const TrainingView& v = bands[e];
    ASSERT_TRUE(v.boxedTarget);
    EXPECT_TRUE(v.target.empty());
    EXPECT_EQ(v.seen.eye().x, eyes[e].position.x);
    Image ideal =
        idealView(scene, accel, d, eyes[e].position, 72, rows, 2, 0, 0, trainingEyeSeed(5, e));
    for (Vec3f& p : ideal.pixels()) p = p * 0.3f;
    // Each eye's own jitter: the truth's samples (or another eye's) give other targets.
    for (const uint64_t other : {kTruthJitterSeed, trainingEyeSeed(5, e + 1), uint64_t(5)}) {
      Image moved = idealView(scene, accel, d, eyes[e].position, 72, rows, 2, 0, 0, other);
      for (Vec3f& p : moved.pixels()) p = p * 0.3f;
      TrainingView elsewhere{SeenLayers(d, eyes[e].position), moved, 0.0f};
      elsewhere.encodeBoxedTarget(2);
      EXPECT_NE(v.encodedTarget, elsewhere.encodedTarget) << e << " " << other;
    }
    TrainingView whole{SeenLayers(d, eyes[e].position), ideal, 0.0f};
    whole.encodeBoxedTarget(2);
    EXPECT_TRUE(std::equal(v.encodedTarget.begin(), v.encodedTarget.end(),
                           whole.encodedTarget.begin(), whole.encodedTarget.end()))
        << e;
    EXPECT_EQ(v.rowUnits, whole.rowUnits);
    EXPECT_EQ(v.rowTargetSquares, whole.rowTargetSquares);
    const Image boxed = v.seen.boxTransposed(ideal, 1);
    std::vector<Vec3f> row(72), scratch(72);
    for (int j = 0; j < rows; ++j) {
      v.boxedTargetRow(j, row.data(), scratch.data());
      for (int i = 0; i < 72; ++i)
        for (int c = 0; c < 3; ++c)
          ASSERT_NEAR(row[size_t(i)][c], boxed.at(i, j)[c], 0.51f * v.rowUnits[size_t(j)]);
    }
  }
}

// No two training eyes, of one render or of renders of nearby seeds, draw the same jitter, nor
// any the truth's ideal views or a render of seed 0 to 9 draw.
TEST(Training, EveryEyeJittersOnItsOwn) {
  std::vector<uint64_t> seeds{kTruthJitterSeed};
  for (uint64_t render = 0; render < 10; ++render) seeds.push_back(render);
  for (uint64_t render = 0; render < 10; ++render)
    for (size_t eye = 0; eye < 1000; ++eye) seeds.push_back(trainingEyeSeed(render, eye));
  std::sort(seeds.begin(), seeds.end());
  EXPECT_EQ(std::adjacent_find(seeds.begin(), seeds.end()), seeds.end());
  // The same eye of the same render: the same seed (the targets are deterministic).
  EXPECT_EQ(trainingEyeSeed(3, 17), trainingEyeSeed(3, 17));
}

// The encoding is S(t / c) (IEC 61966-2-1) in 16 bits, against the standard's formula.
TEST(Training, EncodedTargetsAreTheSrgbFormula) {
  const DisplayDesign d = smallDisplay();
  const SeenLayers seen(d, {0, 0, d.viewDistanceMm});
  Image target(seen.width(), seen.height());
  for (size_t i = 0; i < target.pixels().size(); ++i)
    target.pixels()[i] = Vec3f(0.5f * float(i) / float(target.pixels().size()), 0.0005f, 0.6f);
  TrainingView v{seen, target, 0.5f};
  v.encodeTarget();
  ASSERT_EQ(v.encodedTarget.size(), 3 * target.pixels().size());
  for (size_t i = 0; i < target.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double x = std::min(1.0, double(target.pixels()[i][c]) / 0.5);
      const double s = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
      // Rounding to 16 bits (half a step, 1 / 131070) and the arithmetic (2e-7).
      EXPECT_NEAR(v.encodedTarget[3 * i + size_t(c)] / 65535.0, s, 1.0 / 131070 + 2e-7)
          << i << " " << c;
    }
  // A target with a value that is not finite cannot be kept in 16 bits.
  Image broken = target;
  broken.pixels()[5].y = std::numeric_limits<float>::infinity();
  TrainingView linear{seen, broken};
  EXPECT_THROW(linear.encodeTarget(), std::invalid_argument);
  broken.pixels()[5].y = std::numeric_limits<float>::quiet_NaN();
  TrainingView notANumber{seen, broken};
  EXPECT_THROW(notANumber.encodeTarget(), std::invalid_argument);
  // An all-black target: codes 0 (in any unit).
  TrainingView black{seen, Image(seen.width(), seen.height())};
  black.encodeTarget();
  EXPECT_GT(black.linearUnit, 0.0f);
  for (const uint16_t code : black.encodedTarget) EXPECT_EQ(code, 0);
}

TEST(Training, MeanTransmittanceAveragesPixelsAndChannels) {
  Image layer(4, 2, Vec3f(0.0f));
  layer.at(0, 0) = {1, 1, 1};
  layer.at(3, 1) = {0.3f, 0.6f, 0.9f};
  EXPECT_NEAR(meanTransmittance(layer), (1.0 + 0.6) / 8.0, 1e-7);
  EXPECT_EQ(meanTransmittance(Image()), 0.0);
}

}  // namespace
}  // namespace parallax
