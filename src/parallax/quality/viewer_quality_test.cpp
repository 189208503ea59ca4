// The dense measure against hand-computed truths: eye positions from the view-window formula,
// design eyes from the ray generator, the flicker figure of known image sequences, summaries,
// and a display whose layers equal the ideal picture in the aperture plane.
#include "parallax/quality/viewer_quality.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "parallax/image/metrics.h"
#include "parallax/render/display_render.h"
#include "parallax/render/display_test_support.h"

namespace parallax {
namespace {

TEST(ViewerQuality, DenseEyesSitEvenlyInsideEveryViewsWindow) {
  const DisplayDesign d = designDisplay(smallDisplaySpec());
  const std::vector<DenseEye> eyes = denseEyes(d, 4, {0.8, 1.0, 1.25});
  ASSERT_EQ(eyes.size(), 3u * 9u * 4u);
  const double S = d.viewZoneWidthMm, D = d.viewDistanceMm;
  for (size_t i = 0; i < eyes.size(); ++i) {
    const DenseEye& e = eyes[i];
    const int v = int(i / 4) % 9, k = int(i % 4);
    const double f = i < 36 ? 0.8 : i < 72 ? 1.0 : 1.25;
    EXPECT_EQ(e.view, v);
    EXPECT_DOUBLE_EQ(e.distance, f);
    EXPECT_NEAR(e.position.x, (-0.5 * S + (v + (k + 0.5) / 4) * S / 9) * f, 1e-9);
    EXPECT_NEAR(e.position.z, D * f, 1e-9);
    EXPECT_FALSE(e.designEye);
  }
  // At D the K eyes of view v bracket its design eye, which is the window's centre.
  const std::vector<DenseEye> design = designEyes(d);
  ASSERT_EQ(design.size(), 9u);
  for (int v = 0; v < 9; ++v) {
    EXPECT_NEAR(design[size_t(v)].position.x, -0.5 * S + (v + 0.5) * S / 9, 1e-6);
    EXPECT_TRUE(design[size_t(v)].designEye);
  }
}

TEST(ViewerQuality, FlickerIsTheChangeTheIdealDoesNotHave) {
  Image ideal0(16, 16, Vec3f(0.2f)), ideal1(16, 16, Vec3f(0.6f));
  // The display shows the ideal's change exactly, only darker by a constant (in sRGB): 0.
  const auto shifted = [](const Image& image, float codes) {
    Image out = image;
    for (Vec3f& p : out.pixels())
      for (int c = 0; c < 3; ++c) p[c] = srgbToLinear(linearToSrgb(p[c]) - codes);
    return out;
  };
  EXPECT_NEAR(flickerBetween(shifted(ideal0, 0.1f), ideal0, shifted(ideal1, 0.1f), ideal1), 0.0,
              1e-6);
  // The display does not change while the ideal does: the whole sRGB change.
  const double change = linearToSrgb(0.6f) - linearToSrgb(0.2f);
  EXPECT_NEAR(flickerBetween(ideal0, ideal0, ideal0, ideal1), change, 1e-6);
}

TEST(ViewerQuality, SummaryHasTheMeanAndTheWorstEye) {
  std::vector<EyeQuality> eyes(3);
  eyes[0].psnr = 30, eyes[1].psnr = 20, eyes[2].psnr = 25;
  eyes[1].eye.position = {7, 0, 600};
  eyes[0].flicker = std::nan(""), eyes[1].flicker = 0.1, eyes[2].flicker = 0.3;
  const QualitySummary s = summarise(eyes);
  EXPECT_EQ(s.eyes, 3);
  EXPECT_DOUBLE_EQ(s.meanPsnr, 25.0);
  EXPECT_DOUBLE_EQ(s.worstPsnr, 20.0);
  EXPECT_DOUBLE_EQ(s.worstEye.x, 7.0);
  EXPECT_DOUBLE_EQ(s.meanFlicker, 0.2);  // the first eye of a row has none
}

// The built-in scene framed for a small display, and 4 samples per pixel.
Scene smallScene() {
  Scene scene = defaultScene();
  scene.display.width = 0.75f;
  return scene;
}
RenderSettings fourSamples() {
  RenderSettings settings;
  settings.samplesPerPixel = 4;
  return settings;
}

TEST(ViewerQuality, SharedIdealViewsGiveTheSameScoresAsSeparateRuns) {
  const DisplayDesign d = designDisplay(smallDisplaySpec(90, 30));
  const Scene scene = smallScene();
  const Accelerator accel(scene);
  const DisplayLayers none = renderDisplay(scene, accel, d, {}, {}, {ViewFilterKind::None, 1.0});
  const DisplayLayers view = renderDisplay(scene, accel, d, fourSamples());
  const std::unique_ptr<DisplayModel> display = makeBarrierDisplay(d);
  const std::unique_ptr<SimulatedDisplay> a = simulateDisplay(*display, {none.image, none.mask});
  const std::unique_ptr<SimulatedDisplay> b = simulateDisplay(*display, {view.image, view.mask});
  const std::vector<DenseEye> eyes = denseEyes(d, 1, {1.0});
  const ViewerQualityOptions options{1, 1};
  const std::vector<ViewerQuality> both =
      measureViewerQuality(scene, accel, *display, {a.get(), b.get()}, eyes, options);
  const ViewerQuality alone = measureViewerQuality(scene, accel, *display, *b, eyes, options);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_DOUBLE_EQ(both[1].all.meanPsnr, alone.all.meanPsnr);
  EXPECT_DOUBLE_EQ(both[1].all.meanFlicker, alone.all.meanFlicker);
  EXPECT_EQ(both[1].eyes.size(), eyes.size());
  ASSERT_EQ(both[0].byDistance.size(), 1u);
  EXPECT_TRUE(std::isnan(both[0].eyes.front().flicker));
  EXPECT_FALSE(std::isnan(both[0].eyes.back().flicker));
}

// The default ideal views (kDefaultReferenceSpp, stratified) are as good a truth as 64 samples
// per pixel, because both pictures are compared through the period box: every dense eye's PSNR
// within 0.05 dB of its PSNR against 64-spp ideal views, where the pixel centres alone (1 spp)
// miss by several times as much at some eye (so the comparison resolves what it claims).
TEST(ViewerQuality, TheDefaultIdealViewsAreAsGoodAsSixtyFourSamples) {
  const DisplayDesign d = designDisplay(smallDisplaySpec(180, 60));
  const Scene scene = smallScene();
  const Accelerator accel(scene);
  const DisplayLayers layers = renderDisplay(scene, accel, d, fourSamples());
  const std::unique_ptr<DisplayModel> display = makeBarrierDisplay(d);
  const std::unique_ptr<SimulatedDisplay> seen =
      simulateDisplay(*display, {layers.image, layers.mask});
  const std::vector<DenseEye> eyes = denseEyes(d, 2, {0.8, 1.0, 1.25});
  const auto scores = [&](int spp) {
    return measureViewerQuality(scene, accel, *display, *seen, eyes, {spp, 0}).eyes;
  };
  const std::vector<EyeQuality> truth = scores(64),
                                usual = scores(ViewerQualityOptions{}.referenceSamplesPerPixel),
                                centres = scores(1);
  double usualMiss = 0, centresMiss = 0;
  for (size_t i = 0; i < eyes.size(); ++i) {
    usualMiss = std::max(usualMiss, std::abs(usual[i].psnr - truth[i].psnr));
    centresMiss = std::max(centresMiss, std::abs(centres[i].psnr - truth[i].psnr));
  }
  // 0.034 dB and 0.102 dB here, the truths' jitter their own (kTruthJitterSeed); 0.026 and
  // 0.116 dB when they drew the render's own jitter (seed 0), which the render then matched.
  EXPECT_LT(usualMiss, 0.05);
  EXPECT_GT(centresMiss, 2.5 * usualMiss);
}

// A white image layer behind the real mask (9.045-pixel slit period, openings split over two
// mask pixels where the phase steps), seen from the eye exactly between two design eyes: every
// pixel centre's ray meets the rear layer on the edge of a mask pixel. Integrated exactly over
// each output pixel (the simulator's default) and over a screen period, the picture is even:
// the light through every opening is the same. Point samples alias there: one centre sample
// per output pixel reads whole periods black or too bright as rounding falls, and even 4 x 4
// samples leave +-20 % (a one-pixel opening is 4 samples wide).
TEST(ViewerQuality, AWhiteImageLooksEvenFromBetweenTwoDesignEyes) {
  const DisplayDesign d = designDisplay(smallDisplaySpec(480, 8));
  Scene scene = defaultScene();
  const Accelerator accel(scene);
  DisplayLayers layers = renderDisplay(scene, accel, d, {}, {}, {ViewFilterKind::None, 1.0});
  for (Vec3f& p : layers.image.pixels()) p = Vec3f(1.0f);
  const DisplaySimulator simulator(d, {layers.image, layers.mask}, {});
  const double viewWidth = d.viewZoneWidthMm / 9;
  for (const double x : {0.5 * viewWidth, -1.5 * viewWidth}) {
    const Image seen = atDisplayResolution(d, simulator.view({x, 0, d.viewDistanceMm}));
    // Away from the panel's edges (a period there has parts outside the panel). Within 3 %: the
    // normaliser is the whole mask's mean, and the box is 9 pixels where the seen period is not.
    double lo = 1e9, hi = 0;
    for (int column = 20; column < seen.width() - 20; ++column) {
      const double v = seen.at(column, 4).y;
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
    EXPECT_GT(lo, 0.97) << "eye at x = " << x;
    EXPECT_LT(hi, 1.03) << "eye at x = " << x;
  }
}

}  // namespace
}  // namespace parallax
