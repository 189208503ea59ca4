// The solvers' operator against the simulator it models (a second code path), and its adjoints
// against itself (the dot-product test <A x, y> = <x, A^T y>).
#include "parallax/sim/seen_layers.h"

#include <gtest/gtest.h>

#include "parallax/core/random.h"
#include "parallax/display/display_model.h"
#include "parallax/sim/diffuser.h"
#include "parallax/sim/sim_test_support.h"
#include "parallax/sim/simulated_display.h"
#include "parallax/sim/simulator.h"

namespace parallax {
namespace {

Image randomImage(int width, int height, uint64_t seed) {
  Rng rng(seed);
  Image image(width, height);
  for (Vec3f& p : image.pixels()) p = {rng.uniform(), rng.uniform(), rng.uniform()};
  return image;
}

double dot(const Image& a, const Image& b) {
  double sum = 0;
  for (size_t i = 0; i < a.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) sum += double(a.pixels()[i][c]) * b.pixels()[i][c];
  return sum;
}

TEST(SeenLayers, EqualsTheSimulatorsExactViewInBothLayerOrders) {
  for (const LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
    const DisplayDesign d = smallDisplay(order, 90, 8);
    const Image image = randomImage(d.spec.imagePanel.width, d.spec.imagePanel.height, 3);
    const Image mask = maskLayerImage(d);
    const std::unique_ptr<DisplayModel> model = makeBarrierDisplay(d);
    SimulationOptions options;
    options.normalisation = 0.5;  // a known divisor: the operator is unnormalised
    const auto simulated = simulateDisplay(*model, LayerImages{image, mask}, options);
    for (const Vec3d eye : {Vec3d{0, 0, 600}, Vec3d{-37.5, 4, 520}, Vec3d{61, -3, 790}}) {
      const SeenLayers seen(d, eye);
      const SeenLayers unboxed(d, eye, {.periodBox = false});
      const bool front = order == LayerOrder::BarrierBack;
      const Image a = front ? seen.view(image, mask) : seen.view(mask, image);
      const Image b = front ? unboxed.view(image, mask) : unboxed.view(mask, image);
      const Image raw = simulated->view(eye);
      const Image boxed = simulated->atDisplayResolution(raw);
      for (size_t i = 0; i < a.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(b.pixels()[i][c], 0.5f * raw.pixels()[i][c], 1e-5f) << i;
          EXPECT_NEAR(a.pixels()[i][c], 0.5f * boxed.pixels()[i][c], 1e-5f) << i;
        }
    }
  }
}

// Columns whose rear cells are not two neighbours at a constant shift are read through their
// pieces (SeenLayers::unevenColumns_): every column when the rear panel's pitch is a third of
// the front's (three or four cells a column), the rows' ends otherwise.
TEST(SeenLayers, EqualsTheSimulatorsExactViewWithARearPanelOfAnotherPitch) {
  DisplaySpec s = smallDisplay(LayerOrder::BarrierBack, 60, 8).spec;
  s.maskPanel.width = 3 * s.imagePanel.width;
  s.maskPanel.height = 3 * s.imagePanel.height;
  s.maskPanel.pitchMm = s.imagePanel.pitchMm / 3;
  const DisplayDesign d = designDisplay(s);
  const Image image = randomImage(d.spec.imagePanel.width, d.spec.imagePanel.height, 8);
  const Image mask = randomImage(d.spec.maskPanel.width, d.spec.maskPanel.height, 9);
  const std::unique_ptr<DisplayModel> model = makeBarrierDisplay(d);
  SimulationOptions options;
  options.normalisation = 0.5;
  const auto simulated = simulateDisplay(*model, LayerImages{image, mask}, options);
  for (const Vec3d eye : {Vec3d{0, 0, 600}, Vec3d{-37.5, 4, 520}}) {
    const Image a = SeenLayers(d, eye, {.periodBox = false}).view(image, mask);
    const Image raw = simulated->view(eye);
    for (size_t i = 0; i < a.pixels().size(); ++i)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.pixels()[i][c], 0.5f * raw.pixels()[i][c], 1e-5f);
    // And its adjoint.
    const SeenLayers seen(d, eye);
    const Image y = randomImage(seen.width(), seen.height(), 10);
    Image gRear(mask.width(), mask.height());
    seen.addRearGradient(y, image, gRear);
    const double vy = dot(seen.view(image, mask), y);
    EXPECT_NEAR(vy, dot(mask, gRear), 1e-4 * vy);
  }
}

// Through colour filters (SeenOptics::colourFilters) the operator reads the layers' pixels
// through their stripes, the simulator its striped cells (a second code path): equal in both
// layer orders, with the mask panel in RGB, BGR or no stripes, its adjoints with them; and not
// the view without filters.
TEST(SeenLayers, ThroughColourFiltersEqualsTheSimulatorsStripedView) {
  for (const LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront})
    for (const SubpixelOrder maskStripes :
         {SubpixelOrder::RGB, SubpixelOrder::BGR, SubpixelOrder::None}) {
      DisplaySpec s = smallDisplay(order, 90, 8).spec;
      s.maskPanel.subpixels = maskStripes;
      const DisplayDesign d = designDisplay(s);
      const Image image = randomImage(d.spec.imagePanel.width, d.spec.imagePanel.height, 11);
      const Image mask = randomImage(d.spec.maskPanel.width, d.spec.maskPanel.height, 12);
      const std::unique_ptr<DisplayModel> model = makeBarrierDisplay(d);
      SimulationOptions options;
      options.colourFilters = true;
      options.normalisation = 0.5;                  // the simulator then scales by (stripes) / 0.5
      options.width = 3 * d.spec.imagePanel.width;  // view()'s general path, three columns a pixel
      const auto simulated = simulateDisplay(*model, LayerImages{image, mask}, options);
      const bool front = order == LayerOrder::BarrierBack;
      for (const Vec3d eye : {Vec3d{0, 0, 600}, Vec3d{-37.5, 4, 520}, Vec3d{61, -3, 790}}) {
        const SeenLayers seen(d, eye, {.periodBox = false, .colourFilters = true});
        EXPECT_FALSE(seen.seesGreyAsGrey());
        const Image a = front ? seen.view(image, mask) : seen.view(mask, image);
        // The simulator's view three columns a pixel, summed back to pixels (exact integrals
        // add up).
        const Image raw = simulated->view(eye);
        const Image plain = front ? SeenLayers(d, eye, {.periodBox = false}).view(image, mask)
                                  : SeenLayers(d, eye, {.periodBox = false}).view(mask, image);
        double differs = 0;
        for (int y = 0; y < a.height(); ++y)
          for (int x = 0; x < a.width(); ++x) {
            const Vec3f sum =
                (raw.at(3 * x, y) + raw.at(3 * x + 1, y) + raw.at(3 * x + 2, y)) * (0.5f / 3.0f);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.at(x, y)[c], sum[c], 1e-5f) << x;
            differs = std::max(differs, double(std::abs(a.at(x, y).x - plain.at(x, y).x)));
          }
        EXPECT_GT(differs, 0.05);
        const SeenLayers boxed(d, eye, {.colourFilters = true});
        const Image f = randomImage(90, 8, 13), r = randomImage(90, 8, 14);
        const Image y = randomImage(boxed.width(), boxed.height(), 15);
        Image gFront(90, 8), gRear(90, 8);
        boxed.addFrontGradient(y, r, gFront);
        boxed.addRearGradient(y, f, gRear);
        const double vy = dot(boxed.view(f, r), y);
        EXPECT_NEAR(vy, dot(f, gFront), 1e-4 * vy);
        EXPECT_NEAR(vy, dot(r, gRear), 1e-4 * vy);
      }
    }
}

// The rear layer's stripes two ways: SeenLayers' filtered pieces on its pixels, and its stripe
// cells (sim/diffuser.h, unblurred) read as they are (SeenOptics::rearStripeCells); and the
// stripe cells' blur and its transpose pass the dot-product test.
TEST(SeenLayers, RearStripeCellsAreTheRearPixelsThroughTheirFilters) {
  for (const SubpixelOrder stripes : {SubpixelOrder::RGB, SubpixelOrder::BGR}) {
    DisplaySpec s = smallDisplay(LayerOrder::BarrierBack, 90, 8).spec;
    s.maskPanel.subpixels = stripes;
    const DisplayDesign d = designDisplay(s);
    const Image front = randomImage(90, 8, 21), rear = randomImage(90, 8, 22);
    const double pitch = d.spec.maskPanel.pitchMm;
    for (const Vec3d eye : {Vec3d{0, 0, 600}, Vec3d{-37.5, 4, 520}}) {
      const Image a = SeenLayers(d, eye, {.colourFilters = true}).view(front, rear);
      const Image b = SeenLayers(d, eye, {.colourFilters = true, .rearStripeCells = true})
                          .view(front, stripedDiffuserBlurred(rear, stripes, 0.0, pitch));
      for (size_t i = 0; i < a.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.pixels()[i][c], b.pixels()[i][c], 1e-5f) << i;
      // The cells' adjoint (their runs of four or five cells a column, read as planes).
      const SeenLayers seen(d, eye, {.colourFilters = true, .rearStripeCells = true});
      const Image cells = randomImage(270, 8, 24), y = randomImage(90, 8, 25);
      Image gCells(270, 8);
      seen.addRearGradient(y, front, gCells);
      const double vy = dot(seen.view(front, cells), y);
      EXPECT_NEAR(vy, dot(cells, gCells), 1e-5 * vy);
    }
    const Image cells = randomImage(270, 8, 23);
    const Image blurred = stripedDiffuserBlurred(rear, stripes, 0.7, pitch);
    const Image back = stripedDiffuserBlurredTransposed(cells, stripes, 0.7, pitch);
    ASSERT_EQ(blurred.width(), 270);
    ASSERT_EQ(back.width(), 90);
    EXPECT_NEAR(dot(blurred, cells), dot(rear, back), 1e-5 * dot(blurred, cells));
  }
}

// For a pinhole eye and through a pupil (its sights' adjoints gathered by rearRowSources).
TEST(SeenLayers, AdjointsPassTheDotProductTest) {
  for (const double pupil : {0.0, 40.0})
    for (const LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
      const DisplayDesign d = smallDisplay(order, 60, 6);
      const SeenLayers seen(d, {12, 2, 560}, {.pupilDiameterMm = pupil, .pupilSamples = 4});
      EXPECT_EQ(seen.sights(), pupil > 0 ? 4 : 1);
      const Image front = randomImage(60, 6, 1), rear = randomImage(60, 6, 2);
      const Image y = randomImage(seen.width(), seen.height(), 4);
      const Image v = seen.view(front, rear);
      Image gFront(60, 6), gRear(60, 6);
      seen.addFrontGradient(y, rear, gFront);
      seen.addRearGradient(y, front, gRear);
      // V is linear in each layer: <V(front, rear), y> = <front, A_rear^T y> = <rear, A_front^T y>.
      EXPECT_NEAR(dot(v, y), dot(front, gFront), 1e-4 * dot(v, y));
      EXPECT_NEAR(dot(v, y), dot(rear, gRear), 1e-4 * dot(v, y));
      const Image boxed = seen.box(y), back = seen.boxTransposed(y);
      EXPECT_NEAR(dot(boxed, v), dot(y, seen.boxTransposed(v)), 1e-4 * dot(boxed, v));
      EXPECT_GT(dot(back, back), 0.0);
    }
}

TEST(SeenLayers, SameGradientsForAnyThreadCount) {
  const DisplayDesign d = smallDisplay(LayerOrder::BarrierBack, 60, 40);
  const SeenLayers seen(d, {-20, 0, 640});
  const Image front = randomImage(60, 40, 5), rear = randomImage(60, 40, 6);
  const Image y = randomImage(60, 40, 7);
  Image a(60, 40), b(60, 40), c(60, 40), e(60, 40);
  seen.addFrontGradient(y, rear, a, 1);
  seen.addFrontGradient(y, rear, b, 2);
  seen.addRearGradient(y, front, c, 1);
  seen.addRearGradient(y, front, e, 2);
  EXPECT_EQ(a.pixels(), b.pixels());
  EXPECT_EQ(c.pixels(), e.pixels());
}

// Time-multiplexed frames are seen as the average of their views.
// A scratch that keeps its blends (RowScratch::keepBlends) gives every eye's seen rear row as a
// fresh scratch does: eyes at one distance (the same rear rows and weights: the blend taken
// again), at another distance and height (made anew), two rear layers in turn (one blend each),
// and an eye of the first distance again after them. The eyes at one distance do share it.
TEST(SeenLayers, KeptBlendsGiveTheSeenRearRowsOfAFreshScratch) {
  const DisplayDesign d = smallDisplay(LayerOrder::BarrierBack, 90, 12);
  const Image first = randomImage(d.spec.maskPanel.width, d.spec.maskPanel.height, 5);
  const Image second = randomImage(d.spec.maskPanel.width, d.spec.maskPanel.height, 6);
  const std::vector<Vec3d> eyes{
      {-20, 0, 600}, {15, 0, 600}, {40, 0, 600}, {0, 7, 480}, {5, 0, 600}};
  const int width = d.spec.imagePanel.width;
  SeenLayers::RowScratch kept;
  kept.keepBlends = true;
  for (int j = 0; j < d.spec.imagePanel.height; ++j)
    for (const Vec3d& eye : eyes) {
      const SeenLayers seen(d, eye);
      for (const Image* rear : {&first, &second}) {
        std::vector<Vec3f> fresh(static_cast<size_t>(width)), reused(static_cast<size_t>(width));
        SeenLayers::RowScratch scratch;
        seen.seenRearRow(*rear, j, fresh.data(), scratch);
        seen.seenRearRow(*rear, j, reused.data(), kept);
        for (int i = 0; i < width; ++i)
          ASSERT_EQ(fresh[size_t(i)], reused[size_t(i)]) << j << " " << i;
      }
    }
  EXPECT_EQ(kept.blends.size(), 2u);
  // The eyes at 600 mm see a row through the same rear rows and weights.
  SeenLayers::RowScratch one;
  one.keepBlends = true;
  std::vector<Vec3f> row(static_cast<size_t>(width));
  SeenLayers(d, eyes[0]).seenRearRow(first, 5, row.data(), one);
  const std::vector<Piece> pieces = one.blends.front().pieces;
  ASSERT_FALSE(pieces.empty());
  one.blends.front().rows.assign(one.blends.front().rows.size(), Vec3f(0.5f));
  SeenLayers(d, eyes[1]).seenRearRow(first, 5, row.data(), one);
  for (const Vec3f& p : row) EXPECT_LE(p.x, 0.5f + 1e-6f);  // read from the kept (altered) blend
}

TEST(SimulatedFrames, SeeTheAverageOfTheFramesViews) {
  const DisplayDesign d = smallDisplay(LayerOrder::BarrierBack, 90, 8);
  const std::unique_ptr<DisplayModel> model = makeBarrierDisplay(d);
  SimulationOptions options;
  options.normalisation = 0.25;
  std::vector<LayerImages> frames;
  for (uint64_t k = 0; k < 3; ++k)
    frames.push_back({randomImage(90, 8, 10 + k), randomImage(90, 8, 20 + k)});
  const auto all = simulateDisplay(*model, frames, options);
  const Vec3d eye{14, -2, 610};
  const Image seen = all->view(eye);
  Image expected(seen.width(), seen.height());
  for (const LayerImages& f : frames) {
    const Image one = simulateDisplay(*model, f, options)->view(eye);
    for (size_t i = 0; i < one.pixels().size(); ++i) expected.pixels()[i] += one.pixels()[i] / 3.0f;
  }
  for (size_t i = 0; i < seen.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(seen.pixels()[i][c], expected.pixels()[i][c], 1e-5f);
}

}  // namespace
}  // namespace parallax
