// renderDisplay's own sampling rule (render/display_render.h, displayRenderSettings).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/camera/display_camera.h"
#include "parallax/display/display_model.h"
#include "parallax/display/flat_monitor_test_support.h"
#include "parallax/display/lenticular_presets.h"
#include "parallax/render/display_render.h"
#include "parallax/render/display_test_support.h"
#include "parallax/render/render.h"
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

TEST(ThirdDisplayKind, AFlatMonitorRendersAsThePinholeEyeThatSeesIt) {
  const Scene scene = defaultScene();
  const Accelerator accelerator(scene);
  const FlatMonitor monitor(64, 36, 300.0, {12.0, -5.0, 600.0});
  EXPECT_STREQ(displayKindName(monitor.kind()), "other");
  EXPECT_FALSE(monitor.barrierDesign() || monitor.lenticularDesign() || monitor.hasMaskLayer());
  RenderSettings settings;
  settings.samplesPerPixel = 1;
  const DisplayLayers layers = renderDisplay(scene, accelerator, monitor, settings);
  EXPECT_TRUE(layers.mask.empty());
  ASSERT_EQ(layers.image.width(), 64);
  ASSERT_EQ(layers.image.height(), 36);
  const WindowCamera eye(monitor.window().eyeMm, monitor, scene.display, 64, 36);
  const Image seen = render(scene, accelerator, eye, settings);
  // The same rays, generated two ways: the same picture but for the rays' last bits.
  double largest = 0, sum = 0;
  for (size_t i = 0; i < seen.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = std::abs(double(seen.pixels()[i][c]) - layers.image.pixels()[i][c]);
      largest = std::max(largest, d), sum += seen.pixels()[i][c];
    }
  EXPECT_GT(sum, 0.0);  // the content is in view
  EXPECT_LT(largest, 1e-3);
}

}  // namespace
}  // namespace parallax
