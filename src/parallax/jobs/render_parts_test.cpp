// The render runner's parts (jobs/render_parts.h): the quilt's layout and tiles, the work
// estimate's refusal, and the accelerator sized by the rays the request traces.
#include "parallax/jobs/render_parts.h"

#include <gtest/gtest.h>

#include "parallax/io/lenticular_file.h"
#include "parallax/jobs/jobs_test_support.h"
#include "parallax/jobs/limits.h"

namespace parallax::jobs {
namespace {

// planQuilt of `request` (a quilt, auto unless it says) at one sample a pixel.
RenderPlan plannedQuilt(RenderRequest request, const DisplayModel& display,
                        RecordingReporter& reporter) {
  request.quilt.wanted = true;
  RenderPlan plan;
  plan.settings.samplesPerPixel = 1;
  planQuilt(request, display, plan, reporter);
  return plan;
}

TEST(RenderParts, AQuiltTakesTheDevicesOwnLayoutAndTiles) {
  const BuiltDisplay panel = makeDisplay(portrait());
  RenderRequest request;
  request.quilt.wanted = true;
  RecordingReporter reporter;
  const RenderPlan plan = plannedQuilt(request, *panel, reporter);
  const QuiltFormat& device = panel->lenticularDesign()->calibration.quilt;
  EXPECT_EQ(plan.layout.columns, device.columns);
  EXPECT_EQ(plan.layout.rows, device.rows);
  EXPECT_EQ(plan.tileWidth, device.width / device.columns);
  EXPECT_EQ(plan.tileHeight, device.height / device.rows);
  // The name's aspect is the display's (3:4), here also the tiles'.
  EXPECT_NEAR(plan.layout.aspect, 0.75, 1e-12);
  EXPECT_DOUBLE_EQ(double(plan.tileWidth) / plan.tileHeight, 0.75);
  // The rays traced are the quilt's pixels times the samples: twice that many expected (one
  // shadow ray each).
  EXPECT_DOUBLE_EQ(cameraRayAccelerator(request, plan, *panel).expectedRays,
                   2.0 * device.columns * device.rows * plan.tileWidth * plan.tileHeight);
}

// A 16" Gen3 owner's own visual.json (its serial, its measured pitch): `--quilt auto` is the
// device's 7x7 on 5999 x 5999, square tiles, named for the panel's 16:9 as Looking Glass names
// it, not the Portrait's 8x6 a0.75.
TEST(RenderParts, AUnitsOwnFileGetsItsDevicesQuilt) {
  LenticularCalibration unit = *lenticularPreset("16-gen3");
  unit.serial = "LKG-J00332";
  unit.pitch = 44.61;
  unit.center = 0.137;
  DisplayDescription description;
  description.kind = DisplayKind::Lenticular;
  description.lenticular =
      parseLenticularCalibration(lenticularCalibrationText(unit), "visual.json");
  const BuiltDisplay panel = makeDisplay(description);
  const RenderRequest request;
  RecordingReporter reporter;
  const RenderPlan plan = plannedQuilt(request, *panel, reporter);
  EXPECT_EQ(plan.layout.columns, 7);
  EXPECT_EQ(plan.layout.rows, 7);
  EXPECT_EQ(plan.tileWidth, 5999 / 7);
  EXPECT_EQ(plan.tileHeight, 5999 / 7);
  EXPECT_EQ(quiltFileName("quilt", plan.layout, ".png"), "quilt_qs7x7a1.7778.png");
  EXPECT_EQ(panel->viewCount(), 49);
  // Which device, and why; then square tiles on a 16:9 panel: stretched, as Looking Glass's.
  ASSERT_EQ(reporter.notes.size(), 2u);
  EXPECT_NE(reporter.notes[0].find("(lkg:16-gen3, by its serial LKG-J00332): its default quilt "
                                   "7x7 views on 5999x5999"),
            std::string::npos)
      << reporter.notes[0];
  EXPECT_NE(reporter.notes[1].find("a1.7778"), std::string::npos) << reporter.notes[1];
}

TEST(RenderParts, TilesOfAnotherAspectAreNoted) {
  const BuiltDisplay barrier = makeDisplay(smallBarrier());
  RenderRequest request;
  request.quilt.wanted = true;
  request.quilt.width = 40, request.quilt.height = 40;  // the window is 3:1
  RenderPlan plan;
  plan.settings.samplesPerPixel = 1;
  RecordingReporter reporter;
  planQuilt(request, *barrier, plan, reporter);
  ASSERT_EQ(reporter.notes.size(), 1u);
  EXPECT_NE(reporter.notes[0].find("stretched"), std::string::npos) << reporter.notes[0];
}

TEST(RenderParts, TheLayersEstimateRefusesBeforeAllocating) {
  const Limits saved = limits();
  limits().maxMemoryGiB = 1e-6;  // about 1 kB
  const BuiltDisplay barrier = makeDisplay(smallBarrier());
  RenderSettings settings;
  EXPECT_THROW(checkPictureWork(*barrier, false, settings, "small.json"), InputError);
  const BuiltDisplay panel = makeDisplay(portrait());
  try {
    checkPictureWork(*panel, false, settings, "portrait");
    ADD_FAILURE() << "no refusal";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("{max_memory}"), std::string::npos) << e.what();
  }
  limits() = saved;
  EXPECT_NO_THROW(checkPictureWork(*barrier, false, settings, "small.json"));
}

}  // namespace
}  // namespace parallax::jobs
