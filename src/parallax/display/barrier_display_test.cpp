// The barrier as a DisplayModel answers what its own parts answer (a second code path: the ray
// generator, the mask raster, the design).
#include <gtest/gtest.h>

#include "parallax/display/barrier_rays.h"
#include "parallax/display/display_model.h"

namespace parallax {
namespace {

DisplayDesign smallDesign(bool subpixels) {
  DisplaySpec s = defaultDisplaySpec();
  s.imagePanel.width = s.maskPanel.width = 120;
  s.imagePanel.height = s.maskPanel.height = 20;
  s.imagePanel.pitchMm = s.maskPanel.pitchMm = 1.0;
  BarrierCameraSettings camera;
  camera.subpixelRays = subpixels;
  return designDisplay(s, camera);
}

TEST(BarrierDisplay, AnswersAsItsRayGeneratorAndMask) {
  for (const bool subpixels : {false, true}) {
    const DisplayDesign d = smallDesign(subpixels);
    const ViewFilter filter{ViewFilterKind::Gaussian, 1.5};
    const std::unique_ptr<DisplayModel> display = makeBarrierDisplay(d, filter);
    const BarrierRayGenerator rays(d, filter);
    EXPECT_EQ(display->film().columns, rays.filmWidth());
    EXPECT_EQ(display->film().subpixelColumns, subpixels);
    EXPECT_EQ(display->viewCount(), subpixels ? 27 : 9);
    EXPECT_EQ(display->viewCount(), interleavedViewCount(d));
    for (int column = 0; column < rays.filmWidth(); column += 7) {
      const BarrierRay expected = rays.ray(column + 0.3, 4.6, 0.8, 0.2);
      const DisplayRay got = display->ray(column + 0.3, 4.6, 0.8, 0.2);
      EXPECT_EQ(got.origin.x, expected.origin.x);
      EXPECT_EQ(got.direction.x, expected.direction.x);
      EXPECT_EQ(display->viewIndex(column, 3), rays.viewIndex(column, 3));
      if (subpixels) {
        EXPECT_EQ(display->channelOfColumn(column), rays.channelOfColumn(column));
      }
    }
    EXPECT_EQ(display->viewPosition(4).x, rays.viewPosition(4).x);
    const Image mask = display->maskLayer();
    const Image raster = maskLayerImage(d);
    ASSERT_EQ(mask.pixels().size(), raster.pixels().size());
    for (size_t i = 0; i < mask.pixels().size(); ++i)
      ASSERT_EQ(mask.pixels()[i], raster.pixels()[i]);
    EXPECT_EQ(display->barrierDesign()->views, d.views);
    EXPECT_EQ(display->window().widthMm, d.frontWidthMm());
  }
}

// The ideal view's eye is the virtual eye when the render compresses depth (g' != g).
TEST(BarrierDisplay, IntendedEyeIsTheVirtualEye) {
  BarrierCameraSettings camera;
  camera.virtualGapMm = 6.0;
  const DisplayDesign d = designDisplay(defaultDisplaySpec(), camera);
  const std::unique_ptr<DisplayModel> display = makeBarrierDisplay(d);
  const Vec3d eye{40, 0, 500};
  EXPECT_EQ(display->intendedEye(eye).x, virtualEye(d, eye).x);
  EXPECT_NE(display->intendedEye(eye).x, eye.x);
}

}  // namespace
}  // namespace parallax
