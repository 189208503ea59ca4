// The renderer against closed forms: Lambertian radiance under directional, point and area
// light, shadows from a sphere, mirrors, ambient, and thread-count independence.
#include <gtest/gtest.h>

#include <stdexcept>

#include <cmath>

#include "parallax/image/metrics.h"
#include "parallax/render/render.h"

namespace parallax {
namespace {

Scene planeScene(float albedo) {
  Scene scene;
  Material m;
  m.diffuse = Vec3f(albedo);
  scene.materials.push_back(m);
  // A 200 x 200 square in the plane y = 0, facing +y.
  addQuad(scene, "plane", {-100, 0, 100}, {200, 0, 0}, {0, 0, -200}, 0);
  return scene;
}

// A camera high above the origin looking straight down.
PinholeCamera downCamera(int size, float height = 10.0f, float fov = 60.0f) {
  return PinholeCamera({0, height, 0}, {0, 0, 0}, {0, 0, -1}, fov, size, size);
}

Vec3f hitOnGround(const Ray& ray) {
  return ray.at(-ray.origin.y / ray.direction.y);
}

TEST(Render, DirectionalLightGivesAlbedoTimesIrradianceOverPi) {
  Scene scene = planeScene(0.5f);
  Light sun;
  sun.kind = Light::Kind::Directional;
  const float tilt = 30.0f * kPi / 180.0f;
  sun.direction = {std::sin(tilt), -std::cos(tilt), 0.0f};
  sun.intensity = Vec3f(2.0f);
  scene.lights.push_back(sun);
  const Accelerator accel(scene);
  const Image img = render(scene, accel, downCamera(16), {});
  const float expected = 0.5f * 2.0f * std::cos(tilt) / kPi;
  for (const Vec3f& p : img.pixels()) EXPECT_NEAR(p.y, expected, 1e-5f);
}

TEST(Render, PointLightFallsOffAsCosineOverDistanceSquared) {
  Scene scene = planeScene(0.8f);
  Light bulb;
  bulb.kind = Light::Kind::Point;
  bulb.position = {1.0f, 2.0f, 0.5f};
  bulb.intensity = Vec3f(10.0f);
  scene.lights.push_back(bulb);
  const Accelerator accel(scene);
  const PinholeCamera camera = downCamera(24);
  const Image img = render(scene, accel, camera, {});
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 24; ++x) {
      const Vec3f p = hitOnGround(camera.generateRay({x + 0.5f, y + 0.5f}));
      const Vec3f toLight = bulb.position - p;
      const float r = length(toLight);
      const float expected = 0.8f / kPi * 10.0f * (toLight.y / r) / (r * r);
      EXPECT_NEAR(img.at(x, y).x, expected, 1e-4f * expected) << x << "," << y;
    }
}

TEST(Render, SphereCastsTheShadowThatGeometryPredicts) {
  Scene scene = planeScene(1.0f);
  Light bulb;
  bulb.kind = Light::Kind::Point;
  bulb.position = {0.0f, 6.0f, 0.0f};
  bulb.intensity = Vec3f(36.0f);
  scene.lights.push_back(bulb);
  const Vec3f centre{0.5f, 3.0f, 0.0f};
  const float radius = 1.0f;
  scene.spheres.push_back({"ball", 0, centre, radius});
  const Accelerator accel(scene);
  // The camera sits beside the light so that it sees the ground around the sphere.
  const PinholeCamera camera({3.0f, 9.0f, 0.0f}, {0, 0, 0}, {0, 0, -1}, 70.0f, 48, 48);
  const Image img = render(scene, accel, camera, {});
  int shadowed = 0, checked = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 48; ++x) {
      const Ray ray = camera.generateRay({x + 0.5f, y + 0.5f});
      // Skip pixels that see the sphere itself.
      const Vec3f oc = ray.origin - centre;
      const Vec3f d = normalize(ray.direction);
      const float b = dot(oc, d), c = dot(oc, oc) - radius * radius;
      if (b * b - c > -1e-3f) continue;
      // The ground point is lit iff the segment to the light misses the sphere (by margin).
      const Vec3f p = hitOnGround(ray);
      const Vec3f toLight = bulb.position - p;
      const Vec3f l = normalize(toLight);
      const Vec3f pc = p - centre;
      const float bl = dot(pc, l), cl = dot(pc, pc) - radius * radius;
      const float disc = bl * bl - cl;
      if (std::abs(disc) < 1e-2f) continue;  // too close to the shadow's edge to call
      const bool inShadow = disc > 0 && -bl - std::sqrt(disc) > 0;
      ++checked;
      if (inShadow) {
        ++shadowed;
        EXPECT_EQ(img.at(x, y).x, 0.0f) << x << "," << y;
      } else {
        EXPECT_GT(img.at(x, y).x, 0.01f) << x << "," << y;
      }
    }
  EXPECT_GT(shadowed, 20);
  EXPECT_GT(checked, 1000);
}

// Irradiance below the corner of a w x h rectangle of radiance L at height d (the
// differential-area-to-parallel-rectangle form factor times pi L).
double cornerIrradiance(double w, double h, double d, double radiance) {
  const double a = w / d, b = h / d;
  const double sa = std::sqrt(1 + a * a), sb = std::sqrt(1 + b * b);
  const double formFactor =
      (a / sa * std::atan(b / sa) + b / sb * std::atan(a / sb)) / (2.0 * 3.14159265358979);
  return 3.14159265358979 * radiance * formFactor;
}

TEST(Render, QuadLightMatchesTheRectangleFormFactor) {
  Scene scene = planeScene(1.0f);
  Light panel;
  panel.kind = Light::Kind::Quad;
  panel.corner = {-1.0f, 2.0f, -1.0f};
  panel.edgeU = {2.0f, 0.0f, 0.0f};
  panel.edgeV = {0.0f, 0.0f, 2.0f};  // cross(u, v) = -y: faces the ground
  panel.intensity = Vec3f(3.0f);
  panel.samples = 16;
  scene.lights.push_back(panel);
  const Accelerator accel(scene);
  // A narrow camera from below the light's plane sees only the patch under the centre.
  const PinholeCamera camera({0, 1.5f, 0}, {0, 0, 0}, {0, 0, -1}, 0.5f, 4, 4);
  RenderSettings settings;
  settings.samplesPerPixel = 256;
  const Image img = render(scene, accel, camera, settings);
  // Four 1 x 1 quadrants meet above the centre at height 2.
  const double expected = 4.0 * cornerIrradiance(1.0, 1.0, 2.0, 3.0) / 3.14159265358979;
  double mean = 0;
  for (const Vec3f& p : img.pixels()) mean += p.x / 16.0;
  EXPECT_NEAR(mean, expected, 0.01 * expected);
}

TEST(Render, MirrorReflectsALitCeiling) {
  // A grey ceiling under uniform ambient light, seen in a floor mirror of reflectance 0.7
  // whose remaining 0.3 is diffuse white.
  Scene scene;
  Material mirror, ceiling;
  mirror.diffuse = Vec3f(1.0f);
  mirror.mirror = Vec3f(0.7f);
  ceiling.diffuse = Vec3f(0.6f);
  scene.materials = {mirror, ceiling};
  addQuad(scene, "mirror", {-100, 0, 100}, {200, 0, 0}, {0, 0, -200}, 0);
  addQuad(scene, "ceiling", {-100, 20, -100}, {200, 0, 0}, {0, 0, 200}, 1);
  scene.ambient = Vec3f(1.0f);
  const Accelerator accel(scene);
  const Image img = render(scene, accel, downCamera(8, 10.0f, 20.0f), {});
  const float expected = 0.3f * 1.0f + 0.7f * 0.6f;
  for (const Vec3f& p : img.pixels()) EXPECT_NEAR(p.x, expected, 1e-5f);
  // Without bounces only the diffuse part is left.
  scene.maxDepth = 0;
  const Image direct = render(scene, accel, downCamera(8, 10.0f, 20.0f), {});
  for (const Vec3f& p : direct.pixels()) EXPECT_NEAR(p.x, 0.3f, 1e-5f);
}

TEST(Render, AmbientAndBackground) {
  Scene scene = planeScene(0.25f);
  scene.ambient = Vec3f(0.8f);
  scene.background = {0.1f, 0.2f, 0.3f};
  const Accelerator accel(scene);
  const Image ground = render(scene, accel, downCamera(4), {});
  for (const Vec3f& p : ground.pixels()) EXPECT_NEAR(p.x, 0.25f * 0.8f, 1e-6f);
  const PinholeCamera up({0, 1, 0}, {0, 5, 0}, {0, 0, -1}, 40.0f, 4, 4);
  const Image sky = render(scene, accel, up, {});
  for (const Vec3f& p : sky.pixels()) EXPECT_EQ(p, scene.background);
}

TEST(Render, SameImageForAnyThreadCount) {
  const Scene scene = defaultScene();
  const Accelerator accel(scene);
  const CameraSpec& c = *scene.camera;
  const PinholeCamera camera(c.eye, c.lookAt, c.up, c.fovDegrees, 61, 37);
  RenderSettings one, many;
  one.samplesPerPixel = many.samplesPerPixel = 4;
  one.threads = 1;
  many.threads = 2;
  RenderStats stats;
  const Image a = render(scene, accel, camera, one, &stats);
  const Image b = render(scene, accel, camera, many);
  EXPECT_EQ(a.pixels(), b.pixels());
  EXPECT_EQ(stats.cameraRays, 61u * 37u * 4u);
  EXPECT_GT(stats.shadowRays, stats.cameraRays / 4);
  // A different seed moves the jitter, so some pixel must change.
  many.seed = 7;
  EXPECT_NE(a.pixels(), render(scene, accel, camera, many).pixels());
}

// render() is its tiles: rendered one at a time in reverse order by TileRenderer, they make
// the same picture and the same counts.
TEST(Render, TilesRenderedOneAtATimeMakeTheSameImage) {
  const Scene scene = defaultScene();
  const Accelerator accel(scene);
  const CameraSpec& c = *scene.camera;
  const PinholeCamera camera(c.eye, c.lookAt, c.up, c.fovDegrees, 75, 41);
  RenderSettings settings;
  settings.samplesPerPixel = 4;
  RenderStats whole;
  const Image expected = render(scene, accel, camera, settings, &whole);
  const TileRenderer renderer(scene, accel, camera, settings);
  ASSERT_GT(renderer.tileCount(), 1);
  Image image(camera.width(), camera.height());
  RenderStats tiles;
  for (int tile = renderer.tileCount() - 1; tile >= 0; --tile)
    renderer.renderTile(tile, image, tiles);
  EXPECT_EQ(image.pixels(), expected.pixels());
  EXPECT_EQ(tiles.totalRays(), whole.totalRays());
  EXPECT_EQ(tiles.cameraMisses, whole.cameraMisses);
}

// A band of film rows at a time (TileRenderer::renderTile into an image of those rows only):
// each band's pixels are the whole film's rows, adaptive sampling included (its neighbours are
// the packet's own); a tile outside the band's image is refused.
TEST(Render, TilesRenderedIntoABandOfRowsAreTheFilmsRows) {
  const Scene scene = defaultScene();
  const Accelerator accel(scene);
  const CameraSpec& c = *scene.camera;
  const PinholeCamera camera(c.eye, c.lookAt, c.up, c.fovDegrees, 75, 41);
  for (const bool adaptive : {false, true}) {
    RenderSettings settings;
    settings.samplesPerPixel = 4;
    settings.adaptive = adaptive;
    const Image expected = render(scene, accel, camera, settings);
    const TileRenderer renderer(scene, accel, camera, settings);
    for (int firstRow = 0; firstRow < 41; firstRow += 2 * TileGrid::kRows) {
      const int rows = std::min(2 * TileGrid::kRows, 41 - firstRow);
      Image band(75, rows);
      RenderStats stats;
      for (int tile = 0; tile < renderer.tileCount(); ++tile) {
        const int tileRow = renderer.tileBand(tile) * TileGrid::kRows;
        if (tileRow >= firstRow && tileRow < firstRow + rows)
          renderer.renderTile(tile, band, firstRow, stats);
        else
          EXPECT_THROW(renderer.renderTile(tile, band, firstRow, stats), std::logic_error);
      }
      for (int y = 0; y < rows; ++y)
        for (int x = 0; x < 75; ++x) ASSERT_EQ(band.at(x, y), expected.at(x, firstRow + y));
    }
  }
}

// Adaptive sampling: a flat picture stops every pixel after its first stratified group (n of
// n^2 samples: an exact count), the image still equals the flat value, and a scene with edges
// gives the same image for any thread count, spends more on its edges than on flat regions,
// and stays close to the fixed-rate render.
TEST(Render, AdaptiveSamplingStopsFlatPixelsAfterOneGroup) {
  Scene scene = planeScene(0.25f);
  scene.ambient = Vec3f(0.8f);
  const Accelerator accel(scene);
  RenderSettings settings;
  settings.samplesPerPixel = 16;
  settings.adaptive = true;
  RenderStats stats;
  const Image flat = render(scene, accel, downCamera(8), settings, &stats);
  EXPECT_EQ(stats.cameraRays, 8u * 8u * 4u);
  for (const Vec3f& p : flat.pixels()) EXPECT_NEAR(p.x, 0.25f * 0.8f, 1e-6f);
}

// A plane under downCamera(kStripeSize) whose texture gives every pixel one period of its own:
// the pixels of the first `flatColumns` image columns a flat grey of sRGB value 1/2, the others
// a black-and-white stripe, black on the pixel's left half and white on its right (ramps between
// texels 1/1024 of a pixel wide). A margin of two pixels on each side.
constexpr int kStripeSize = 8;
Scene stripeScene(int flatColumns) {
  const float pixel = 2 * 10 * std::tan(30 * kPi / 180) / kStripeSize;  // on the plane
  const int periods = kStripeSize + 4;
  Scene scene;
  Image texels(1024 * periods, 1);
  for (int p = 0; p < periods; ++p)
    for (int x = 0; x < 1024; ++x)
      texels.at(1024 * p + x, 0) = Vec3f(p - 2 < flatColumns ? srgbToLinear(0.5f)
                                         : x < 512           ? 0.0f
                                                             : 1.0f);
  scene.images.push_back(texels);
  Texture texture;
  texture.kind = Texture::Kind::Image;
  texture.image = 0;
  scene.textures.push_back(texture);
  Material m;
  m.diffuse = Vec3f(1.0f);
  m.diffuseTexture = 0;
  scene.materials.push_back(m);
  scene.ambient = Vec3f(1.0f);
  const float left = -(kStripeSize / 2 + 2) * pixel, across = float(periods) * pixel;
  TriangleMesh plane;
  plane.positions = {
      {left, 0, 50}, {left + across, 0, 50}, {left + across, 0, -50}, {left, 0, -50}};
  plane.normals.assign(4, Vec3f{0, 1, 0});
  plane.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  plane.indices = {0, 1, 2, 0, 2, 3};
  scene.meshes.push_back(plane);
  return scene;
}

RenderStats adaptiveStripeRender(const Scene& scene, Image* image = nullptr) {
  const Accelerator accel(scene);
  RenderSettings settings;
  settings.samplesPerPixel = 16;
  settings.adaptive = true;
  RenderStats stats;
  const Image img = render(scene, accel, downCamera(kStripeSize), settings, &stats);
  if (image) *image = img;
  return stats;
}

// The stopping test after two groups uses the spread of the group means, not of the samples:
// a stratified group varies far less than independent samples. Every pixel sees a stripe: its
// samples disagree completely (so no pixel stops after the first group), but each Latin group
// has two samples in each half, so the group means agree and the pixels stop after two groups
// (a sample that lands on a ramp can make one go on).
TEST(Render, AdaptiveSamplingStopsStratifiedStripesAfterTwoGroups) {
  Image img;
  const RenderStats stats = adaptiveStripeRender(stripeScene(0), &img);
  const uint64_t pixels = kStripeSize * kStripeSize;
  EXPECT_GE(stats.cameraRays, 8 * pixels);  // none stopped after the first group
  EXPECT_LE(stats.cameraRays, 9 * pixels);  // nearly all after the second
  for (const Vec3f& p : img.pixels()) EXPECT_NEAR(p.x, 0.5f, 0.01f);
}

// A pixel that has stopped keeps its mean for its neighbours' test: six flat columns stop after
// the first group (4 rays), and the two stripe columns beside them, whose group means equal the
// flat grey, after the second (8 rays), the column next to the flat ones included. (Counted
// over the groups a pixel had not taken, its mean would fall to half and hold that column to
// all 16 rays.)
TEST(Render, AdaptiveSamplingStoppedPixelsKeepTheirMeanForTheirNeighbours) {
  const RenderStats stats = adaptiveStripeRender(stripeScene(6));
  const uint64_t rows = kStripeSize, expected = rows * (6 * 4 + 2 * 8);
  EXPECT_GE(stats.cameraRays, expected);
  EXPECT_LE(stats.cameraRays, expected + 8);
}

TEST(Render, AdaptiveSamplingIsDeterministicAndSpendsRaysOnEdges) {
  const Scene scene = defaultScene();
  const Accelerator accel(scene);
  const CameraSpec& c = *scene.camera;
  const PinholeCamera camera(c.eye, c.lookAt, c.up, c.fovDegrees, 96, 54);
  RenderSettings fixed, adaptive, reference;
  fixed.samplesPerPixel = adaptive.samplesPerPixel = 16;
  reference.samplesPerPixel = 256;
  adaptive.adaptive = true;
  adaptive.threads = 1;
  RenderStats fixedStats, adaptiveStats;
  const Image truth = render(scene, accel, camera, reference);
  const Image a = render(scene, accel, camera, fixed, &fixedStats);
  const Image b = render(scene, accel, camera, adaptive, &adaptiveStats);
  adaptive.threads = 2;
  EXPECT_EQ(b.pixels(), render(scene, accel, camera, adaptive).pixels());
  EXPECT_LT(adaptiveStats.cameraRays, fixedStats.cameraRays * 3 / 4);
  EXPECT_GT(adaptiveStats.cameraRays, fixedStats.cameraRays / 4);  // edges kept their rays
  EXPECT_GT(psnr(b, truth), psnr(a, truth) - 0.1);
}

}  // namespace
}  // namespace parallax
