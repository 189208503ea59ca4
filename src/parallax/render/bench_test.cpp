// The benchmark counts what it claims: our rays are the renderer's, and each limit traces one
// primary ray per sample plus one shadow ray per primary hit.
#include "parallax/render/bench.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "parallax/display/lenticular_test_support.h"
#include "parallax/render/display_render.h"
#include "parallax/render/quilt.h"
#include "parallax/render/render.h"

namespace parallax {
namespace {

TEST(Bench, CountsTheRaysOfEverySide) {
  const Scene scene = defaultScene();
  const Accelerator accel(scene);
  const CameraSpec& c = *scene.camera;
  const PinholeCamera camera(c.eye, c.lookAt, c.up, c.fovDegrees, 40, 24);
  RenderSettings settings;
  settings.samplesPerPixel = 4;
  const BenchResult r = benchmark(scene, accel, camera, camera.grid(4), settings, 1);
  RenderStats stats;
  render(scene, accel, camera, settings, &stats);
  EXPECT_EQ(r.ours.rays, stats.totalRays());
  // Primary: 40 x 24 x 4. Shadow: one per primary hit, counted here with single rays.
  uint64_t hits = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 40; ++x)
      for (int s = 0; s < 4; ++s) {
        const float jx = (s % 2 + 0.5f) / 2, jy = (s / 2 + 0.5f) / 2;
        hits += accel.intersect(camera.generateRay({x + jx, y + jy})).valid();
      }
  EXPECT_NEAR(double(r.limit.rays), double(40 * 24 * 4 + hits), 4.0);
  // Misses: the limit's primaries are the stratum centres counted above; ours are the
  // renderer's own count.
  EXPECT_EQ(r.limit.primaryRays, uint64_t(40 * 24 * 4));
  EXPECT_NEAR(double(r.limit.primaryMisses), double(40 * 24 * 4 - hits), 4.0);
  EXPECT_EQ(r.ours.primaryRays, stats.cameraRays);
  EXPECT_EQ(r.ours.primaryMisses, stats.cameraMisses);
  EXPECT_GT(r.ours.missFraction(), 0.0);
  EXPECT_LT(r.ours.missFraction(), 1.0);
  // Embree alone traces exactly the same-rays loop's rays; only the clock differs.
  EXPECT_EQ(r.embreeAlone.rays, r.sameRays.rays);
  EXPECT_EQ(r.embreeAlone.primaryRays, r.sameRays.primaryRays);
  EXPECT_EQ(r.embreeAlone.primaryMisses, r.sameRays.primaryMisses);
  EXPECT_EQ(r.sameRays.primaryRays, stats.cameraRays);
  EXPECT_GT(r.embreeAlone.seconds, 0.0);
  EXPECT_EQ(r.packetWidth, accel.packetWidth());
  EXPECT_NEAR(r.sameRaysRatio(), r.ours.perSecond() / r.sameRays.perSecond(), 1e-12);
  EXPECT_NEAR(r.rayOrderRatio() * r.sameRaysRatio(), r.ratio(), 1e-12);
  // The same-rays limit traces the renderer's primary rays: as many as the renderer's.
  EXPECT_GE(r.sameRays.rays, stats.cameraRays);
  EXPECT_LE(r.sameRays.rays, 2 * stats.cameraRays);
  EXPECT_GT(r.ours.perSecond(), 0.0);
  EXPECT_GT(r.limit.perSecond(), 0.0);
  EXPECT_NEAR(r.ratio(), r.ours.perSecond() / r.limit.perSecond(), 1e-12);
  // Embree on our rays traced what the renderer counted, ray for ray: the accelerator's log
  // against the tracer's own tally (camera, shadow and mirror rays).
  EXPECT_EQ(r.embreeOnOurs.rays, stats.totalRays());
  EXPECT_GT(r.embreeOnOurs.seconds, 0.0);
  const double generation = r.sameRays.seconds - r.embreeAlone.seconds;
  EXPECT_NEAR(r.rayGenerationSeconds(), std::max(0.0, generation), 1e-12);
  EXPECT_NEAR(r.tracedRaysRatio(),
              (r.rayGenerationSeconds() + r.embreeOnOurs.seconds) / r.ours.seconds, 1e-12);
  EXPECT_GE(r.shadingOverEmbree(), 0.0);
}

TEST(Bench, EmbreeOnOurRaysCountsMirrorBouncesAndEveryLight) {
  // Two lights and a mirror floor: ours traces far more than one shadow ray per camera ray,
  // and Embree on our rays traces all of them.
  Scene scene = defaultScene();
  scene.materials[0].mirror = Vec3f(0.3f);
  Light point;
  point.kind = Light::Kind::Point;
  point.position = {2, 3, 2};
  point.intensity = Vec3f(5.0f);
  scene.lights.push_back(point);
  const Accelerator accel(scene);
  const CameraSpec& c = *scene.camera;
  const PinholeCamera camera(c.eye, c.lookAt, c.up, c.fovDegrees, 32, 20);
  RenderSettings settings;
  settings.samplesPerPixel = 4;
  const BenchResult r = benchmark(scene, accel, camera, camera.grid(4), settings, 1);
  RenderStats stats;
  render(scene, accel, camera, settings, &stats);
  EXPECT_GT(stats.secondaryRays, 0u);
  EXPECT_EQ(r.embreeOnOurs.rays, stats.totalRays());
  EXPECT_EQ(r.embreeOnOurs.primaryRays, stats.cameraRays + stats.secondaryRays);
  EXPECT_GT(r.embreeOnOurs.rays, r.sameRays.rays);
}

TEST(Bench, CameraMissesAreTheRaysThatSeeTheBackground) {
  // Counted against single rays through the same pixels at 1 spp (pixel centres).
  const Scene scene = defaultScene();
  const Accelerator accel(scene);
  const CameraSpec& c = *scene.camera;
  // The scene's own view (some background), and straight up into the sky (all background).
  for (const Vec3f& lookAt : {c.lookAt, c.eye + Vec3f{0, 1, 0.2f}}) {
    const PinholeCamera camera(c.eye, lookAt, c.up, c.fovDegrees, 33, 19);
    RenderSettings settings;
    settings.samplesPerPixel = 1;
    RenderStats stats;
    render(scene, accel, camera, settings, &stats);
    uint64_t misses = 0;
    for (int y = 0; y < 19; ++y)
      for (int x = 0; x < 33; ++x)
        misses += !accel.intersect(camera.generateRay({x + 0.5f, y + 0.5f})).valid();
    EXPECT_EQ(stats.cameraRays, uint64_t(33 * 19));
    EXPECT_EQ(stats.cameraMisses, misses);
    EXPECT_GT(misses, 0u);
    if (lookAt == c.lookAt) {
      EXPECT_LT(misses, stats.cameraRays);
    }
  }
}

TEST(Bench, AtOneSampleBothLimitsTraceThePixelCentres) {
  // At 1 spp the renderer's pinhole rays are the pixel centres, which is what the pinhole
  // limit traces: two code paths, one set of rays, the same count of primary and shadow rays.
  const Scene scene = defaultScene();
  const Accelerator accel(scene);
  const CameraSpec& c = *scene.camera;
  const PinholeCamera camera(c.eye, c.lookAt, c.up, c.fovDegrees, 37, 21);
  const BenchResult r = benchmark(scene, accel, camera, camera.grid(1), RenderSettings{}, 1);
  EXPECT_EQ(r.sameRays.rays, r.limit.rays);
  EXPECT_GT(r.limit.rays, uint64_t(37 * 21));
}

// The views' limit traces each view's grid as the limit traces its one: given the limit's own
// grid as its only view it traces the same rays; given two views, each's.
TEST(Bench, TheViewsLimitTracesEveryViewsGrid) {
  const Scene scene = defaultScene();
  const Accelerator accel(scene);
  const CameraSpec& c = *scene.camera;
  const PinholeCamera camera(c.eye, c.lookAt, c.up, c.fovDegrees, 37, 21);
  const PinholeCamera narrow(c.eye + Vec3f{0.3f, 0, 0}, c.lookAt, c.up, c.fovDegrees, 19, 21);
  const BenchResult one =
      benchmark(scene, accel, camera, camera.grid(4), RenderSettings{}, 1, {camera.grid(4)});
  EXPECT_EQ(one.viewsLimit.rays, one.limit.rays);
  EXPECT_EQ(one.viewsLimit.primaryMisses, one.limit.primaryMisses);
  const BenchResult none = benchmark(scene, accel, camera, camera.grid(4), RenderSettings{}, 1);
  EXPECT_EQ(none.viewsLimit.rays, 0u);
  EXPECT_EQ(none.viewsRatio(), 0.0);
  const BenchResult two = benchmark(scene, accel, camera, camera.grid(4), RenderSettings{}, 1,
                                    {camera.grid(4), narrow.grid(4)});
  const BenchResult alone =
      benchmark(scene, accel, camera, narrow.grid(4), RenderSettings{}, 1, {});
  EXPECT_EQ(two.viewsLimit.primaryRays, uint64_t((37 + 19) * 21 * 4));
  EXPECT_EQ(two.viewsLimit.rays, one.limit.rays + alone.limit.rays);
}

// The quilt route's timing traces what each route traces: the direct render one camera ray per
// subpixel and sample (3 W H spp), the device quilt one per tile pixel and sample (views w h
// spp), each plus its shadow rays, as the renders themselves count them.
TEST(Bench, TheQuiltRouteTracesBothRoutesRays) {
  LenticularCalibration c = smallLenticularDesign(40).calibration;
  c.quilt = {4, 2, 96, 64};  // tiles of 24x32
  const std::unique_ptr<DisplayModel> display = makeLenticularDisplay(designLenticular(c));
  const Scene scene = defaultScene();
  const Accelerator accel(scene);
  RenderSettings settings;
  settings.samplesPerPixel = 4;
  const QuiltRouteTimes t = benchmarkQuiltRoute(scene, accel, *display, settings, 1);
  EXPECT_EQ(t.views, 8);
  EXPECT_EQ(t.tileWidth, 24);
  EXPECT_EQ(t.tileHeight, 32);
  const DisplayLayers direct = renderDisplay(scene, accel, *display, settings);
  EXPECT_EQ(direct.stats.cameraRays, uint64_t(3 * 180 * 40 * 4));
  EXPECT_EQ(t.directRays, direct.stats.totalRays());
  RenderStats quiltStats;
  QuiltLayout layout;
  layout.columns = 4, layout.rows = 2;
  renderQuilt(scene, accel, *display, settings, layout, 24, 32, &quiltStats);
  EXPECT_EQ(quiltStats.cameraRays, uint64_t(8 * 24 * 32 * 4));
  EXPECT_EQ(t.quiltRays, quiltStats.totalRays());
  EXPECT_GT(t.direct, 0.0);
  EXPECT_GT(t.quilt, 0.0);
  EXPECT_GT(t.interlace, 0.0);
  EXPECT_DOUBLE_EQ(t.directOverQuilt(), t.direct / t.quilt);
  EXPECT_DOUBLE_EQ(t.directOverRoute(), t.direct / (t.quilt + t.interlace));
  // A barrier has no quilt route of a device.
  const std::unique_ptr<DisplayModel> barrier = makeBarrierDisplay(designDisplay(DisplaySpec{}));
  EXPECT_THROW(benchmarkQuiltRoute(scene, accel, *barrier, settings, 1), std::invalid_argument);
  EXPECT_EQ(quiltRouteBytes(*barrier), 0.0);
}

}  // namespace
}  // namespace parallax
