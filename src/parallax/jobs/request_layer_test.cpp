// The request layer itself (docs/architecture.md, "Requests"): checks name the request's
// fields, the factory builds every kind, and each runner gives what the library's own calls
// give (a second code path), in memory, before any front end is involved.
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
#include "parallax/jobs/limits.h"
#include "parallax/jobs/render_job.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/view_job.h"
#include "parallax/render/display_render.h"
#include "parallax/render/display_test_support.h"
#include "parallax/render/quilt.h"

namespace parallax::jobs {
namespace {

// The field a request's check names, or "" when it passes.
std::string fieldOf(const std::function<void()>& check) {
  try {
    check();
  } catch (const RequestError& e) {
    return e.field();
  }
  return "";
}

DisplayDescription smallBarrier() {
  DisplayDescription d;
  d.barrier = smallDisplaySpec(90, 30);
  return d;
}

DisplayDescription portrait() {
  DisplayDescription d;
  d.kind = DisplayKind::Lenticular;
  d.lenticular = *lenticularPreset("portrait");
  return d;
}

TEST(Requests, ChecksNameTheirFields) {
  SamplingRequest sampling;
  sampling.spp = 0;
  EXPECT_EQ(fieldOf([&] { sampling.settings(); }), "spp");
  sampling.spp = 4, sampling.jitter = "sideways";
  EXPECT_EQ(fieldOf([&] { sampling.settings(); }), "jitter");
  sampling.jitter = "auto", sampling.bounces = -1;
  EXPECT_EQ(fieldOf([&] { sampling.settings(); }), "bounces");
  FilterRequest filter;
  filter.kind = "blur";
  EXPECT_EQ(fieldOf([&] { filter.filter(); }), "filter");
  filter.kind = "view", filter.widthViews = 50;
  EXPECT_EQ(fieldOf([&] { filter.filter(); }), "filter_width");
  FramingRequest framing;
  framing.fit = "sideways";
  EXPECT_EQ(fieldOf([&] { framing.check(); }), "fit");
  LayersRequest layers;
  layers.method = "nmf", layers.rank = 17;
  EXPECT_EQ(fieldOf([&] { layers.check(); }), "rank");
  layers.rank = 2, layers.method = "optimized-image";
  EXPECT_EQ(fieldOf([&] { layers.check(); }), "rank");
  layers.rank = 1, layers.error = "srgb", layers.method = "nmf";
  EXPECT_EQ(fieldOf([&] { layers.check(); }), "layer_error");
  layers.error = "", layers.trainEyes = 0;
  EXPECT_EQ(fieldOf([&] { layers.check(); }), "train_eyes");
  RgbdRequest rgbd;
  rgbd.range = "3:1";
  EXPECT_EQ(fieldOf([&] { rgbd.options(); }), "depth_range");
}

TEST(Limits, TheTimeEstimateNamesTheFieldAndItsValue) {
  const Limits saved = limits();
  limits().maxSeconds = 1;
  SamplingRequest sampling;
  sampling.spp = 1 << 20;
  try {
    sampling.checkWork(4096, 4096);
    ADD_FAILURE() << "no refusal";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.field(), "spp");
    EXPECT_EQ(e.value(), std::to_string(1 << 20));
    EXPECT_NE(e.message().find("{max_time}"), std::string::npos) << e.message();
  }
  limits() = saved;
  EXPECT_NO_THROW(sampling.checkWork(16, 16));
}

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

TEST(RenderRunner, InMemoryLayersAreTheLibrarysLayers) {
  const Scene scene = defaultScene();
  RenderRequest request;
  request.loaded = smallBarrier();
  request.sampling.spp = 4;
  RecordingReporter reporter;
  const RenderResult result = renderInMemory(request, scene, reporter);
  ASSERT_EQ(result.frames.size(), 1u);

  // The same layers through the library alone: framed, accelerated and rendered by hand.
  Scene framed = defaultScene();
  const Framing framing = frameForDisplay(framed, designDisplay(smallDisplaySpec(90, 30)));
  framed.display = framing.placement;
  const Accelerator accelerator(framed);
  RenderSettings settings;
  settings.samplesPerPixel = 4;
  const DisplayLayers expected =
      renderDisplay(framed, accelerator, *makeBarrierDisplay(framing.design), settings);
  EXPECT_EQ(result.frames[0].image.pixels(), expected.image.pixels());
  EXPECT_EQ(result.frames[0].mask.pixels(), expected.mask.pixels());
  EXPECT_NE(result.record.find("\"method\": \"barrier-camera\""), std::string::npos);
  EXPECT_NE(result.record.find("\"spp\": 4"), std::string::npos);
}

TEST(RenderRunner, RefusesBeforeAnyWork) {
  const Scene scene = defaultScene();
  RenderRequest request;
  request.loaded = smallBarrier();
  request.quilt.width = request.quilt.height = 64;  // a tile size without a quilt
  EXPECT_EQ(fieldOf([&] { renderInMemory(request, scene, silentReporter()); }), "size");
  request.quilt = {};
  request.sequence.frames = "1:2";
  EXPECT_EQ(fieldOf([&] { renderInMemory(request, scene, silentReporter()); }), "sequence");
  request.sequence = {};
  request.loaded = portrait();
  request.directMapping = true;
  EXPECT_EQ(fieldOf([&] { renderInMemory(request, scene, silentReporter()); }), "direct_mapping");
  request.directMapping = false;
  request.layers.method = "nmf";
  EXPECT_EQ(fieldOf([&] { renderInMemory(request, scene, silentReporter()); }), "layers");
}

TEST(RenderRunner, AQuiltInMemoryTakesTheDisplaysOwnLayout) {
  const Scene scene = defaultScene();
  RenderRequest request;
  request.loaded = smallBarrier();
  request.sampling.spp = 1;
  request.quilt.wanted = true;
  request.quilt.width = 30, request.quilt.height = 10;
  const RenderResult result = renderInMemory(request, scene, silentReporter());
  // auto: one row of the barrier's 9 views.
  EXPECT_EQ(result.quilt.width(), 9 * 30);
  EXPECT_EQ(result.quilt.height(), 10);
  EXPECT_NE(result.record.find("quilt_qs9x1a3.png"), std::string::npos) << result.record;
}

TEST(ViewRunner, APinholeViewIsTheLibrarysRender) {
  const Scene scene = defaultScene();
  ViewRequest request;
  request.width = 64, request.height = 36;
  request.sampling.spp = 1;
  const Image view = viewInMemory(request, scene, silentReporter());
  const CameraSpec spec = scene.camera ? *scene.camera : frameScene(scene);
  const PinholeCamera camera(spec.eye, spec.lookAt, spec.up, spec.fovDegrees, 64, 36);
  const Accelerator accelerator(scene);
  RenderSettings settings;
  settings.samplesPerPixel = 1;
  EXPECT_EQ(view.pixels(), render(scene, accelerator, camera, settings).pixels());
  request.fov = 180.0f;
  EXPECT_EQ(fieldOf([&] { viewInMemory(request, scene, silentReporter()); }), "fov");
  request.fov.reset();
  request.displayEye = Vec3d{0, 0, -10};
  request.loaded = smallBarrier();
  EXPECT_EQ(fieldOf([&] { viewInMemory(request, scene, silentReporter()); }), "display_eye");
}

TEST(DesignRunner, TextAndJsonSayTheSameDesign) {
  DesignRequest request;
  request.loaded = smallBarrier();
  const DesignReport report = designReport(request, silentReporter());
  EXPECT_NE(report.text.find("views                9"), std::string::npos) << report.text;
  EXPECT_NE(report.json.find("\"views\": 9"), std::string::npos) << report.json;
  request.framing.fit = "depth";  // framing needs a scene
  EXPECT_EQ(fieldOf([&] { designReport(request, silentReporter()); }), "fit");
  request.loaded = portrait();
  request.framing = {};
  request.scene = SceneRequest{};
  EXPECT_EQ(fieldOf([&] { designReport(request, silentReporter()); }), "scene");
}

}  // namespace
}  // namespace parallax::jobs
