// The display factory (jobs/display_factory.h): every kind built, what a kind lacks refused,
// a framed barrier equal to the library's own framing.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "parallax/io/display_file.h"
#include "parallax/jobs/design_job.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/jobs_test_support.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/render_job.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/view_job.h"
#include "parallax/render/display_test_support.h"

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
  EXPECT_EQ(fieldOf([&] { checkFramingApplies(portrait(), framing); }), "");
  EXPECT_EQ(fieldOf([&] { checkFramingApplies(smallBarrier(), framing); }), "");
  framing.focus = "near";
  EXPECT_EQ(fieldOf([&] { checkFramingApplies(portrait(), framing); }), "focus");
}

// A lenticular panel frames the scene as a barrier does, with the lens's depth of field and a
// depth scale instead of g': the built display's camera rays turn by that scale, and the
// ideal views (intendedEye) look from where the camera looked.
TEST(DisplayFactory, AFramedLenticularPanelScalesItsCameraByTheFraming) {
  Scene scene = defaultScene();
  scene.display.fit = scene.bounds();  // a bare scene: no width given, so the depth fit
  scene.display.content = scene.bounds();
  FramingRequest framing;
  const BuiltDisplay built = makeFramedDisplay(portrait(), {}, framing, scene);
  ASSERT_TRUE(built.framing.has_value());
  const Framing& f = *built.framing;
  EXPECT_TRUE(f.lenticular);
  EXPECT_EQ(f.fit, DisplayFit::Depth);
  ASSERT_LT(f.depthScale, 1);
  EXPECT_TRUE(f.withinBudget());
  EXPECT_EQ(scene.display.width, f.placement.width);
  const double D = built->lenticularDesign()->viewDistanceMm;
  EXPECT_NEAR(built->intendedEye({0, 0, D}).z, D / f.depthScale, 1e-9);
  const BuiltDisplay plain = makeDisplay(portrait());
  const DisplayRay a = plain->ray(2300.5, 1000.5, 0.5, 0.5),
                   b = built->ray(2300.5, 1000.5, 0.5, 0.5);
  EXPECT_NEAR(b.direction.x, f.depthScale * a.direction.x, 1e-12);
  // The file a render writes is the physical calibration.
  EXPECT_EQ(built.file.text, plain.file.text);
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
