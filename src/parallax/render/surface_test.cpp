// The packet shader against the scalar one, lane by lane (two code paths, one answer), and
// textures against their definitions.
#include "parallax/render/surface.h"

#include <gtest/gtest.h>

#include "parallax/core/random.h"

namespace parallax {
namespace {

Scene mixedScene() {
  Scene scene = defaultScene();  // checker floor, flat box, emissive lamp
  Material mirror;
  mirror.diffuse = {0.9f, 0.5f, 0.2f};
  mirror.mirror = Vec3f(0.4f);
  Image tex(2, 2);
  tex.at(0, 0) = {1, 0, 0}, tex.at(1, 0) = {0, 1, 0}, tex.at(0, 1) = {0, 0, 1};
  scene.images.push_back(tex);
  Texture image;
  image.kind = Texture::Kind::Image;
  image.image = 0;
  scene.textures.push_back(image);
  Material textured;
  textured.diffuseTexture = int(scene.textures.size()) - 1;
  scene.materials.push_back(mirror);
  scene.materials.push_back(textured);
  scene.spheres.push_back(
      {"ball", uint32_t(scene.materials.size() - 2), {-1.2f, 0.2f, 0.3f}, 0.4f});
  addQuad(scene, "poster", {0.8f, -0.5f, -1.0f}, {1, 0, 0}, {0, 1, 0},
          uint32_t(scene.materials.size() - 1));
  // A smooth-shaded triangle whose vertex normals differ.
  TriangleMesh smooth;
  smooth.name = "smooth";
  smooth.positions = {{-2, -1, -2}, {-1, -1, -2}, {-1.5f, 0, -2}};
  smooth.normals = {normalize(Vec3f{-1, 0, 1}), normalize(Vec3f{1, 0, 1}), {0, 1, 0}};
  smooth.indices = {0, 1, 2};
  scene.meshes.push_back(smooth);
  // A flat triangle with red, green and blue corners.
  TriangleMesh painted;
  painted.name = "painted";
  painted.positions = {{1.5f, 0.5f, -2}, {2.5f, 0.5f, -2}, {1.5f, 1.5f, -2}};
  painted.colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  painted.indices = {0, 1, 2};
  scene.meshes.push_back(painted);
  return scene;
}

void expectNear(float a, float b, const char* what, int lane) {
  EXPECT_NEAR(a, b, 1e-5f * (1.0f + std::abs(b))) << what << " lane " << lane;
}

TEST(SurfaceShader, PacketMatchesScalarLaneByLane) {
  const Scene scene = mixedScene();
  const Accelerator accel(scene);
  const SurfaceShader shader(scene, accel);
  Rng rng(5);
  int hits = 0;
  for (int packetIndex = 0; packetIndex < 200; ++packetIndex) {
    RayPacket16 rays;
    for (int lane = 0; lane < 16; ++lane) {
      const Vec3f origin{rng.uniform() * 4 - 2, rng.uniform() * 2, 4.0f};
      const Vec3f target{rng.uniform() * 6 - 3, rng.uniform() * 3 - 1.5f, -rng.uniform() * 3};
      rays.set(lane, {origin, target - origin});
      if (lane % 7 == 3) rays.deactivate(lane);
    }
    HitPacket16 h;
    accel.intersect16(rays, h);
    SurfacePacket16 sp;
    Color16 emitted;
    emitted.fill(0.0f);
    shader.evaluate16(rays, h, sp, emitted);
    for (int lane = 0; lane < 16; ++lane) {
      const bool hit = rays.active[lane] && h.hit(lane).valid();
      ASSERT_EQ(bool(sp.hit[lane]), hit);
      if (!hit) continue;
      ++hits;
      const SurfacePoint s = shader.evaluate(rays.ray(lane), h.hit(lane));
      expectNear(sp.px[lane], s.position.x, "px", lane);
      expectNear(sp.pz[lane], s.position.z, "pz", lane);
      expectNear(sp.gx[lane], s.geometricNormal.x, "gx", lane);
      expectNear(sp.gy[lane], s.geometricNormal.y, "gy", lane);
      expectNear(sp.nx[lane], s.shadingNormal.x, "nx", lane);
      expectNear(sp.nz[lane], s.shadingNormal.z, "nz", lane);
      expectNear(sp.diffuse.r[lane], s.diffuse.x, "diffuse r", lane);
      expectNear(sp.diffuse.b[lane], s.diffuse.z, "diffuse b", lane);
      expectNear(sp.mirror.g[lane], s.mirror.y, "mirror", lane);
      expectNear(emitted.r[lane], s.emission.x, "emission", lane);
    }
  }
  EXPECT_GT(hits, 1000);
}

// A triangle with red, green and blue corners, hit where its barycentrics are known from the
// geometry alone: the point a + 0.2 (b - a) + 0.3 (c - a) has weights (0.5, 0.2, 0.3), so
// the albedo is the material's times (0.5, 0.2, 0.3), in the scalar and the packet shader.
TEST(SurfaceShader, VertexColoursInterpolateWithBarycentrics) {
  Scene scene;
  Material grey;
  grey.diffuse = {0.8f, 0.6f, 0.4f};
  scene.materials.push_back(grey);
  TriangleMesh mesh;
  const Vec3f a{-1, -1, 0}, b{2, -1, 0}, c{-1, 3, 0};
  mesh.positions = {a, b, c};
  mesh.colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.indices = {0, 1, 2};
  scene.meshes.push_back(mesh);
  const Accelerator accel(scene);
  const SurfaceShader shader(scene, accel);

  const float wb = 0.2f, wc = 0.3f;
  const Vec3f target = a + (b - a) * wb + (c - a) * wc;
  const Vec3f origin = target + Vec3f(0.3f, -0.2f, 2.0f);
  const Ray ray{origin, normalize(target - origin)};
  const Hit hit = accel.intersect(ray);
  ASSERT_TRUE(hit.valid());
  const Vec3f expected = grey.diffuse * Vec3f(1 - wb - wc, wb, wc);
  const SurfacePoint s = shader.evaluate(ray, hit);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(s.diffuse[k], expected[k], 1e-5f) << k;

  RayPacket16 rays;
  for (int lane = 0; lane < 16; ++lane) rays.set(lane, ray);
  HitPacket16 hits;
  accel.intersect16(rays, hits);
  SurfacePacket16 sp;
  Color16 emitted;
  emitted.fill(0.0f);
  shader.evaluate16(rays, hits, sp, emitted);
  for (int lane = 0; lane < 16; ++lane) {
    EXPECT_NEAR(sp.diffuse.r[lane], expected.x, 1e-5f);
    EXPECT_NEAR(sp.diffuse.g[lane], expected.y, 1e-5f);
    EXPECT_NEAR(sp.diffuse.b[lane], expected.z, 1e-5f);
  }
}

TEST(Texture, CheckerAlternatesBySquare) {
  Scene scene;
  Texture t;
  t.kind = Texture::Kind::Checker;
  t.color = Vec3f(1.0f);
  t.color2 = Vec3f(0.0f);
  t.checkerSize = 0.5f;
  EXPECT_EQ(evaluateTexture(scene, t, {0.25f, 0.1f, 0.25f}, {}).x, 1.0f);
  EXPECT_EQ(evaluateTexture(scene, t, {0.75f, 0.1f, 0.25f}, {}).x, 0.0f);
  EXPECT_EQ(evaluateTexture(scene, t, {0.75f, 0.1f, 0.75f}, {}).x, 1.0f);
  EXPECT_EQ(evaluateTexture(scene, t, {-0.25f, 0.1f, 0.25f}, {}).x, 0.0f);
}

}  // namespace
}  // namespace parallax
