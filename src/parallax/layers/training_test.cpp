// The training set: the dense eyes' layout, targets equal to the ideal views (a second call of
// quality's own idealView) times the scale, and the memory estimate equal to what is held.
#include "parallax/layers/training.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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
  EXPECT_EQ(seenMaskBytes(d, options), held / 3);  // one float per pixel against three
  // sRGB errors: the same targets, encoded (TrainingView::encodeTarget), in half the bytes.
  options.srgbWeights = true;
  const std::vector<TrainingView> encoded = trainingViews(scene, accel, d, options);
  ASSERT_EQ(encoded.size(), views.size());
  held = 0;
  for (size_t i = 0; i < views.size(); ++i) {
    EXPECT_EQ(encoded[i].encodingScale, 0.25f);
    EXPECT_TRUE(encoded[i].target.empty());
    TrainingView linear = views[i];
    linear.encodingScale = 0.25f;
    linear.encodeTarget();
    EXPECT_EQ(encoded[i].encodedTarget, linear.encodedTarget);
    held += double(encoded[i].encodedTarget.size()) * sizeof(uint16_t);
  }
  EXPECT_EQ(trainingBytes(d, options), held);
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
  TrainingView linear{seen, target};
  EXPECT_THROW(linear.encodeTarget(), std::invalid_argument);
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
