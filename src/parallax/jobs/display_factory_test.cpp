// The display factory (jobs/display_factory.h): every kind built, what a kind lacks refused,
// a framed barrier equal to the library's own framing.
#include <gtest/gtest.h>

#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "parallax/display/flat_monitor_test_support.h"
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
  const auto frame = [&framing](const DisplayDescription& description) {
    Scene scene = defaultScene();
    makeFramedDisplay(description, {}, framing, scene);
  };
  EXPECT_EQ(fieldOf([&] { frame(portrait()); }), "");
  EXPECT_EQ(fieldOf([&] { frame(smallBarrier()); }), "");
  framing.focus = "near";
  EXPECT_EQ(fieldOf([&] { frame(portrait()); }), "focus");
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
  framing.depthBudget = "2";  // shallower than the scene: a virtual gap flattens it
  const BuiltDisplay built = makeFramedDisplay(smallBarrier(), {}, framing, scene);
  ASSERT_TRUE(built.framing.has_value());
  // The second path: the library's framing of the same scene and design.
  Scene direct = defaultScene();
  framing.apply(direct.display);
  const Framing expected = frameForDisplay(direct, designDisplay(smallDisplaySpec(90, 30)));
  EXPECT_EQ(built->barrierDesign()->virtualGapMm, expected.design.virtualGapMm);
  EXPECT_EQ(scene.display.width, expected.placement.width);
  EXPECT_EQ(built.framing->virtualGapMm, expected.virtualGapMm);
  ASSERT_GT(expected.virtualGapMm, built.framing->gapMm);  // the budget chose a virtual gap...
  EXPECT_NE(built.file.text, makeDisplay(smallBarrier()).file.text);  // ...kept in display.json
}

// A display is designed once: framing keeps the model it is given unless the depth budget gives
// a barrier a virtual gap of its own (or a lenticular panel a depth scale, which wraps it).
TEST(DisplayFactory, FramingKeepsTheDesignedModelWhenTheDesignStands) {
  for (const DisplayDescription& description : {smallBarrier(), portrait()}) {
    Scene scene = defaultScene();
    FramingRequest framing;
    framing.fit = "window";  // no depth budget: the design stands
    BuiltDisplay designed = makeDisplay(description);
    const DisplayModel* model = designed.model.get();
    const BuiltDisplay framed = frameDisplay(std::move(designed), framing, scene);
    ASSERT_TRUE(framed.framing.has_value());
    EXPECT_EQ(framed.framing->depthScale, 1.0);
    EXPECT_EQ(framed.model.get(), model) << description.source();
    EXPECT_EQ(framed.file.text, makeDisplay(description).file.text);
  }
}

// A third kind made in code reaches the runners through the display request, the runners
// unchanged: the render runner's picture is the view runner's ideal view from the monitor's eye
// (a second code path: a pinhole through the window), the design runner reports the model's own
// figures, and a render to files writes the picture and its record without a display file.
TEST(ThirdDisplayKind, TheRunnersTakeADisplayMadeInCode) {
  const Vec3d eye{12.0, -5.0, 600.0};
  DisplayRequest monitor;
  monitor.madeInCode = [eye](const DisplayCameraRequest&) {
    return std::make_unique<FlatMonitor>(64, 36, 300.0, eye);
  };
  const Scene scene = defaultScene();
  RenderRequest render;
  render.display = monitor;
  render.sampling.spp = 1;
  const RenderResult rendered = renderInMemory(render, scene, silentReporter());
  ASSERT_EQ(rendered.frames.size(), 1u);
  EXPECT_TRUE(rendered.frames[0].mask.empty());
  const Image& picture = rendered.frames[0].image;
  ASSERT_EQ(picture.width(), 64);
  ASSERT_EQ(picture.height(), 36);

  ViewRequest view;
  view.display = monitor;
  view.displayEye = eye;
  view.sampling.spp = 1;
  const Image seen = viewInMemory(view, scene, silentReporter());
  ASSERT_EQ(seen.width(), 64);  // the model's viewer panel: its film
  ASSERT_EQ(seen.height(), 36);
  double largest = 0, sum = 0;
  for (size_t i = 0; i < seen.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = std::abs(double(seen.pixels()[i][c]) - picture.pixels()[i][c]);
      largest = std::max(largest, d), sum += seen.pixels()[i][c];
    }
  EXPECT_GT(sum, 0.0);  // the content is in view
  EXPECT_LT(largest, 1e-3);

  DesignRequest design;
  design.display = monitor;
  const DesignReport report = designReport(design, silentReporter());
  EXPECT_NE(report.json.find("\"kind\": \"other\""), std::string::npos) << report.json;
  EXPECT_NE(report.json.find("\"width_mm\": 300"), std::string::npos) << report.json;

  // Layers are a barrier's own: refused by name, as for a lenticular panel.
  RenderRequest solved = render;
  solved.layers.method = "optimized-image";
  EXPECT_EQ(fieldOf([&] { renderInMemory(solved, scene, silentReporter()); }), "layers");

  char pattern[] = "/tmp/parallax-third-kind-XXXXXX";
  ASSERT_NE(mkdtemp(pattern), nullptr);
  const std::filesystem::path root = pattern;
  render.output = (root / "set").string();
  runRender(render, silentReporter());
  std::vector<std::string> written;
  for (const auto& entry : std::filesystem::directory_iterator(root / "set"))
    if (entry.path().filename().string()[0] != '.')  // OutputSet's own mark
      written.push_back(entry.path().filename().string());
  std::sort(written.begin(), written.end());
  EXPECT_EQ(written, (std::vector<std::string>{"image.png", "render.json"}));
  EXPECT_NE(rendered.record.find("\"display_file\": \"<flat monitor>\""), std::string::npos)
      << rendered.record;
  std::filesystem::remove_all(root);
}

}  // namespace
}  // namespace parallax::jobs
