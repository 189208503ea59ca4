// Splats through the renderer (docs/splats.md, render/splat_blend.h): what one Gaussian's pixel
// holds, splats over and behind a surface, and the picture against the two truths of
// splat_truth_test_support.h: brute force along the same rays, and the 3DGS rasteriser's
// algorithm.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "parallax/core/random.h"
#include "parallax/image/metrics.h"
#include "parallax/render/render.h"
#include "parallax/render/splat_truth_test_support.h"

namespace parallax {
namespace {

constexpr float kC0 = 0.28209479177387814f;

GaussianCloud oneGaussian(const Vec3f& centre, float sigma, float opacity, const Vec3f& colour) {
  GaussianCloud cloud;
  cloud.centres = {centre};
  cloud.scales = {Vec3f(sigma)};
  cloud.rotations = {Quatf{}};
  cloud.opacities = {opacity};
  cloud.sh = {(colour - Vec3f(0.5f)) * (1.0f / kC0)};
  return cloud;
}

// The centre pixel of a small pinhole render looking down -z at the origin.
Vec3f centrePixel(const Scene& scene, int threads = 0) {
  const Accelerator accelerator(scene);
  const PinholeCamera camera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 20.0f, 9, 9);
  RenderSettings settings;
  settings.threads = threads;
  return render(scene, accelerator, camera, settings).at(4, 4);
}

Vec3f display(const Vec3f& linear) {
  return {linearToSrgb(linear.x), linearToSrgb(linear.y), linearToSrgb(linear.z)};
}

void expectNear(const Vec3f& a, const Vec3f& b, float tolerance) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], tolerance) << "channel " << c;
}

TEST(SplatRender, AnOpaqueGaussiansPixelHasItsFilesColourAndAHalfTransparentOneHalf) {
  const Vec3f colour{0.8f, 0.3f, 0.1f};
  Scene scene;
  scene.background = Vec3f(srgbToLinear(0.2f));  // 0.2 as a display value
  scene.splats.push_back({"one", oneGaussian({0, 0, 0}, 0.5f, 1.0f, colour), Transform()});
  // Opacity 1 is capped at alpha 0.99: the colour and 1 % of the background.
  expectNear(display(centrePixel(scene)), colour * 0.99f + Vec3f(0.2f * 0.01f), 1e-5f);
  scene.splats[0].cloud.opacities[0] = 0.5f;
  expectNear(display(centrePixel(scene)), colour * 0.5f + Vec3f(0.2f * 0.5f), 1e-5f);
}

TEST(SplatRender, ASplatBeforeASurfaceBlendsOverItAndOneBehindItIsHidden) {
  Scene scene;
  Material grey;
  grey.diffuse = Vec3f(0.5f);
  scene.materials.push_back(grey);
  scene.ambient = Vec3f(1.0f);  // the quad shows its albedo: 0.5 linear
  addQuad(scene, "wall", {-2, -2, 0}, {4, 0, 0}, {0, 4, 0}, 0);
  const Vec3f colour{0.1f, 0.9f, 0.4f};
  scene.splats.push_back({"front", oneGaussian({0, 0, 1}, 0.3f, 0.5f, colour), Transform()});
  const float wall = linearToSrgb(0.5f);
  expectNear(display(centrePixel(scene)), colour * 0.5f + Vec3f(wall * 0.5f), 1e-5f);
  scene.splats[0].cloud.centres[0] = {0, 0, -1};  // behind the wall
  expectNear(display(centrePixel(scene)), Vec3f(wall), 1e-5f);
}

TEST(SplatRender, TheColourFollowsEachRaysOwnDirectionThroughAPlacedSet) {
  // A degree-1 Gaussian whose red grows with the direction's +z in its file frame (basis
  // Y_1,0 = C1 z). Placed turned 180 degrees about Y, the rays along world -z run along its
  // file's +z: red rises by C1 * 0.2 in display value.
  GaussianCloud cloud = oneGaussian({0, 0, 0}, 0.5f, 1.0f, {0.5f, 0.5f, 0.5f});
  cloud.shDegree = 1;
  cloud.sh = {Vec3f(0.0f), Vec3f(0.0f), {0.2f, 0, 0}, Vec3f(0.0f)};
  Scene scene;
  scene.splats.push_back({"turned", cloud, Transform::rotate(180.0f, {0, 1, 0})});
  const float c1 = 0.4886025119029199f;
  // The centre ray's direction is exactly -z in the world: +z in the file.
  const Vec3f seen = display(centrePixel(scene));
  // The coefficient as kept: 0.2 in a half float.
  EXPECT_NEAR(seen.x, 0.99f * (0.5f + c1 * fromHalf(toHalf(0.2f))), 1e-5f);
  EXPECT_NEAR(seen.y, 0.99f * 0.5f, 1e-5f);
}

// A random cloud in front of the camera: `count` Gaussians of degree 3, sizes and opacities
// spread as captures' are.
GaussianCloud randomCloud(size_t count, uint64_t seed, float sizeScale) {
  Rng rng(seed);
  GaussianCloud cloud;
  cloud.shDegree = 3;
  for (size_t g = 0; g < count; ++g) {
    cloud.centres.push_back({2 * rng.uniform() - 1, 2 * rng.uniform() - 1, 2 * rng.uniform() - 1});
    const float s = sizeScale * std::exp(1.0f * (rng.uniform() - 0.5f));
    cloud.scales.push_back({s, s * (0.3f + rng.uniform()), s * (0.2f + rng.uniform())});
    cloud.rotations.push_back(
        {rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f});
    cloud.opacities.push_back(0.05f + 0.94f * rng.uniform());
    for (int k = 0; k < 16; ++k)
      cloud.sh.push_back(
          k == 0 ? Vec3f(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f) * 3.0f
                 : Vec3f(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f) *
                       (0.3f / float(k)));
  }
  return cloud;
}

TEST(SplatRender, ThePictureIsBruteForcesAlongTheSameRays) {
  Scene scene;
  scene.background = Vec3f(0.05f);
  scene.splats.push_back({"cloud", randomCloud(1500, 3, 0.06f), Transform()});
  const Accelerator accelerator(scene);
  const PinholeCamera camera({0.3f, 0.2f, 4}, {0, 0, 0}, {0, 1, 0}, 35.0f, 48, 40);
  RenderSettings settings;
  const Image traced = render(scene, accelerator, camera, settings);
  Image brute(camera.width(), camera.height());
  const Vec3f background = display(scene.background);
  float worst = 0;
  for (int y = 0; y < camera.height(); ++y)
    for (int x = 0; x < camera.width(); ++x) {
      const Ray ray = camera.generateRay({float(x) + 0.5f, float(y) + 0.5f});
      const Vec3f v = splat_truth::bruteForceSplatPixel(scene.splats[0].cloud, ray.origin,
                                                        ray.direction, background);
      const Vec3f seen = display(traced.at(x, y));
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(seen[c] - v[c]));
      brute.at(x, y) = {srgbToLinear(v.x), srgbToLinear(v.y), srgbToLinear(v.z)};
    }
  const double db = psnr(traced, brute);
  std::printf("splats: traced against brute force: PSNR %.1f dB, largest difference %.2g\n", db,
              double(worst));
  // Float against double arithmetic, nothing else: far below one 8-bit step.
  EXPECT_LT(worst, 1e-3f);
  EXPECT_GT(db, 60.0);
}

TEST(SplatRender, ThePictureIsTheRasterisersWhereItsApproximationsHold) {
  // Gaussians several pixels wide, where the 0.3 px^2 low-pass, the affine projection and the
  // per-Gaussian sort and colour barely matter, and then smaller ones, where they show.
  struct Case {
    const char* name;
    float size;
    double floorDb, pointFloorDb;
  };
  // Measured: large 37.2 and 38.2 dB, small 24.6 and 58.1 dB (docs/splats.md, "Truth"): small
  // Gaussians differ by the filter alone, large ones by the rasteriser's approximations.
  for (const Case& c : {Case{"large", 0.08f, 34.0, 34.0}, Case{"small", 0.02f, 22.0, 50.0}}) {
    Scene scene;
    scene.splats.push_back({"cloud", randomCloud(800, 5, c.size), Transform()});
    const Accelerator accelerator(scene);
    const splat_truth::View view{{0.2f, 0.3f, 4}, {0, 0, 0}, {0, 1, 0}, 35.0f, 96, 80};
    const PinholeCamera camera(view.eye, view.lookAt, view.up, view.fovDegrees, view.width,
                               view.height);
    RenderSettings settings;
    settings.samplesPerPixel = 16;  // the pixel's area, as the rasteriser's low-pass stands for
    const Image traced = render(scene, accelerator, camera, settings);
    const Image raster = splat_truth::rasteriseSplats(scene.splats[0].cloud, view, Vec3f(0.0f));
    const double db = psnr(traced, raster);
    // The same without the low-pass, against one ray through each pixel's centre: what is left
    // is the projection's affine approximation, the per-Gaussian depth order and the colour
    // taken once along the line to the centre.
    settings.samplesPerPixel = 1;
    const Image point = render(scene, accelerator, camera, settings);
    const double pointDb =
        psnr(point, splat_truth::rasteriseSplats(scene.splats[0].cloud, view, Vec3f(0.0f), 0.0));
    std::printf(
        "splats: traced against the 3DGS rasteriser, %s Gaussians: PSNR %.1f dB "
        "(16 rays a pixel; the rasteriser's 0.3 px^2 low-pass), %.1f dB (one ray at each "
        "pixel's centre; no low-pass)\n",
        c.name, db, pointDb);
    EXPECT_GT(db, c.floorDb) << c.name;
    EXPECT_GT(pointDb, c.pointFloorDb) << c.name;
  }
}

TEST(SplatRender, TheSamePictureWhateverTheThreadCount) {
  Scene scene;
  scene.splats.push_back({"cloud", randomCloud(600, 9, 0.05f), Transform()});
  const Accelerator accelerator(scene);
  const PinholeCamera camera({0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 35.0f, 64, 48);
  RenderSettings one, two;
  one.threads = 1, two.threads = 2;
  one.samplesPerPixel = two.samplesPerPixel = 4;
  RenderStats stats;
  const Image a = render(scene, accelerator, camera, one, &stats);
  const Image b = render(scene, accelerator, camera, two);
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) ASSERT_EQ(a.at(x, y), b.at(x, y));
  EXPECT_GT(stats.splatsBlended, 0u);
  EXPECT_GE(stats.splatsEvaluated, stats.splatsBlended);
}

}  // namespace
}  // namespace parallax
