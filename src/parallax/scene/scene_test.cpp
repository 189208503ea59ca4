#include "parallax/scene/scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace parallax {
namespace {

TEST(Scene, BoxIsClosedAndFacesOutward) {
  Scene scene;
  addBox(scene, "b", {-1, -2, -3}, {1, 2, 3}, 0);
  const TriangleMesh& m = scene.meshes.at(0);
  ASSERT_EQ(m.triangleCount(), 12u);
  // Divergence theorem: the signed volume of a closed outward mesh is its volume (2*4*6).
  double volume = 0;
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    const Vec3f a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                c = m.positions[m.indices[t + 2]];
    volume += dot(a, cross(b, c)) / 6.0;
    // Every face's normal points away from the centre.
    const Vec3f n = cross(b - a, c - a);
    EXPECT_GT(dot(n, (a + b + c) / 3.0f), 0.0f);
  }
  EXPECT_NEAR(volume, 48.0, 1e-4);
  const Bounds3f bounds = scene.bounds();
  EXPECT_EQ(bounds.lo, Vec3f(-1, -2, -3));
  EXPECT_EQ(bounds.hi, Vec3f(1, 2, 3));
}

TEST(Scene, QuadFrontFaceIsCrossOfEdges) {
  Scene scene;
  addQuad(scene, "q", {0, 0, 0}, {2, 0, 0}, {0, 3, 0}, 0);
  const TriangleMesh& m = scene.meshes.at(0);
  ASSERT_EQ(m.triangleCount(), 2u);
  double area = 0;
  for (size_t t = 0; t < 6; t += 3) {
    const Vec3f n = cross(m.positions[m.indices[t + 1]] - m.positions[m.indices[t]],
                          m.positions[m.indices[t + 2]] - m.positions[m.indices[t]]);
    EXPECT_GT(n.z, 0.0f);
    area += 0.5 * length(n);
  }
  EXPECT_NEAR(area, 6.0, 1e-6);
}

TEST(Scene, BoundsIncludeSpheres) {
  Scene scene;
  scene.spheres.push_back({"s", 0, {1, 2, 3}, 0.5f});
  EXPECT_EQ(scene.bounds().lo, Vec3f(0.5f, 1.5f, 2.5f));
  EXPECT_EQ(scene.triangleCount(), 0u);
}

TEST(Scene, DefaultSceneIsThePapers) {
  const Scene scene = defaultScene();
  ASSERT_TRUE(scene.camera.has_value());
  // A checkerboard floor, a box above it, and an area light that casts soft shadows.
  const auto floor = std::find_if(scene.meshes.begin(), scene.meshes.end(),
                                  [](const TriangleMesh& m) { return m.name == "floor"; });
  const auto box = std::find_if(scene.meshes.begin(), scene.meshes.end(),
                                [](const TriangleMesh& m) { return m.name == "box"; });
  ASSERT_NE(floor, scene.meshes.end());
  ASSERT_NE(box, scene.meshes.end());
  EXPECT_EQ(scene.textures[size_t(scene.materials[floor->material].diffuseTexture)].kind,
            Texture::Kind::Checker);
  float floorTop = -1e9f, boxBottom = 1e9f;
  for (const Vec3f& p : floor->positions) floorTop = std::max(floorTop, p.y);
  for (const Vec3f& p : box->positions) boxBottom = std::min(boxBottom, p.y);
  EXPECT_GT(boxBottom - floorTop, 0.3f) << "the box must levitate";
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].kind, Light::Kind::Quad);
  EXPECT_GT(scene.lights[0].corner.y, 2.0f);
}

TEST(Scene, FrameSceneSeesTheWholeScene) {
  Scene scene;
  addBox(scene, "b", {-1, -1, -1}, {3, 1, 1}, 0);
  const CameraSpec c = frameScene(scene, 40.0f);
  EXPECT_EQ(c.lookAt, Vec3f(1, 0, 0));
  // The bounding sphere (radius sqrt(6)) fits the vertical field of view.
  const float distance = length(c.eye - c.lookAt);
  EXPECT_GT(std::asin(std::sqrt(6.0f) / distance), 0.0f);
  EXPECT_LE(std::asin(std::sqrt(6.0f) / distance), 20.0f * kPi / 180.0f);
  EXPECT_GT(c.eye.z, 0.0f);  // on the viewer's side of the display
}

}  // namespace
}  // namespace parallax
