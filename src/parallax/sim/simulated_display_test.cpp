// One simulator front for every display: each kind's SimulatedDisplay sees exactly what that
// kind's own simulator sees (a second code path), at the kind's own display resolution.
#include "parallax/sim/simulated_display.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/display/lenticular_test_support.h"
#include "parallax/image/metrics.h"
#include "parallax/sim/lenticular_sim.h"

namespace parallax {
namespace {

Image ramp(int width, int height) {
  Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image.at(x, y) = {float(x) / width, float(y) / height, float((x * 7 + y * 3) % 11) / 10};
  return image;
}

TEST(SimulatedDisplay, TheBarrierSeesWhatTheTwoLayerSimulatorSees) {
  DisplaySpec s = defaultDisplaySpec();
  s.imagePanel.width = s.maskPanel.width = 90;
  s.imagePanel.height = s.maskPanel.height = 30;
  s.imagePanel.pitchMm = s.maskPanel.pitchMm = 1.0;
  const DisplayDesign d = designDisplay(s);
  const LayerImages layers{ramp(90, 30), maskLayerImage(d)};
  SimulationOptions options;
  options.pupilDiameterMm = 3;
  const std::unique_ptr<DisplayModel> display = makeBarrierDisplay(d);
  const std::unique_ptr<SimulatedDisplay> seen = simulateDisplay(*display, layers, options);
  const DisplaySimulator direct(d, layers, options);
  const Vec3d eye{23, 4, 610};
  const Image a = seen->view(eye), b = direct.view(eye);
  ASSERT_EQ(a.pixels().size(), b.pixels().size());
  for (size_t i = 0; i < a.pixels().size(); ++i) ASSERT_EQ(a.pixels()[i], b.pixels()[i]);
  const Image ra = seen->atDisplayResolution(a), rb = atDisplayResolution(d, b);
  for (size_t i = 0; i < ra.pixels().size(); ++i) ASSERT_EQ(ra.pixels()[i], rb.pixels()[i]);
}

// seen(eye) is atDisplayResolution(view(eye)): through SeenLayers' rows where the options allow
// (in both layer orders, with a diffuser, a backlight and time-multiplexed frames), through the
// general simulator otherwise (a pupil, colour filters, point samples, another output size).
TEST(SimulatedDisplay, SeenIsTheViewAtTheDisplaysResolution) {
  for (const LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
    DisplaySpec s = defaultDisplaySpec();
    s.order = order;
    s.imagePanel.width = s.maskPanel.width = 90;
    s.imagePanel.height = s.maskPanel.height = 30;
    s.imagePanel.pitchMm = s.maskPanel.pitchMm = 1.0;
    const DisplayDesign d = designDisplay(s);
    const std::unique_ptr<DisplayModel> display = makeBarrierDisplay(d);
    const LayerImages layers{ramp(90, 30), maskLayerImage(d)};
    Image dimmer = ramp(90, 30);
    for (Vec3f& p : dimmer.pixels()) p = p * 0.5f;
    SimulationOptions plain, diffused, pupil, filters, filtersDiffused, everything, sampled,
        resized;
    diffused.diffuserSigmaMm = 0.7;
    diffused.backlight = Vec3f(0.9f, 1.0f, 0.8f);
    pupil.pupilDiameterMm = 3;
    filters.colourFilters = true;
    filters.backlight = Vec3f(0.9f, 1.0f, 0.8f);
    filtersDiffused = filters;
    filtersDiffused.diffuserSigmaMm = 0.7;
    everything = filtersDiffused;
    everything.pupilDiameterMm = 5;
    everything.pupilSamples = 5;
    sampled.samplesPerPixel = 4;
    resized.width = 180;
    for (const auto& [options, fast] : {std::pair{plain, true},
                                        {diffused, true},
                                        {pupil, true},
                                        {filters, true},
                                        {filtersDiffused, true},
                                        {everything, true},
                                        {sampled, false},
                                        {resized, false}}) {
      EXPECT_EQ(DisplaySimulator(d, layers, options).viewsThroughSeenLayers(), fast);
      EXPECT_THROW(DisplaySimulator(d, layers, options).seen({0, 0, -600}), InputError);
      const std::unique_ptr<SimulatedDisplay> one = simulateDisplay(*display, layers, options);
      const std::unique_ptr<SimulatedDisplay> two = simulateDisplay(
          *display, std::vector<LayerImages>{layers, LayerImages{dimmer, layers.mask}}, options);
      for (const Vec3d eye : {Vec3d{23, 4, 610}, Vec3d{-41, -2, 480}})
        for (const SimulatedDisplay* simulated : {one.get(), two.get()}) {
          const Image a = simulated->seen(eye);
          const Image b = simulated->atDisplayResolution(simulated->view(eye));
          ASSERT_EQ(a.pixels().size(), b.pixels().size());
          double largest = 0;
          for (size_t i = 0; i < a.pixels().size(); ++i)
            for (int c = 0; c < 3; ++c)
              largest = std::max(largest, double(std::abs(a.pixels()[i][c] - b.pixels()[i][c])));
          EXPECT_LT(largest, 1e-5);
          EXPECT_GT(meanLuminance(a), 0.01);
        }
    }
  }
}

TEST(SimulatedDisplay, TheLenticularSeesThroughItsLensesAtOneLensAcross) {
  const LenticularDesign d = smallLenticularDesign();
  const Image panel = ramp(180, 120);
  const std::unique_ptr<DisplayModel> display = makeLenticularDisplay(d);
  const std::unique_ptr<SimulatedDisplay> seen = simulateDisplay(*display, {panel, Image()});
  const Vec3d eye{-120, 10, d.viewDistanceMm};
  const Image a = seen->view(eye), b = simulateLenticularView(d, panel, eye);
  for (size_t i = 0; i < a.pixels().size(); ++i) ASSERT_EQ(a.pixels()[i], b.pixels()[i]);
  // One lens along a row (pixelsPerLens panel pixels at the panel's resolution), and along a
  // column the |slope| rows over which the lenses cycle the three colours.
  const Image ra = seen->atDisplayResolution(a), rb = boxFilterY(boxFilterX(b, d.pixelsPerLens), 6);
  for (size_t i = 0; i < ra.pixels().size(); ++i) ASSERT_EQ(ra.pixels()[i], rb.pixels()[i]);
  // Other optics read the same panel differently (the simulator's readings).
  SimulationOptions ideal;
  ideal.lensOptics = LensOptics{LensBundles::Parallel, 0, 0.0};
  const Image c = simulateDisplay(*display, {panel, Image()}, ideal)->view(eye);
  LensOptics parallelIdeal = ideal.lensOptics.value();
  const Image expected = simulateLenticularView(withOptics(d, parallelIdeal), panel, eye);
  for (size_t i = 0; i < c.pixels().size(); ++i) ASSERT_EQ(c.pixels()[i], expected.pixels()[i]);
  EXPECT_GT(meanSquaredError(a, c), 1e-4);
  // A mask layer has no place on a lenticular: refused, naming the display.
  try {
    simulateDisplay(*display, {panel, Image(180, 120)});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("small.json"), std::string::npos);
  }
}

}  // namespace
}  // namespace parallax
