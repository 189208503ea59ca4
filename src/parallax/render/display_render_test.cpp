// renderDisplay's own sampling rule (render/display_render.h, displayRenderSettings).
#include <gtest/gtest.h>

#include <memory>

#include "parallax/accel/accelerator.h"
#include "parallax/display/display_model.h"
#include "parallax/display/lenticular_presets.h"
#include "parallax/render/display_render.h"
#include "parallax/render/display_test_support.h"
#include "parallax/scene/scene.h"

namespace parallax {
namespace {

// render itself knows the view filter none's rule: every sample is the pixel's central ray, so
// any sample count renders as one sample per film pixel, on both display kinds.
TEST(DisplayRenderSettings, FilterNoneRendersOneSamplePerPixel) {
  const Scene scene = defaultScene();
  const Accelerator accelerator(scene);
  ViewFilter none;
  none.kind = ViewFilterKind::None;
  const std::unique_ptr<DisplayModel> barrier =
      makeBarrierDisplay(designDisplay(smallDisplaySpec(60, 20)), none);
  RenderSettings many;
  many.samplesPerPixel = 16;
  EXPECT_EQ(displayRenderSettings(*barrier, many).samplesPerPixel, 1);
  const DisplayLayers once = renderDisplay(scene, accelerator, *barrier, many);
  EXPECT_EQ(once.stats.cameraRays, uint64_t(60 * 20));
  RenderSettings one;
  one.samplesPerPixel = 1;
  EXPECT_EQ(once.image.pixels(), renderDisplay(scene, accelerator, *barrier, one).image.pixels());
  // Any other filter spreads the samples: the count stays.
  const std::unique_ptr<DisplayModel> spread =
      makeBarrierDisplay(designDisplay(smallDisplaySpec(60, 20)));
  EXPECT_EQ(displayRenderSettings(*spread, many).samplesPerPixel, 16);
  const LenticularCalibration calibration = *lenticularPreset("portrait");
  EXPECT_EQ(displayRenderSettings(*makeLenticularDisplay(designLenticular(calibration), none), many)
                .samplesPerPixel,
            1);
}

}  // namespace
}  // namespace parallax
