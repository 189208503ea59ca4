// The photo maker (the truth calibration from photos is tested against) checked against what it
// did not compute: what an eye sees through a barrier display, from the photo maker's physics
// and from the simulator's own model of the same two colour panels (docs/calibration.md, "The
// photo maker"); the moire of the photo maker's panels is the analytic one in its own tests.
#include <gtest/gtest.h>

#include <cmath>

#include "parallax/display/display.h"
#include "parallax/photomaker/photo_maker.h"
#include "parallax/sim/simulator.h"

namespace parallax {
namespace {

// A picture whose every pixel differs from its neighbours (so a view one pixel off differs).
Image testPicture(int width, int height, int seed) {
  Image picture(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double t = std::sin(0.37 * x * (seed + 1) + 0.71 * y) * 0.5 + 0.5;
      picture.at(x, y) =
          Vec3f(float(t), float(1 - t), float(0.5 + 0.4 * std::cos(0.23 * x + seed)));
    }
  return picture;
}

TEST(PhotoTruth, EyeThroughTwoColourPanelsSeesWhatTheSimulatorSees) {
  for (const LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
    DisplaySpec spec = defaultDisplaySpec();
    spec.imagePanel.width = 180, spec.imagePanel.height = 60, spec.imagePanel.pitchMm = 0.3;
    spec.maskPanel = spec.imagePanel;
    spec.order = order;
    spec.gapMm = 2.5;
    const DisplayDesign design = designDisplay(spec);
    const Image image = testPicture(180, 60, 1), mask = testPicture(180, 60, 2);
    const bool back = order == LayerOrder::BarrierBack;

    photomaker::PhysicalBarrier truth;
    truth.front = {180, 60, 0.3, false, 1.0, 0, 0, 0};  // no black matrix: the simulator has none
    truth.rear = truth.front;
    truth.gapMm = 2.5;
    const Vec3d eye{23, 11, 480};
    // Three output pixels per panel pixel across: each colour stripe its own.
    const Image physics = photomaker::eyeViewBarrier(
        truth, back ? image : mask, back ? mask : image, {eye.x, eye.y, eye.z}, 540, 60, 256);

    SimulationOptions options;
    options.width = 540, options.height = 60;
    options.colourFilters = true;
    options.normalise = false;
    const auto differenceFrom = [&](const DisplayDesign& model) {
      const Image simulated = DisplaySimulator(model, {image, mask}, options).view(eye);
      double difference = 0, total = 0;
      for (int y = 0; y < 60; ++y)
        for (int x = 0; x < 540; ++x)
          for (int c = 0; c < 3; ++c) {
            difference += std::abs(physics.at(x, y)[c] - simulated.at(x, y)[c]);
            total += simulated.at(x, y)[c];
          }
      return difference / total;
    };
    // The two integrate each output pixel differently (256 stratified samples against the
    // simulator's exact pieces): within 2 % of the light; a gap a tenth off, which moves the
    // rear pixels seen by a fifth of a pixel at the edges, is several times that.
    const double same = differenceFrom(design);
    EXPECT_LT(same, 0.02) << (back ? "barrier-back" : "barrier-front");
    DisplaySpec other = spec;
    other.gapMm = 2.75;
    EXPECT_GT(differenceFrom(designDisplay(other)), 3 * same);
  }
}

}  // namespace
}  // namespace parallax
