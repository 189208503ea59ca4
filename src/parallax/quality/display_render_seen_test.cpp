// The two layer images belong together: from an eye at a design position, the image pixels
// seen through the mask are what an ideal window shows that eye (view --display-eye). The
// "seeing" here is a small simulation written for the test: the line from the eye through a
// front pixel's centre, on to the rear (mask) layer, open where an aperture lies.
#include "parallax/render/display_render.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "parallax/camera/display_camera.h"
#include "parallax/display/display_model.h"
#include "parallax/image/metrics.h"
#include "parallax/render/display_test_support.h"
#include "parallax/sim/simulator.h"

namespace parallax {
namespace {

TEST(DisplayRender, SeenThroughTheMaskTheImageIsTheWindowView) {
  const DisplayDesign d = designDisplay(smallDisplaySpec());
  Scene scene = defaultScene();
  // 180 pixels of 0.2745 mm: the display is 49.4 mm wide; the box is about 0.9 units.
  scene.display.width = 1.5f;
  const Accelerator accel(scene);
  const DisplayLayers layers = renderDisplay(scene, accel, d, {});
  ASSERT_EQ(layers.image.width(), 180);
  ASSERT_EQ(layers.mask.width(), 180);

  const double dx = d.spec.imagePanel.pitchMm, D = d.viewDistanceMm, g = d.gapMm;
  const double halfWidth = 0.5 * d.spec.imagePanel.widthMm();
  const double aperture = d.spec.mask.dutyCycle * d.slitPeriodMm;
  for (int view : {1, 4, 7}) {
    // Rays of view j meet at x = (j - (N-1)/2) dx (1 + D / g) on the view line (G1, G2).
    const Vec3d eye{(view - 4) * dx * (1.0 + D / g), d.spec.viewZoneHeightMm, D};
    const WindowCamera window(eye, d, scene.display, 180, 60);
    const Image ideal = render(scene, accel, window, {});
    int seen = 0, matching = 0;
    for (int y = 0; y < 60; ++y)
      for (int x = 0; x < 180; ++x) {
        const double fx = -halfWidth + (x + 0.5) * dx;
        // On to the mask layer at z = -g: open if an aperture centre is within half a width.
        const double mx = eye.x + (fx - eye.x) * (D + g) / D;
        const double k = std::round((mx - d.apertureOriginMm) / d.slitPeriodMm);
        const double centre = d.apertureOriginMm + k * d.slitPeriodMm;
        if (std::abs(mx - centre) >= 0.5 * aperture) continue;
        ++seen;
        const Vec3f a = layers.image.at(x, y), b = ideal.at(x, y);
        matching += length(a - b) <= 1e-3f * (1.0f + length(b));
      }
    // The eye sees about a duty cycle's share of the pixels, and each is the window's view.
    EXPECT_NEAR(double(seen) / (180 * 60), d.spec.mask.dutyCycle, 0.03) << "view " << view;
    EXPECT_GE(matching, seen - seen / 100) << "view " << view << ": " << matching << " of " << seen;
  }
}

TEST(DisplayRender, SubpixelChannelsComeFromTheirOwnRays) {
  BarrierCameraSettings subpixels;
  subpixels.subpixelRays = true;
  const DisplayDesign d = designDisplay(smallDisplaySpec(), subpixels);
  Scene scene = defaultScene();
  scene.display.width = 1.5f;
  const Accelerator accel(scene);
  const DisplayLayers layers = renderDisplay(scene, accel, d, {});
  // The film has three columns per pixel; pixel x's red is film column 3x's red (RGB order).
  const DisplayCamera camera(d, scene.display);
  const Image film = render(scene, accel, camera, {});
  ASSERT_EQ(film.width(), 540);
  for (int y = 0; y < 60; y += 7)
    for (int x = 0; x < 180; ++x) {
      EXPECT_EQ(layers.image.at(x, y).x, film.at(3 * x, y).x);
      EXPECT_EQ(layers.image.at(x, y).y, film.at(3 * x + 1, y).y);
      EXPECT_EQ(layers.image.at(x, y).z, film.at(3 * x + 2, y).z);
    }
}

TEST(DisplayRender, DirectMappingAtOneSampleCastsTheBarrierCamerasRays) {
  // At spp = 1 the display ray of a pixel passes through the pixel centre and its view's
  // design eye position, which is exactly the ray of that view's ordinary (one-axis) camera
  // through the same pixel: two code paths, one image.
  const DisplayDesign d = designDisplay(smallDisplaySpec());
  Scene scene = defaultScene();
  scene.display.width = 1.5f;
  const Accelerator accel(scene);
  const Image barrier = renderDisplay(scene, accel, d, {}).image;
  const Image direct = renderDirectMapping(scene, accel, d, {}).image;
  int close = 0;
  for (size_t i = 0; i < barrier.pixels().size(); ++i)
    close += length(barrier.pixels()[i] - direct.pixels()[i]) <= 1e-3f;
  EXPECT_GE(close, int(barrier.pixels().size()) * 99 / 100);
  // With super-sampling they differ: the barrier camera also jitters across the aperture.
  RenderSettings sixteen;
  sixteen.samplesPerPixel = 16;
  EXPECT_NE(renderDisplay(scene, accel, d, sixteen).image.pixels(),
            renderDirectMapping(scene, accel, d, sixteen).image.pixels());
}

// The simulated view of a rendered scene against the ideal view of the same eye, both at the
// display's spatial resolution (one screen period).
double psnrToReference(const Scene& scene, const Accelerator& accel, const DisplayDesign& d,
                       const DisplayLayers& layers, const Vec3d& eye) {
  SimulationOptions options;
  options.samplesPerPixel = 4;
  const DisplaySimulator simulator(d, {layers.image, layers.mask}, options);
  const WindowCamera camera(eye, d, scene.display, d.spec.imagePanel.width,
                            d.spec.imagePanel.height, true);
  RenderSettings settings;
  settings.samplesPerPixel = 4;
  const double period = d.screenPeriodPx;
  const Image reference = boxFilterX(render(scene, accel, camera, settings), period);
  return psnr(boxFilterX(simulator.view(eye), period), reference);
}

TEST(DisplayRender, SimulatedViewMatchesItsReferenceBestInsideTheViewZone) {
  const DisplayDesign d = designDisplay(smallDisplaySpec());
  Scene scene = defaultScene();
  scene.display.width = 1.5f;
  const Accelerator accel(scene);
  RenderSettings settings;
  settings.samplesPerPixel = 4;
  const DisplayLayers layers = renderDisplay(scene, accel, d, settings);
  const std::unique_ptr<DisplayModel> rays = makeBarrierDisplay(d);
  double inside = 1e9;
  for (int view : {2, 4, 6})
    inside = std::min(inside, psnrToReference(scene, accel, d, layers, rays->viewPosition(view)));
  // Outside the zone the periodic barrier wraps: the eye sees other groups' views.
  const Vec3d outside{0.75 * d.viewZoneWidthMm, 0.0, d.viewDistanceMm};
  const double out = psnrToReference(scene, accel, d, layers, outside);
  EXPECT_GT(inside, out + 6.0) << "inside " << inside << " dB, outside " << out << " dB";
}

// A checkerboard plane at depth z (mm, display frame), lit uniformly; 1 scene unit = 1 mm.
Scene checkerPlaneAt(const DisplayDesign& d, float z) {
  Scene scene;
  scene.display = DisplayPlacement{};
  scene.display.center = {0, 0, 0}, scene.display.normal = {0, 0, 1}, scene.display.up = {0, 1, 0};
  scene.display.width = float(d.frontWidthMm());
  scene.display.fit = std::nullopt;
  Texture checker;
  checker.kind = Texture::Kind::Checker;
  checker.color = Vec3f(0.9f);
  checker.color2 = Vec3f(0.1f);
  checker.checkerSize = float(4.0 * d.screenPeriodMm);  // squares four groups wide
  scene.textures.push_back(checker);
  Material m;
  m.diffuse = Vec3f(1.0f);
  m.diffuseTexture = 0;
  scene.materials.push_back(m);
  scene.ambient = Vec3f(1.0f);
  addQuad(scene, "plane", {-300, -300, z}, {600, 0, 0}, {0, 600, 0}, 0);
  return scene;
}

TEST(DisplayRender, SceneInTheAperturePlaneAgreesWithItsReference) {
  // Content lying in the mask (aperture) plane, z = -g for barrier-back, is reproduced at the
  // full spatial resolution from every eye (depth 0 in G4): every pixel of a group shows the
  // point at its aperture, which is the point each design eye sees there. The same checker
  // far beyond the depth of field (G4: 27 mm) is not.
  const DisplayDesign d = designDisplay(smallDisplaySpec());
  const std::unique_ptr<DisplayModel> rays = makeBarrierDisplay(d);
  RenderSettings settings;
  settings.samplesPerPixel = 4;
  for (const auto& [z, inPlane] : {std::pair{float(d.maskLayerZ()), true}, {-150.0f, false}}) {
    const Scene scene = checkerPlaneAt(d, z);
    const Accelerator accel(scene);
    const DisplayLayers layers = renderDisplay(scene, accel, d, settings);
    for (int view : {1, 4, 7}) {
      const double p = psnrToReference(scene, accel, d, layers, rays->viewPosition(view));
      if (inPlane) {
        EXPECT_GT(p, 17.0) << "in the aperture plane, view " << view;
      } else {
        EXPECT_LT(p, 14.0) << "far behind, view " << view;
      }
    }
  }
}

// The display's prefilter against a construction made only from ideal views (the truth of
// docs/display-geometry.md, "Super-sampling"): for every view, ideal views from K eyes evenly
// inside its window at D, averaged; each pixel then takes the average of its own view. With
// many rays per pixel the `view` filter must give that picture, and the other filters must
// not (they integrate over other windows).
TEST(DisplayRender, ViewFilterEqualsIdealViewsAveragedOverEachPixelsViewWindow) {
  const DisplayDesign d = designDisplay(smallDisplaySpec());
  Scene scene = defaultScene();
  scene.display.width = 1.5f;
  const Accelerator accel(scene);
  const std::unique_ptr<DisplayModel> rays = makeBarrierDisplay(d);
  const int width = d.spec.imagePanel.width, height = d.spec.imagePanel.height;
  const int views = 9, eyesPerView = 8;
  RenderSettings idealSettings;
  idealSettings.samplesPerPixel = 16;
  std::vector<Image> perView;
  for (int v = 0; v < views; ++v) {
    Image sum(width, height);
    for (int k = 0; k < eyesPerView; ++k) {
      const double x =
          -0.5 * d.viewZoneWidthMm + (v + (k + 0.5) / eyesPerView) * d.viewZoneWidthMm / views;
      const WindowCamera camera({x, d.spec.viewZoneHeightMm, d.viewDistanceMm}, d, scene.display,
                                width, height, true);
      const Image ideal = render(scene, accel, camera, idealSettings);
      for (size_t i = 0; i < sum.pixels().size(); ++i)
        sum.pixels()[i] = sum.pixels()[i] + ideal.pixels()[i] * (1.0f / eyesPerView);
    }
    perView.push_back(sum);
  }
  Image construction(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      construction.at(x, y) = perView[size_t(rays->viewIndex(x, y))].at(x, y);

  RenderSettings settings;
  settings.samplesPerPixel = 64;
  const auto score = [&](ViewFilterKind kind) {
    const DisplayLayers layers = renderDisplay(scene, accel, d, settings, {}, {kind, 1.0});
    return psnr(layers.image, construction);
  };
  const double view = score(ViewFilterKind::View), none = score(ViewFilterKind::None);
  const double period = score(ViewFilterKind::Period), tent = score(ViewFilterKind::Tent);
  EXPECT_GT(view, 45.0);
  EXPECT_GT(view, none + 6.0) << "none " << none;
  EXPECT_GT(view, tent + 3.0) << "tent " << tent;
  EXPECT_GT(view, period + 10.0) << "period " << period;
  RecordProperty("psnr_view", std::to_string(view));
  std::printf("against the construction: view %.2f dB, tent %.2f, none %.2f, period %.2f\n", view,
              tent, none, period);
}

TEST(DisplayRender, MaskLayerImageIsTheRaster) {
  const DisplayDesign d = designDisplay(smallDisplaySpec());
  const Image mask = maskLayerImage(d);
  double mean = 0;
  for (const Vec3f& p : mask.pixels()) mean += p.x;
  mean /= double(mask.pixels().size());
  EXPECT_NEAR(mean, d.spec.mask.dutyCycle, 0.1 * d.spec.mask.dutyCycle);
}

}  // namespace
}  // namespace parallax
