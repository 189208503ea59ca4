// Display cameras in the scene: the display-to-world mapping, and the window cameras.
#include "parallax/camera/display_camera.h"

#include <gtest/gtest.h>

#include <cmath>

namespace parallax {
namespace {

DisplayPlacement tiltedPlacement() {
  // A display at (1, 2, 3), facing +x, 4 units wide, upright.
  return {{1, 2, 3}, {1, 0, 0}, {0, 1, 0}, 4.0f};
}

TEST(WorldFromDisplay, MapsTheFrontLayerOntoThePlacement) {
  const DisplayDesign d = designDisplay(defaultDisplaySpec());
  const Transform t = worldFromDisplay(tiltedPlacement(), d.frontWidthMm());
  const Vec3f centre = t.point({0, 0, 0});
  EXPECT_NEAR(length(centre - Vec3f(1, 2, 3)), 0.0f, 1e-6f);
  // The right edge is half the width away along right = up x normal = (0, 0, -1).
  const Vec3f right = t.point({float(0.5 * d.frontWidthMm()), 0, 0});
  EXPECT_NEAR(right.z, 3.0f - 2.0f, 1e-5f);
  // The viewer's side (+z in mm) is the normal's side.
  EXPECT_GT(t.point({0, 0, 100}).x, 1.0f);
  EXPECT_GT(t.point({0, 100, 0}).y, 2.0f);
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
  const Transform t = worldFromDisplay(placement, d.frontWidthMm());
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
  const Transform displayFromWorld = worldFromDisplay(placement, d.frontWidthMm()).inverse();
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

}  // namespace
}  // namespace parallax
