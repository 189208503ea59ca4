#include "parallax/scene/motion.h"

#include <gtest/gtest.h>

#include <cmath>

namespace parallax {
namespace {

void expectNear(const Vec3f& a, const Vec3f& b, float tolerance = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

// A unit cube [-1, 1]^3 centred on (2, 0, 0), and a lamp mesh that is a light.
Scene cubeAndLamp() {
  Scene scene;
  scene.materials.push_back({});
  addBox(scene, "cube", Vec3f(1, -1, -1), Vec3f(3, 1, 1), 0);
  addQuad(scene, "lamp", Vec3f(-1, 5, -1), Vec3f(2, 0, 0), Vec3f(0, 0, 2), 0);
  Light lamp;
  lamp.kind = Light::Kind::Mesh;
  lamp.mesh = 1;
  scene.lights.push_back(lamp);
  scene.spheres.push_back({"ball", 0, Vec3f(2, 0, 3), 0.5f});
  return scene;
}

TEST(Turntable, TurnsContentAboutTheAxisThroughThePivotAndLeavesLightsAlone) {
  const Scene rest = cubeAndLamp();
  SceneMotion motion;
  motion.turntable = Turntable{Vec3f(2, 0, 0), Vec3f(0, 1, 0), 90.0};  // a quarter turn a second
  Scene posed = rest;
  poseScene(rest, motion, 1.0, posed);
  // About +y by 90 degrees (right-handed): (x, z) -> (z, -x) relative to the pivot.
  for (size_t i = 0; i < rest.meshes[0].positions.size(); ++i) {
    const Vec3f p = rest.meshes[0].positions[i] - Vec3f(2, 0, 0);
    expectNear(posed.meshes[0].positions[i], Vec3f(2 + p.z, p.y, -p.x));
  }
  for (size_t i = 0; i < rest.meshes[0].normals.size(); ++i) {
    const Vec3f n = rest.meshes[0].normals[i];
    expectNear(posed.meshes[0].normals[i], Vec3f(n.z, n.y, -n.x));
  }
  expectNear(posed.spheres[0].center, Vec3f(2 + 3, 0, 0));
  EXPECT_EQ(posed.meshes[1].positions, rest.meshes[1].positions);  // the lamp stays
  // A whole turn comes back to the rest pose.
  poseScene(rest, motion, 4.0, posed);
  for (size_t i = 0; i < rest.meshes[0].positions.size(); ++i)
    expectNear(posed.meshes[0].positions[i], rest.meshes[0].positions[i], 1e-4f);
}

TEST(Turntable, ContentTurntableTurnsAboutTheDisplayUpThroughTheContentCentre) {
  Scene scene = cubeAndLamp();
  scene.display.up = Vec3f(0, 0, 2);
  scene.display.content = Bounds3f{Vec3f(1, -1, -1), Vec3f(3, 1, 1)};
  const Turntable t = contentTurntable(scene, 30.0);
  expectNear(t.pivot, Vec3f(2, 0, 0));
  expectNear(t.axis, Vec3f(0, 0, 1));
  EXPECT_EQ(t.degreesPerSecond, 30.0);
}

TEST(Turntable, MovedBoundsAreTheEnvelopeOfTheTurnedContent) {
  const Scene rest = cubeAndLamp();
  SceneMotion motion;
  motion.turntable = Turntable{Vec3f(2, 0, 0), Vec3f(0, 1, 0), 45.0};
  const Bounds3f cube{Vec3f(1, -1, -1), Vec3f(3, 1, 1)};
  // At 45 degrees the cube's corners reach sqrt(2) from the axis along x and z.
  const Bounds3f b = movedBounds(rest, motion, cube, {0.0, 1.0});
  const float r = float(std::sqrt(2.0));
  expectNear(b.lo, Vec3f(2 - r, -1, -r));
  expectNear(b.hi, Vec3f(2 + r, 1, r));
  // Only what lies in the box counts: the ball (outside the cube) does not widen it.
  const Bounds3f still = movedBounds(rest, motion, cube, {0.0});
  expectNear(still.lo, cube.lo);
  expectNear(still.hi, cube.hi);
  // Without a turntable nothing moves.
  const Bounds3f none = movedBounds(rest, SceneMotion{}, cube, {0.0, 1.0});
  expectNear(none.lo, cube.lo);
  expectNear(none.hi, cube.hi);
}

TEST(Keys, CameraKeysInterpolateLinearlyAndHoldOutside) {
  CameraKey a, b;
  a.seconds = 1, b.seconds = 3;
  a.camera.eye = Vec3f(0, 0, 5), b.camera.eye = Vec3f(4, 0, 5);
  a.camera.lookAt = Vec3f(0.0f), b.camera.lookAt = Vec3f(0, 2, 0);
  a.camera.fovDegrees = 30, b.camera.fovDegrees = 50;
  const std::vector<CameraKey> keys{a, b};
  const CameraSpec mid = cameraAt(keys, 2.5);
  expectNear(mid.eye, Vec3f(3, 0, 5));
  expectNear(mid.lookAt, Vec3f(0, 1.5f, 0));
  EXPECT_NEAR(mid.fovDegrees, 45.0f, 1e-5f);
  expectNear(cameraAt(keys, 0).eye, a.camera.eye);
  expectNear(cameraAt(keys, 9).eye, b.camera.eye);
}

TEST(Keys, DisplayKeysTurnTheNormalAndKeepUpPerpendicular) {
  DisplayKey a, b;
  a.seconds = 0, b.seconds = 2;
  a.normal = Vec3f(0, 0, 1), b.normal = Vec3f(1, 0, 0);
  a.up = b.up = Vec3f(0, 1, 0.3f);  // not perpendicular: made so
  b.center = Vec3f(2, 0, 0);
  const DisplayKey d = displayAt({a, b}, 1.0);
  const float h = float(std::sqrt(0.5));
  expectNear(d.normal, Vec3f(h, 0, h));
  expectNear(d.center, Vec3f(1, 0, 0));
  EXPECT_NEAR(dot(d.up, d.normal), 0.0f, 1e-6f);
  EXPECT_NEAR(length(d.up), 1.0f, 1e-6f);
  EXPECT_GT(d.up.y, 0.9f);
  // poseScene writes them into the placement.
  Scene rest = cubeAndLamp();
  SceneMotion motion;
  motion.displayKeys = {a, b};
  Scene posed = rest;
  poseScene(rest, motion, 1.0, posed);
  expectNear(posed.display.normal, d.normal);
  expectNear(posed.display.center, d.center);
  EXPECT_EQ(posed.meshes[0].positions, rest.meshes[0].positions);
  EXPECT_NEAR(motion.keyedSeconds(), 2.0, 0);
}

}  // namespace
}  // namespace parallax
