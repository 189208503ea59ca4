// designDisplay refuses quantities outside their physically sensible ranges (display.h),
// naming the key, before any of them can turn a ray into NaN.
#include <gtest/gtest.h>

#include <functional>

#include "parallax/core/error.h"
#include "parallax/display/display.h"
#include "parallax/display/lenticular.h"

namespace parallax {
namespace {

void expectRefused(const std::function<void(DisplaySpec&, BarrierCameraSettings&)>& change,
                   const std::string& key) {
  DisplaySpec spec = defaultDisplaySpec();
  spec.source = "d.json";
  BarrierCameraSettings camera;
  change(spec, camera);
  try {
    designDisplay(spec, camera);
    ADD_FAILURE() << key << ": accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.path(), key) << e.what();
    EXPECT_EQ(e.file(), "d.json");
  }
}

TEST(DisplayRanges, NonsenseQuantitiesAreRefusedWithTheirKey) {
  expectRefused([](DisplaySpec& s, BarrierCameraSettings&) { s.imagePanel.pitchMm = 1e-300; },
                "/image_layer/pixel_pitch_mm");
  expectRefused([](DisplaySpec& s, BarrierCameraSettings&) { s.maskPanel.pitchMm = 11; },
                "/mask_layer/pixel_pitch_mm");
  expectRefused([](DisplaySpec& s, BarrierCameraSettings&) { s.gapMm = 1e300; }, "/gap_mm");
  expectRefused([](DisplaySpec& s, BarrierCameraSettings&) { s.viewDistanceMm = 1e300; },
                "/view_distance_mm");
  expectRefused([](DisplaySpec& s, BarrierCameraSettings&) { s.viewDistanceMm = 5; },
                "/view_distance_mm");
  expectRefused([](DisplaySpec& s, BarrierCameraSettings&) { s.viewZoneCenterXMm = 1e300; },
                "/view_zone/center_x_mm");
  expectRefused([](DisplaySpec& s, BarrierCameraSettings&) { s.views = 1e300; }, "/views");
  expectRefused([](DisplaySpec& s, BarrierCameraSettings&) { s.mask.phasePx = 1e300; },
                "/mask/phase_px");
  expectRefused([](DisplaySpec&, BarrierCameraSettings& c) { c.virtualGapMm = 1e300; },
                "/virtual/gap_mm");
  expectRefused([](DisplaySpec&, BarrierCameraSettings& c) { c.virtualDistanceMm = 1e300; },
                "/virtual/distance_mm");
  expectRefused(
      [](DisplaySpec& s, BarrierCameraSettings&) {
        s.views.reset();
        s.viewDistanceMm.reset();
        s.screenPeriodPx = 9;
        s.slitPeriodPx = 1e300;
      },
      "/slit_period_px");
}

TEST(DisplayRanges, SensibleDisplaysStillDesign) {
  DisplaySpec spec = defaultDisplaySpec();
  BarrierCameraSettings camera;
  camera.virtualDistanceMm = kInfinity;
  EXPECT_NO_THROW(designDisplay(spec, camera));
  spec.gapMm = 999;
  spec.viewDistanceMm = 1e5;
  EXPECT_NO_THROW(designDisplay(spec, camera));
}

TEST(DisplayRanges, LenticularFieldsOutOfRange) {
  LenticularCalibration c;
  c.source = "visual.json";
  c.pitch = 47;
  c.slope = -6;
  c.viewConeDegrees = 40;
  c.dpi = 324;
  c.screenW = 1536;
  c.screenH = 2048;
  EXPECT_NO_THROW(designLenticular(c));
  for (auto [field, key] : {std::pair{&LenticularCalibration::dpi, "/DPI"},
                            std::pair{&LenticularCalibration::pitch, "/pitch"}}) {
    for (double v : {1e-300, 1e300}) {
      LenticularCalibration bad = c;
      bad.*field = v;
      try {
        designLenticular(bad);
        ADD_FAILURE() << key << " " << v << " accepted";
      } catch (const InputError& e) {
        EXPECT_EQ(e.path(), key) << e.what();
      }
    }
  }
}

}  // namespace
}  // namespace parallax
