// RGB-D scenes against the analytic formulas of docs/rgbd.md: the three depth conventions, the
// pinhole unprojection (centre on the axis, film corners on the field of view's edges), the
// mesh's faces and UVs, and the layered mode's cut and background sheet.
#include "parallax/scene/rgbd.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace parallax {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

DepthMap constantDepth(int width, int height, float value) {
  DepthMap map;
  map.width = width;
  map.height = height;
  map.values.assign(size_t(width) * size_t(height), value);
  return map;
}

RgbdOptions withConvention(DepthConvention convention, float nearZ, float farZ) {
  RgbdOptions o;
  o.convention = convention;
  o.nearDistance = nearZ;
  o.farDistance = farZ;
  return o;
}

TEST(Rgbd, DisparityIsLinearInInverseDistance) {
  const RgbdOptions o = withConvention(DepthConvention::Disparity, 1.5f, 6.0f);
  EXPECT_FLOAT_EQ(depthFromValue(1.0f, o), 1.5f);  // bright = near
  EXPECT_FLOAT_EQ(depthFromValue(0.0f, o), 6.0f);
  // Half-way in 1/z: the harmonic mean 2 n f / (n + f).
  EXPECT_NEAR(depthFromValue(0.5f, o), 2.0 * 1.5 * 6.0 / 7.5, 1e-5);
  for (float v : {0.1f, 0.3f, 0.77f}) {
    const double invZ = 1.0 / depthFromValue(v, o);
    EXPECT_NEAR(invZ, (1.0 - v) / 6.0 + v / 1.5, 1e-6) << v;
  }
}

TEST(Rgbd, DepthAndInverseAreLinearInDistance) {
  const RgbdOptions depth = withConvention(DepthConvention::Depth, 2.0f, 5.0f);
  const RgbdOptions inverse = withConvention(DepthConvention::Inverse, 2.0f, 5.0f);
  for (float v : {0.0f, 0.25f, 0.6f, 1.0f}) {
    EXPECT_NEAR(depthFromValue(v, depth), 2.0 + 3.0 * v, 1e-6) << v;    // dark = near
    EXPECT_NEAR(depthFromValue(v, inverse), 5.0 - 3.0 * v, 1e-6) << v;  // bright = near
  }
}

TEST(Rgbd, UnprojectionPutsTheCentreOnTheAxisAndTheCornersOnTheFovEdges) {
  const int w = 9, h = 5;
  const float fov = 50.0f, z = 2.5f;
  const Vec3f centre = unprojectFilm(4.5f, 2.5f, z, w, h, fov);
  EXPECT_NEAR(centre.x, 0.0, 1e-6);
  EXPECT_NEAR(centre.y, 0.0, 1e-6);
  EXPECT_FLOAT_EQ(centre.z, -z);
  // The film's corners: horizontally at half the field of view, vertically at half the
  // vertical field of view tan(v/2) = tan(h/2) * height / width (square pixels).
  const double halfH = 0.5 * fov * kDegree;
  const double tanV = std::tan(halfH) * h / w;
  const Vec3f topLeft = unprojectFilm(0, 0, z, w, h, fov);
  const Vec3f bottomRight = unprojectFilm(float(w), float(h), z, w, h, fov);
  EXPECT_NEAR(std::atan2(-topLeft.x, z), halfH, 1e-6);
  EXPECT_NEAR(std::atan2(bottomRight.x, z), halfH, 1e-6);
  EXPECT_NEAR(topLeft.y, tanV * z, 1e-6);
  EXPECT_NEAR(bottomRight.y, -tanV * z, 1e-6);
  EXPECT_NEAR(verticalFovDegrees(fov, w, h), 2.0 * std::atan(tanV) / kDegree, 1e-4);
}

TEST(Rgbd, EveryConventionPutsTheCentrePixelOnTheAxisAtItsDistance) {
  const int w = 7, h = 5;  // odd: pixel (3, 2)'s centre is the film's centre
  struct Case {
    DepthConvention convention;
    float value;
    double z;  // the analytic distance for near 1, far 4
  };
  const Case cases[] = {
      {DepthConvention::Disparity, 0.25f, 1.0 / (0.25 / 1.0 + 0.75 / 4.0)},
      {DepthConvention::Depth, 0.25f, 1.0 + 0.25 * 3.0},
      {DepthConvention::Inverse, 0.25f, 4.0 - 0.25 * 3.0},
  };
  for (const Case& c : cases) {
    RgbdOptions o = withConvention(c.convention, 1.0f, 4.0f);
    o.fovDegrees = 60.0f;
    const Scene scene = makeRgbdScene(Image(w, h, Vec3f(0.5f)), constantDepth(w, h, c.value), o);
    ASSERT_EQ(scene.meshes.size(), 1u);
    const TriangleMesh& mesh = scene.meshes[0];
    ASSERT_EQ(mesh.positions.size(), size_t(w * h));
    const Vec3f centre = mesh.positions[2 * w + 3];
    EXPECT_NEAR(centre.x, 0.0, 1e-6) << depthConventionName(c.convention);
    EXPECT_NEAR(centre.y, 0.0, 1e-6);
    EXPECT_NEAR(-centre.z, c.z, 1e-5);
    // Pixel (0, 0)'s vertex sits at its centre, half a pixel in from the corner: its direction
    // is tan = (2 * 0.5 / w - 1) tan(30 deg) horizontally.
    const Vec3f first = mesh.positions[0];
    EXPECT_NEAR(first.x / -first.z, (1.0 / w - 1.0) * std::tan(30.0 * kDegree), 1e-6);
    EXPECT_NEAR(first.y / -first.z, (1.0 - 1.0 / h) * std::tan(30.0 * kDegree) * h / w, 1e-6);
    EXPECT_NEAR(-first.z, c.z, 1e-5);
  }
}

TEST(Rgbd, StretchedSheetFacesTheCameraAndItsUvsHitTheTexelCentres) {
  const int w = 6, h = 4;
  Image colour(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) colour.at(x, y) = {0.1f * float(x), 0.2f * float(y), 0.3f};
  DepthMap depth = constantDepth(w, h, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) depth.values[size_t(y * w + x)] = float(x + y) / float(w + h);
  const Scene scene = makeRgbdScene(colour, depth, {});
  const TriangleMesh& mesh = scene.meshes[0];
  EXPECT_EQ(mesh.triangleCount(), size_t(2 * (w - 1) * (h - 1)));
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const Vec3f a = mesh.positions[mesh.indices[3 * t]],
                b = mesh.positions[mesh.indices[3 * t + 1]],
                c = mesh.positions[mesh.indices[3 * t + 2]];
    // Front face cross(b - a, c - a) toward the camera at the origin: dot with (origin - a) > 0.
    EXPECT_GT(dot(cross(b - a, c - a), Vec3f(0.0f) - a), 0.0f) << "triangle " << t;
  }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Vec2f uv = mesh.uvs[size_t(y * w + x)];
      const Vec3f seen = colour.sampleBilinear(uv.x, uv.y), want = colour.at(x, y);
      EXPECT_NEAR(seen.x, want.x, 1e-5) << x << "," << y;
      EXPECT_NEAR(seen.y, want.y, 1e-5) << x << "," << y;
    }
  // Lit by ambient 1 alone, black behind, white albedo times the photo.
  EXPECT_TRUE(scene.lights.empty());
  EXPECT_EQ(scene.ambient, Vec3f(1.0f));
  EXPECT_EQ(scene.background, Vec3f(0.0f));
  const Material& m = scene.materials[mesh.material];
  EXPECT_EQ(m.diffuse, Vec3f(1.0f));
  ASSERT_GE(m.diffuseTexture, 0);
  EXPECT_EQ(scene.textures[size_t(m.diffuseTexture)].kind, Texture::Kind::Image);
  // The display faces the viewer and fits the mesh's bounds.
  EXPECT_EQ(scene.display.normal, Vec3f(0, 0, 1));
  EXPECT_EQ(scene.display.up, Vec3f(0, 1, 0));
  ASSERT_TRUE(scene.display.fit.has_value());
  EXPECT_EQ(scene.display.fit->lo, scene.bounds().lo);
  EXPECT_EQ(scene.display.fit->hi, scene.bounds().hi);
}

TEST(Rgbd, LayeredCutsTheDepthStepAndFillsItFromTheFarSide) {
  // Left half near (value 1 = 1 unit), right half far (value 0 = 3 units); a relative jump of 2.
  const int w = 12, h = 5;
  Image colour(w, h);
  DepthMap depth = constantDepth(w, h, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool near = x < w / 2;
      depth.values[size_t(y * w + x)] = near ? 1.0f : 0.0f;
      colour.at(x, y) = near ? Vec3f(1, 0, 0) : Vec3f(0, 0, 1);
    }
  RgbdOptions o;
  o.edges = RgbdEdges::Layered;
  o.backgroundRadius = 2;
  const Scene scene = makeRgbdScene(colour, depth, o);
  ASSERT_EQ(scene.meshes.size(), 2u);
  // One column of quads spans the step: h - 1 of them are cut.
  EXPECT_EQ(scene.meshes[0].triangleCount(), size_t(2 * (w - 1) * (h - 1) - 2 * (h - 1)));
  const TriangleMesh& back = scene.meshes[1];
  EXPECT_EQ(back.triangleCount(), size_t(2 * (w - 1) * (h - 1)));
  const Image& backColour = scene.images[size_t(scene.textures[1].image)];
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y * w + x);
      // Within two pixels of the far side, the background is the far side's, 1 % behind it.
      const bool reached = x >= w / 2 - 2;
      const float wantZ = (reached ? 3.0f : 1.0f) * 1.01f;
      EXPECT_NEAR(-back.positions[i].z, wantZ, 1e-5) << x << "," << y;
      EXPECT_EQ(backColour.at(x, y), reached ? Vec3f(0, 0, 1) : Vec3f(1, 0, 0)) << x << "," << y;
      // Always behind the main sheet, along the same ray.
      const Vec3f front = scene.meshes[0].positions[i];
      EXPECT_GT(-back.positions[i].z, -front.z);
      EXPECT_NEAR(back.positions[i].x / back.positions[i].z, front.x / front.z, 1e-6);
    }
}

TEST(Rgbd, LayeredBackgroundIsTheFarthestPixelNearbyAsBruteForceFindsIt) {
  // Few depth levels, so that many windows hold ties (the first pixel in scan order wins), and
  // a colour that names its pixel, so that the background's colour says which pixel it took.
  const int w = 23, h = 17, radius = 3;
  Image colour(w, h);
  DepthMap depth = constantDepth(w, h, 0.0f);
  uint32_t state = 12345;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      state = state * 1664525u + 1013904223u;
      depth.values[size_t(y * w + x)] = float((state >> 24) % 4) / 3.0f;
      colour.at(x, y) = {float(x), float(y), 0.0f};
    }
  RgbdOptions o;
  o.edges = RgbdEdges::Layered;
  o.backgroundRadius = radius;
  const Scene scene = makeRgbdScene(colour, depth, o);
  const Image& back = scene.images[size_t(scene.textures[1].image)];
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      // Farthest = smallest disparity value; scan order, strictly smaller replaces.
      int bx = -1, by = -1;
      for (int yy = std::max(0, y - radius); yy <= std::min(h - 1, y + radius); ++yy)
        for (int xx = std::max(0, x - radius); xx <= std::min(w - 1, x + radius); ++xx)
          if (bx < 0 || depth.at(xx, yy) < depth.at(bx, by)) bx = xx, by = yy;
      EXPECT_EQ(back.at(x, y), Vec3f(float(bx), float(by), 0.0f)) << x << "," << y;
      EXPECT_NEAR(-scene.meshes[1].positions[size_t(y * w + x)].z,
                  1.01 * depthFromValue(depth.at(bx, by), o), 1e-5);
    }
}

TEST(Rgbd, RefusesMismatchedSizesAndValuesOutsideTheUnitRange) {
  EXPECT_THROW(makeRgbdScene(Image(4, 4), constantDepth(4, 3, 0.5f), {}), std::invalid_argument);
  EXPECT_THROW(makeRgbdScene(Image(4, 4), constantDepth(4, 4, 1.5f), {}), std::invalid_argument);
  EXPECT_THROW(makeRgbdScene(Image(1, 4), constantDepth(1, 4, 0.5f), {}), std::invalid_argument);
  RgbdOptions backwards;
  backwards.nearDistance = 3.0f;
  backwards.farDistance = 1.0f;
  EXPECT_THROW(makeRgbdScene(Image(4, 4), constantDepth(4, 4, 0.5f), backwards),
               std::invalid_argument);
}

}  // namespace
}  // namespace parallax
