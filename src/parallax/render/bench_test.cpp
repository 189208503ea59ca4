// The benchmark counts what it claims: our rays are the renderer's, and the limit traces one
// primary ray per sample plus one shadow ray per primary hit.
#include "parallax/render/bench.h"

#include "parallax/render/render.h"

#include <gtest/gtest.h>

namespace parallax {
namespace {

TEST(Bench, CountsTheRaysOfBothSides) {
  const Scene scene = defaultScene();
  const Accelerator accel(scene);
  const CameraSpec& c = *scene.camera;
  const PinholeCamera camera(c.eye, c.lookAt, c.up, c.fovDegrees, 40, 24);
  const BenchResult r = benchmark(scene, accel, camera, camera, 4, 1);
  RenderStats stats;
  RenderSettings settings;
  settings.samplesPerPixel = 4;
  render(scene, accel, camera, settings, &stats);
  EXPECT_EQ(r.rays, stats.totalRays());
  // Primary: 40 x 24 x 4. Shadow: one per primary hit, counted here with single rays.
  uint64_t hits = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 40; ++x)
      for (int s = 0; s < 4; ++s) {
        const float jx = (s % 2 + 0.5f) / 2, jy = (s / 2 + 0.5f) / 2;
        hits += accel.intersect(camera.generateRay({x + jx, y + jy})).valid();
      }
  EXPECT_NEAR(double(r.limitRays), double(40 * 24 * 4 + hits), 4.0);
  EXPECT_GT(r.raysPerSecond(), 0.0);
  EXPECT_GT(r.limitRaysPerSecond(), 0.0);
  EXPECT_NEAR(r.ratio(), r.raysPerSecond() / r.limitRaysPerSecond(), 1e-12);
}

}  // namespace
}  // namespace parallax
