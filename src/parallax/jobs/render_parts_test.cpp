// The render runner's parts (jobs/render_parts.h): the quilt's layout and tiles, the work
// estimate's refusal, and the accelerator sized by the rays the request traces.
#include "parallax/jobs/render_parts.h"

#include <gtest/gtest.h>

#include "parallax/jobs/jobs_test_support.h"
#include "parallax/jobs/limits.h"

namespace parallax::jobs {
namespace {

TEST(RenderParts, AQuiltTakesTheDevicesOwnLayoutAndTiles) {
  const BuiltDisplay panel = makeDisplay(portrait());
  RenderRequest request;
  request.quilt.wanted = true;
  RenderPlan plan;
  plan.settings.samplesPerPixel = 1;
  RecordingReporter reporter;
  planQuilt(request, *panel, plan, reporter);
  const QuiltFormat& device = panel->lenticularDesign()->calibration.quilt;
  EXPECT_EQ(plan.layout.columns, device.columns);
  EXPECT_EQ(plan.layout.rows, device.rows);
  EXPECT_EQ(plan.tileWidth, device.width / device.columns);
  EXPECT_EQ(plan.tileHeight, device.height / device.rows);
  EXPECT_DOUBLE_EQ(plan.layout.aspect, double(plan.tileWidth) / plan.tileHeight);
  // The rays traced are the quilt's pixels times the samples: twice that many expected (one
  // shadow ray each).
  EXPECT_DOUBLE_EQ(cameraRayAccelerator(request, plan, *panel).expectedRays,
                   2.0 * device.columns * device.rows * plan.tileWidth * plan.tileHeight);
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
