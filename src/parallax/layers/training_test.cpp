// The training set: the dense eyes' layout, targets equal to the ideal views (a second call of
// quality's own idealView) times the scale, and the memory estimate equal to what is held.
#include "parallax/layers/training.h"

#include <gtest/gtest.h>

#include "parallax/quality/viewer_quality.h"

namespace parallax {
namespace {

DisplayDesign smallDisplay() {
  DisplaySpec s = defaultDisplaySpec();
  s.imagePanel.width = s.maskPanel.width = 72;
  s.imagePanel.height = s.maskPanel.height = 12;
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
  for (size_t i : {size_t(0), eyes.size() / 2, eyes.size() - 1}) {
    EXPECT_EQ(views[i].seen.eye().x, eyes[i].position.x);
    EXPECT_EQ(views[i].seen.eye().z, eyes[i].position.z);
    const Image ideal = idealView(scene, accel, d, eyes[i].position, 72, 12, 1, 0);
    for (size_t p = 0; p < ideal.pixels().size(); ++p)
      for (int c = 0; c < 3; ++c)
        EXPECT_FLOAT_EQ(views[i].target.pixels()[p][c], 0.25f * ideal.pixels()[p][c]);
    EXPECT_EQ(views[i].encodingScale, 0.0f);  // linear light unless asked
  }
  double held = 0;
  for (const TrainingView& v : views) held += double(v.target.pixels().size()) * sizeof(Vec3f);
  EXPECT_EQ(trainingBytes(d, options), held);
  options.srgbWeights = true;
  options.distances = {1.0};
  EXPECT_EQ(trainingViews(scene, accel, d, options).front().encodingScale, 0.25f);
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
