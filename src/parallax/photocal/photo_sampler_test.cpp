// The photo read as light: sRGB codes decoded, looked up bilinearly between pixel centres, and
// through a camera at display-frame points, against values worked out by hand.
#include "parallax/photocal/photo_sampler.h"

#include <gtest/gtest.h>

#include <cmath>

#include "parallax/image/image.h"

namespace parallax::photocal {
namespace {

// A 40x30 photo whose codes rise by 5 a column in red, 3 in green, 1 in blue.
vision::Photo rampPhoto() {
  vision::Photo photo{40, 30, std::vector<uint8_t>(40 * 30 * 3)};
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x)
      for (int c = 0; c < 3; ++c)
        photo.rgb[size_t(3 * (y * 40 + x) + c)] = uint8_t((c == 0 ? 5 : c == 1 ? 3 : 1) * x + y);
  return photo;
}

// A camera 100 mm in front of the panel, looking straight at it, 100 pixels a unit of slope:
// display (x, y) mm shows at (20 + x, 15 - y).
vision::CameraPose frontal() {
  vision::CameraPose pose;
  pose.rotation = {1, 0, 0, 0, -1, 0, 0, 0, -1};
  pose.translation = {0, 0, 100};
  return pose;
}

double code(int c, int x, int y) {
  return (c == 0 ? 5 : c == 1 ? 3 : 1) * x + y;
}

TEST(PhotoSampler, LightIsTheCodesDecodedAndInterpolatedBetweenPixelCentres) {
  const vision::CameraIntrinsics camera{100, 20, 15, 0, 0};
  const PhotoSampler grey(rampPhoto(), camera, frontal());
  const PhotoSampler colour(rampPhoto(), camera, frontal(), true);
  const auto mean = [](int x, int y) {
    double sum = 0;
    for (int c = 0; c < 3; ++c) sum += srgb8ToLinear(uint8_t(code(c, x, y)));
    return sum / 3;
  };
  // At a pixel's centre, its own light; halfway between two, their mean.
  EXPECT_NEAR(grey.at({7.5, 4.5}), mean(7, 4), 1e-6);
  EXPECT_NEAR(grey.at({8.0, 4.5}), 0.5 * (mean(7, 4) + mean(8, 4)), 1e-6);
  EXPECT_NEAR(grey.at({7.5, 5.0}), 0.5 * (mean(7, 4) + mean(7, 5)), 1e-6);
  float rgb[3];
  ASSERT_TRUE(colour.rgbAt({8.0, 4.5}, rgb));
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(
        rgb[c],
        0.5 * (srgb8ToLinear(uint8_t(code(c, 7, 4))) + srgb8ToLinear(uint8_t(code(c, 8, 4)))),
        1e-6);
  // The colour sampler's mean is the grey sampler's light.
  EXPECT_NEAR(colour.at({11.3, 9.8}), grey.at({11.3, 9.8}), 1e-6);
  // Outside the pixel centres' span: no light.
  EXPECT_TRUE(std::isnan(grey.at({0.2, 5})));
  EXPECT_TRUE(std::isnan(grey.at({10, 29.9})));
  EXPECT_FALSE(grey.rgbAt({10, 10}, rgb));  // a grey sampler keeps no colours
}

TEST(PhotoSampler, DisplayPointsAreReadWhereTheCameraShowsThem) {
  const vision::CameraIntrinsics camera{100, 20, 15, 0, 0};
  const PhotoSampler grey(rampPhoto(), camera, frontal());
  // (x, y) mm at 100 mm is (x, -y) pixels from the principal point (20, 15).
  const vision::PhotoPoint p = grey.project(-12.5, 4.0, 0);
  EXPECT_NEAR(p.x, 7.5, 1e-12);
  EXPECT_NEAR(p.y, 11.0, 1e-12);
  EXPECT_NEAR(grey.atPoint(-12.5, 4.0, 0), grey.at({7.5, 11.0}), 1e-7);
  // A point 100 mm nearer the camera is twice as far from the principal point.
  EXPECT_NEAR(grey.project(-6.25, 2.0, 50).x, 7.5, 1e-12);
  EXPECT_NEAR(grey.pixelsPerMm(0, 0), 1.0, 1e-12);
}

}  // namespace
}  // namespace parallax::photocal
