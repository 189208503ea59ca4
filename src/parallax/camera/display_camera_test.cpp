// Display cameras in the scene: the display-to-world mapping, and the window cameras.
#include "parallax/camera/display_camera.h"

#include <gtest/gtest.h>

#include <cmath>

namespace parallax {
namespace {

DisplayPlacement tiltedPlacement() {
  // A display at (1, 2, 3), facing +x, 4 units wide, upright.
  DisplayPlacement placement;
  placement.center = {1, 2, 3};
  placement.normal = {1, 0, 0};
  placement.width = 4.0f;
  return placement;
}

TEST(WorldFromDisplay, MapsTheFrontLayerOntoThePlacement) {
  const DisplayDesign d = designDisplay(defaultDisplaySpec());
  const Transform t = worldFromDisplay(tiltedPlacement(), displayWindow(d));
  const Vec3f centre = t.point({0, 0, 0});
  EXPECT_NEAR(length(centre - Vec3f(1, 2, 3)), 0.0f, 1e-6f);
  // The right edge is half the width away along right = up x normal = (0, 0, -1).
  const Vec3f right = t.point({float(0.5 * d.frontWidthMm()), 0, 0});
  EXPECT_NEAR(right.z, 3.0f - 2.0f, 1e-5f);
  // The viewer's side (+z in mm) is the normal's side.
  EXPECT_GT(t.point({0, 0, 100}).x, 1.0f);
  EXPECT_GT(t.point({0, 100, 0}).y, 2.0f);
}

TEST(FitDisplayWidth, AFlatPictureFillsTheWindowLessItsMargin) {
  // A 2 x 2 square in the display plane, seen from straight in front: its projection is itself,
  // so it fits when 2 k <= 0.9 H (the window is wider than high): width = W / k.
  const DisplayWindow window{500, 300, {0, 0, 600}};
  DisplayPlacement placement;
  placement.fit = Bounds3f{{-1, -1, 0}, {1, 1, 0}};
  EXPECT_NEAR(fitDisplayWidth(placement, window), 500.0 / (0.9 * 300 / 2), 1e-3);
  placement.fit.reset();
  placement.width = 7.0f;
  EXPECT_EQ(fitDisplayWidth(placement, window), 7.0f);  // a given width is kept
}

TEST(FitDisplayWidth, TheNearFaceOfADeepObjectSetsTheScale) {
  // A cube of side 2 centred on the display: its near face (z = +1) is magnified by
  // D / (D - k). Its corner x = k D / (D - k) reaches 0.45 W (the margin) when
  // k = 0.45 W D / (D + 0.45 W), taking the narrower of width and height.
  const DisplayWindow window{400, 300, {0, 0, 600}};
  DisplayPlacement placement;
  placement.center = {5, 5, 5};
  placement.fit = Bounds3f{{4, 4, 4}, {6, 6, 6}};
  const double half = 0.45 * 300, d = 600;
  const double k = half * d / (d + half);
  EXPECT_NEAR(fitDisplayWidth(placement, window), 400.0 / k, 1e-3);
  // The transform puts that near corner on the margin, seen from the eye.
  const Transform world = worldFromDisplay(placement, window);
  const Vec3f corner = world.inverse().point({6, 6, 6});  // display mm
  EXPECT_NEAR(corner.y * d / (d - corner.z), half, 1e-2);
}

// Where a world-space ray crosses the display plane, in display millimetres.
Vec3f crossingInMm(const Transform& worldFromDisplay, const Ray& ray) {
  const Transform displayFromWorld = worldFromDisplay.inverse();
  const Vec3f o = displayFromWorld.point(ray.origin), d = displayFromWorld.vector(ray.direction);
  return o + d * (-o.z / d.z);
}

TEST(WindowCamera, FilmIsTheFrontLayerAndRaysStartAtTheEye) {
  const DisplayDesign d = designDisplay(defaultDisplaySpec());
  const DisplayPlacement placement = tiltedPlacement();
  const Transform t = worldFromDisplay(placement, displayWindow(d));
  const Vec3d eye{100, -40, 500};
  const WindowCamera camera(eye, d, placement, 64, 36);
  const Ray corner = camera.generateRay({0, 0});
  const Vec3f hit = crossingInMm(t, corner);
  EXPECT_NEAR(hit.x, -0.5f * float(d.frontWidthMm()), 1e-3f);
  EXPECT_NEAR(hit.y, 0.5f * float(d.frontHeightMm()), 1e-3f);
  const Vec3f origin = t.inverse().point(corner.origin);
  EXPECT_NEAR(origin.x, 100.0f, 1e-2f);
  EXPECT_NEAR(origin.z, 500.0f, 1e-2f);
}

TEST(WindowCamera, HorizontalOnlyMeetsTheViewLineInY) {
  DisplaySpec spec = defaultDisplaySpec();
  spec.viewZoneHeightMm = 25.0;
  const DisplayDesign d = designDisplay(spec);
  const DisplayPlacement placement = tiltedPlacement();
  const Transform displayFromWorld = worldFromDisplay(placement, displayWindow(d)).inverse();
  const Vec3d eye{60, -80, 450};
  const WindowCamera camera(eye, d, placement, 40, 30, true);
  for (float y : {0.5f, 10.5f, 29.5f}) {
    const Ray ray = camera.generateRay({20.5f, y});
    const Vec3f o = displayFromWorld.point(ray.origin),
                dir = displayFromWorld.vector(ray.direction);
    // In x the ray passes through the eye; in y through the view line at z = D.
    const auto at = [&](float z) { return o + dir * ((z - o.z) / dir.z); };
    EXPECT_NEAR(at(450.0f).x, 60.0f, 1e-2f);
    EXPECT_NEAR(at(float(d.viewDistanceMm)).y, 25.0f, 1e-2f);
  }
}

TEST(DisplayCamera, PacketsMatchSingleRays) {
  DisplaySpec spec = defaultDisplaySpec();
  spec.imagePanel.width = spec.maskPanel.width = 90;
  spec.imagePanel.height = spec.maskPanel.height = 20;
  const DisplayCamera camera(designDisplay(spec), tiltedPlacement());
  FilmSamples16 samples;
  RayPacket16 packet;
  for (int i = 0; i < 16; ++i) {
    samples.x[i] = 3.3f * float(i), samples.y[i] = 0.7f * float(i);
    samples.apertureU[i] = 0.06f * float(i), samples.apertureV[i] = 0.5f;
    packet.active[i] = i % 5 == 0 ? 0 : -1;
  }
  camera.generateRays16(samples, packet);
  for (int i = 0; i < 16; ++i) {
    if (!packet.active[i]) continue;
    const Ray single = camera.generateRay(samples.at(i));
    const Ray fromPacket = packet.ray(i);
    EXPECT_NEAR(length(single.origin - fromPacket.origin), 0.0f, 1e-4f);
    EXPECT_NEAR(length(single.direction - fromPacket.direction), 0.0f, 1e-6f);
  }
}

// The ideal views' packets (WindowCamera::generateRays16, a lane loop) are generateRay's rays,
// with and without one-axis perspective; the caller's active flags are left as they were.
TEST(WindowCamera, PacketsMatchSingleRays) {
  DisplaySpec spec = defaultDisplaySpec();
  spec.viewZoneHeightMm = 25.0;
  const DisplayDesign d = designDisplay(spec);
  for (const bool horizontalOnly : {false, true}) {
    const WindowCamera camera({60, -80, 450}, d, tiltedPlacement(), 40, 30, horizontalOnly);
    FilmSamples16 samples;
    RayPacket16 packet;
    for (int i = 0; i < 16; ++i) {
      samples.x[i] = 2.45f * float(i) + 0.3f, samples.y[i] = 1.85f * float(i) + 0.1f;
      samples.apertureU[i] = samples.apertureV[i] = 0.5f;
      packet.active[i] = i % 5 == 0 ? 0 : -1;
    }
    camera.generateRays16(samples, packet);
    for (int i = 0; i < 16; ++i) {
      EXPECT_EQ(packet.active[i], i % 5 == 0 ? 0 : -1);
      const Ray single = camera.generateRay(samples.at(i)), fromPacket = packet.ray(i);
      // Millimetres of a 600 mm scene in float: agreement to rounding.
      EXPECT_LT(length(single.origin - fromPacket.origin), 1e-4f * length(single.origin) + 1e-4f)
          << horizontalOnly << " " << i;
      EXPECT_LT(length(single.direction - fromPacket.direction), 1e-5f * length(single.direction))
          << horizontalOnly << " " << i;
      EXPECT_EQ(fromPacket.tMin, 0.0f);
      EXPECT_EQ(fromPacket.tMax, single.tMax);
    }
  }
}

}  // namespace
}  // namespace parallax
