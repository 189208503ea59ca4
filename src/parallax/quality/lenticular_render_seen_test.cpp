// The rendered panel belongs to its calibration: seen from an eye (sim/lenticular_sim.h), it
// shows what an ideal window shows that eye (WindowCamera, one-axis perspective), inside the view
// cone; beyond the cone the eye sees the repeated views of the other side instead.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "parallax/camera/display_camera.h"
#include "parallax/display/lenticular_test_support.h"
#include "parallax/image/metrics.h"
#include "parallax/render/display_render.h"
#include "parallax/render/quilt.h"
#include "parallax/sim/lenticular_sim.h"

namespace parallax {
namespace {

constexpr double kPi = 3.14159265358979323846;

LenticularDesign smallDesign() {
  return smallLenticularDesign();
}

Scene smallPanelScene() {
  Scene scene = defaultScene();
  scene.display.width = 1.5f;  // the 114 mm panel spans the box and some floor
  return scene;
}

TEST(LenticularRender, EachSubpixelKeepsItsOwnRaysChannel) {
  const LenticularDesign d = smallDesign();
  const Scene scene = smallPanelScene();
  const Accelerator accel(scene);
  const DisplayLayers out = renderDisplay(scene, accel, *makeLenticularDisplay(d), {});
  ASSERT_EQ(out.image.width(), 180);
  ASSERT_EQ(out.image.height(), 120);
  EXPECT_EQ(out.stats.cameraRays, uint64_t(3 * 180 * 120));
  EXPECT_EQ(out.mask.width(), 0);  // one panel, no mask layer
  const Image film =
      render(scene, accel, DisplayCamera(makeLenticularDisplay(d), scene.display), {});
  for (int y = 0; y < 120; y += 7)
    for (int x = 0; x < 180; ++x)
      for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(out.image.at(x, y)[ch], film.at(3 * x + ch, y)[ch]);
}

// Under every reading of the optics (ideal and pixel-wide spot, parallel and converging
// bundles), a panel rendered for that reading and seen under it shows an eye what the window
// shows it, at what an eye resolves (a lens, a colour cycle of rows).
TEST(LenticularRender, SeenFromInsideTheConeItIsTheWindowView) {
  const Scene scene = smallPanelScene();
  const Accelerator accel(scene);
  RenderSettings reference;
  reference.samplesPerPixel = 4;
  for (const double spot : {0.0, 3.0})
    for (const LensBundles bundles : {LensBundles::Parallel, LensBundles::Converging}) {
      LensOptics optics;
      optics.spotWidthSubpixels = spot, optics.bundles = bundles;
      const LenticularDesign d = withOptics(smallDesign(), optics);
      const Image panel = renderDisplay(scene, accel, *makeLenticularDisplay(d), {}).image;
      const std::unique_ptr<DisplayModel> window = makeLenticularDisplay(d);
      const auto error = [&](const Vec3d& seenFrom, const Vec3d& windowFrom) {
        const Image seen = simulateLenticularView(d, panel, seenFrom);
        const WindowCamera camera(windowFrom, *window, scene.display, 180, 120, true);
        return meanSquaredError(
            lenticularAtDisplayResolution(d, seen),
            lenticularAtDisplayResolution(d, render(scene, accel, camera, reference)));
      };
      const double D = d.viewDistanceMm, cone = 40 * kPi / 180;
      const Vec3d centre{0, 0, D}, inside{D * std::tan(0.3 * cone), 0, D};
      const Vec3d outside{D * std::tan(0.8 * cone), 0, D};  // 12 degrees past the cone's edge
      const Vec3d repeat{D * std::tan(-0.2 * cone), 0,
                         D};  // where outside's views were meant to go
      const double centreError = error(centre, centre), insideError = error(inside, inside);
      const double outsideError = error(outside, outside);
      const std::string reading = std::to_string(spot) + " " + lensBundlesName(bundles);
      EXPECT_LT(centreError, 0.01) << reading;
      EXPECT_LT(insideError, 0.01) << reading;
      EXPECT_GT(outsideError, 3 * centreError) << reading;
      EXPECT_GT(outsideError, 3 * insideError) << reading;
      // Past the cone's edge the eye sees the views meant for the other side.
      EXPECT_LT(error(outside, repeat), outsideError / 3) << reading;
      // And an eye above the eye line sees the same views (horizontal parallax only).
      const Image level = simulateLenticularView(d, panel, centre);
      const Image raised = simulateLenticularView(d, panel, {0, 80, D});
      EXPECT_EQ(meanSquaredError(level, raised), 0.0) << reading;
    }
}

// What viewers see: eyes spread evenly over the cone (not only where a subpixel's ray points)
// see the panel closer to the ideal window views when each subpixel's rays cover its own view
// window (filter view) than with its central ray alone, and much closer than when they cover
// the whole lens period.
TEST(LenticularRender, TheViewFilterShowsEyesAcrossTheConeMoreThanTheCentralRay) {
  const LenticularDesign d = smallDesign();
  const Scene scene = smallPanelScene();
  const Accelerator accel(scene);
  RenderSettings sixteen;
  sixteen.samplesPerPixel = 16;
  const Image none =
      renderDisplay(scene, accel, *makeLenticularDisplay(d, {ViewFilterKind::None, 1}), {}).image;
  const Image view = renderDisplay(scene, accel, *makeLenticularDisplay(d), sixteen).image;
  const Image period =
      renderDisplay(scene, accel, *makeLenticularDisplay(d, {ViewFilterKind::Period, 1}), sixteen)
          .image;
  const std::unique_ptr<DisplayModel> window = makeLenticularDisplay(d);
  RenderSettings reference;
  reference.samplesPerPixel = 4;
  const double D = d.viewDistanceMm, cone = 40 * kPi / 180;
  double noneError = 0, viewError = 0, periodError = 0;
  const int eyes = 13;
  for (int i = 0; i < eyes; ++i) {
    const double angle = (-0.4 + 0.8 * i / (eyes - 1)) * cone;
    const Vec3d eye{D * std::tan(angle), 0, D};
    const WindowCamera camera(eye, *window, scene.display, 180, 120, true);
    const Image ideal = lenticularAtDisplayResolution(d, render(scene, accel, camera, reference));
    const auto error = [&](const Image& panel) {
      return meanSquaredError(
                 lenticularAtDisplayResolution(d, simulateLenticularView(d, panel, eye)), ideal) /
             eyes;
    };
    noneError += error(none), viewError += error(view), periodError += error(period);
  }
  std::printf("mean squared error over %d eyes: none %.5f, view %.5f, period %.5f\n", eyes,
              noneError, viewError, periodError);
  EXPECT_LT(viewError, noneError);
  EXPECT_LT(2 * viewError, periodError);
}

}  // namespace
}  // namespace parallax

namespace parallax {
namespace {

// A quilt rendered for a lenticular panel and interlaced onto it the way Looking Glass's shader
// does shows each eye inside the cone its own camera's picture: seen through the lenses it is
// close to the ideal window view, and far closer than the same quilt with its views reversed.
TEST(LenticularQuilt, InterlacedQuiltShowsEachEyeItsView) {
  const LenticularDesign d = smallLenticularDesign();
  const std::unique_ptr<DisplayModel> display = makeLenticularDisplay(d);
  Scene scene = defaultScene();
  scene.display.width = 1.5f;
  const Accelerator accel(scene);
  const QuiltLayout layout{8, 6, 0};
  const Image quilt = renderQuilt(scene, accel, *display, {}, layout, 180, 120);
  std::vector<Image> views = splitQuilt(quilt, layout, "quilt");
  const Image panel = interlaceQuiltLenticular(d, views);
  std::reverse(views.begin(), views.end());
  const Image reversed = interlaceQuiltLenticular(d, views);
  RenderSettings reference;
  reference.samplesPerPixel = 4;
  // Away from the centre, where the reversed quilt's view is another view.
  for (const double t : {0.2, 0.3, 0.8}) {
    const Vec3d eye = display->eyeAcrossZone(t);
    const WindowCamera camera(eye, *display, scene.display, 180, 120, true);
    const Image ideal = render(scene, accel, camera, reference);
    const auto seen = [&](const Image& picture) {
      return lenticularAtDisplayResolution(d, simulateLenticularView(d, picture, eye));
    };
    const double good = psnr(seen(panel), lenticularAtDisplayResolution(d, ideal));
    const double bad = psnr(seen(reversed), lenticularAtDisplayResolution(d, ideal));
    EXPECT_GT(good, 24.0) << "t " << t;
    EXPECT_GT(good, bad + 2.0) << "t " << t;
  }
}

}  // namespace
}  // namespace parallax
