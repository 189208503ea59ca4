// One simulator front for every display: each kind's SimulatedDisplay sees exactly what that
// kind's own simulator sees (a second code path), at the kind's own display resolution.
#include "parallax/sim/simulated_display.h"

#include <gtest/gtest.h>

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
