// The display factory (jobs/display_factory.h): every kind built, what a kind lacks refused,
// a framed barrier equal to the library's own framing.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "parallax/accel/accelerator.h"
#include "parallax/camera/camera.h"
#include "parallax/camera/display_camera.h"
#include "parallax/core/error.h"
#include "parallax/display/lenticular_presets.h"
#include "parallax/io/display_file.h"
#include "parallax/jobs/design_job.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/jobs_test_support.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/render_job.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/view_job.h"
#include "parallax/render/display_render.h"
#include "parallax/render/display_test_support.h"
#include "parallax/render/quilt.h"

namespace parallax::jobs {
namespace {

TEST(DisplayFactory, BuildsEveryKindAndRefusesWhatAKindLacks) {
  const BuiltDisplay barrier = makeDisplay(smallBarrier());
  EXPECT_EQ(barrier->kind(), DisplayKind::Barrier);
  EXPECT_EQ(barrier.file.name, "display.json");
  EXPECT_EQ(barrier.file.text, displayFileText(smallDisplaySpec(90, 30)));
  DisplayCameraRequest subpixels;
  subpixels.subpixels = true;
  const BuiltDisplay split = makeDisplay(smallBarrier(), subpixels);
  EXPECT_EQ(split->film().columns, 3 * barrier->film().columns);
  EXPECT_TRUE(split->film().subpixelColumns);
  // The camera's choice does not change the physical display the file describes...
  EXPECT_EQ(split->barrierDesign()->spec.imagePanel.width, 90);
  // ...but it is kept in the display's file, as subpixel_rays.
  EXPECT_NE(split.file.text.find("\"subpixel_rays\": true"), std::string::npos) << split.file.text;

  const BuiltDisplay panel = makeDisplay(portrait());
  EXPECT_EQ(panel->kind(), DisplayKind::Lenticular);
  EXPECT_EQ(panel.file.name, "visual.json");
  EXPECT_FALSE(panel->hasMaskLayer());
  EXPECT_EQ(fieldOf([&] { makeDisplay(portrait(), subpixels); }), "subpixels");
  DisplayCameraRequest distance;
  distance.viewDistanceMm = 800;
  EXPECT_EQ(fieldOf([&] { makeDisplay(smallBarrier(), distance); }), "distance");
  EXPECT_NEAR(makeDisplay(portrait(), distance)->window().eyeMm.z, 800, 1e-9);
  FramingRequest framing;
  framing.fit = "depth";
  EXPECT_EQ(fieldOf([&] { checkFramingApplies(portrait(), framing); }), "framing");
  EXPECT_EQ(fieldOf([&] { checkFramingApplies(smallBarrier(), framing); }), "");
}

TEST(DisplayFactory, AFramedBarrierIsTheFramingOfItsDesign) {
  Scene scene = defaultScene();
  FramingRequest framing;
  framing.fit = "depth";
  const BuiltDisplay built = makeFramedDisplay(smallBarrier(), {}, framing, scene);
  ASSERT_TRUE(built.framing.has_value());
  // The second path: the library's framing of the same scene and design.
  Scene direct = defaultScene();
  framing.apply(direct.display);
  const Framing expected = frameForDisplay(direct, designDisplay(smallDisplaySpec(90, 30)));
  EXPECT_EQ(built->barrierDesign()->virtualGapMm, expected.design.virtualGapMm);
  EXPECT_EQ(scene.display.width, expected.placement.width);
  EXPECT_EQ(built.framing->virtualGapMm, expected.virtualGapMm);
}

}  // namespace
}  // namespace parallax::jobs
