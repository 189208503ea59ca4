#include "parallax/core/transform.h"

#include <gtest/gtest.h>

#include "parallax/core/random.h"

namespace parallax {
namespace {

void expectNear(const Vec3f& a, const Vec3f& b, float tolerance = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(Transform, RotationFollowsTheRightHandRule) {
  // A quarter turn about +z takes +x to +y; about +x takes +y to +z.
  expectNear(Transform::rotate(90, {0, 0, 1}).vector({1, 0, 0}), {0, 1, 0});
  expectNear(Transform::rotate(90, {1, 0, 0}).vector({0, 1, 0}), {0, 0, 1});
  expectNear(Transform::rotate(120, {1, 1, 1}).vector({1, 0, 0}), {0, 1, 0});
}

TEST(Transform, ComposesRightToLeft) {
  // worldFromObject = translate * scale: scale first, then move.
  const Transform t = Transform::translate({1, 2, 3}) * Transform::scale({2, 2, 2});
  expectNear(t.point({1, 1, 1}), {3, 4, 5});
  expectNear(t.vector({1, 1, 1}), {2, 2, 2});
}

TEST(Transform, InverseUndoesRandomTransforms) {
  Rng rng(1);
  for (int i = 0; i < 100; ++i) {
    const Vec3f axis{rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() + 0.1f};
    const Transform t = Transform::translate({rng.uniform(), rng.uniform(), rng.uniform()}) *
                        Transform::rotate(360 * rng.uniform(), axis) *
                        Transform::scale({0.5f + rng.uniform(), 0.5f + rng.uniform(), 1.5f});
    const Vec3f p{rng.uniform() * 10, rng.uniform() * 10, rng.uniform() * 10};
    expectNear(t.inverse().point(t.point(p)), p, 1e-4f);
    Mat4 inv;
    ASSERT_TRUE(invert(t.matrix(), inv));
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(inv.m[r][c], t.inverseMatrix().m[r][c], 1e-4f);
  }
}

TEST(Transform, NormalsStayPerpendicularUnderNonUniformScale) {
  const Transform t = Transform::scale({4, 1, 1}) * Transform::rotate(30, {0, 0, 1});
  const Vec3f tangent{1, -1, 0}, normal{1, 1, 0};  // perpendicular before
  EXPECT_NEAR(dot(t.vector(tangent), t.normal(normal)), 0.0f, 1e-5f);
  EXPECT_FALSE(t.swapsHandedness());
  EXPECT_TRUE(Transform::scale({-1, 1, 1}).swapsHandedness());
}

TEST(Transform, SingularMatricesAreRejected) {
  Mat4 m = Mat4::identity();
  m.m[2][2] = 0;
  EXPECT_THROW(Transform{m}, std::invalid_argument);
  EXPECT_THROW(Transform::scale({1, 0, 1}), std::invalid_argument);
}

TEST(Transform, LookAtPutsTheTargetOnTheNegativeZAxis) {
  const Transform cameraFromWorld = Transform::lookAt({1, 2, 3}, {1, 2, -7}, {0, 1, 0});
  expectNear(cameraFromWorld.point({1, 2, -7}), {0, 0, -10});
  expectNear(cameraFromWorld.point({1, 3, 3}), {0, 1, 0});
}

}  // namespace
}  // namespace parallax
