#include <gtest/gtest.h>

#include <cmath>

#include "parallax/camera/camera.h"

namespace parallax {
namespace {

TEST(PinholeCamera, CentreRayLooksAtTarget) {
  const PinholeCamera camera({1, 2, 3}, {4, 6, 3}, {0, 0, 1}, 50.0f, 64, 48);
  const Ray ray = camera.generateRay({32.0f, 24.0f});
  const Vec3f d = normalize(ray.direction);
  EXPECT_NEAR(d.x, 0.6f, 1e-6f);
  EXPECT_NEAR(d.y, 0.8f, 1e-6f);
  EXPECT_NEAR(d.z, 0.0f, 1e-6f);
  EXPECT_EQ(ray.origin, Vec3f(1, 2, 3));
}

TEST(PinholeCamera, FilmEdgesSpanTheFieldOfView) {
  const float fov = 60.0f;
  const PinholeCamera camera({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, fov, 200, 100);
  // Top edge centre: the angle to the axis is fov / 2; the left edge: atan(aspect * tan).
  const Vec3f top = normalize(camera.generateRay({100.0f, 0.0f}).direction);
  EXPECT_NEAR(std::acos(-top.z) * 180.0f / kPi, fov / 2, 1e-4f);
  EXPECT_GT(top.y, 0.0f);
  const Vec3f left = normalize(camera.generateRay({0.0f, 50.0f}).direction);
  const float expected = std::atan(2.0f * std::tan(fov / 2 * kPi / 180.0f)) * 180.0f / kPi;
  EXPECT_NEAR(std::acos(-left.z) * 180.0f / kPi, expected, 1e-4f);
  EXPECT_LT(left.x, 0.0f);
}

TEST(PinholeCamera, ProjectsAKnownPointToItsPixel) {
  // A point 10 units ahead, offset by tan(10 deg) * 10 up, must land at
  // y = h/2 * (1 - tan(10)/tan(fov/2)).
  const int w = 101, h = 81;
  const float fov = 40.0f;
  const PinholeCamera camera({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, fov, w, h);
  const float t = std::tan(10.0f * kPi / 180.0f) / std::tan(20.0f * kPi / 180.0f);
  const float y = 0.5f * h * (1.0f - t);
  const Ray ray = camera.generateRay({0.5f * w, y});
  const Vec3f d = ray.direction / -ray.direction.z;
  EXPECT_NEAR(d.y, std::tan(10.0f * kPi / 180.0f), 1e-5f);
  EXPECT_NEAR(d.x, 0.0f, 1e-6f);
}

TEST(PinholeCamera, RejectsImpossibleSettings) {
  EXPECT_THROW(PinholeCamera({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 0.0f, 10, 10),
               std::invalid_argument);
  EXPECT_THROW(PinholeCamera({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 40.0f, 0, 10),
               std::invalid_argument);
}

}  // namespace
}  // namespace parallax

namespace parallax {
namespace {

TEST(PinholeCamera, GridDescribesTheSameRays) {
  const PinholeCamera camera({1, 2, 3}, {0, 0, -4}, {0, 1, 0}, 45.0f, 32, 24);
  const PinholeGrid grid = camera.grid(4);
  for (float y : {0.5f, 7.25f, 23.5f})
    for (float x : {0.5f, 13.75f, 31.5f}) {
      const Vec3f through = grid.pixel00 + grid.pixelDx * x + grid.pixelDy * y;
      const Vec3f expected = normalize(camera.generateRay({x, y}).direction);
      const Vec3f actual = normalize(through - grid.eye);
      EXPECT_NEAR(dot(expected, actual), 1.0f, 1e-6f);
    }
  EXPECT_EQ(grid.eye, Vec3f(1, 2, 3));
}

}  // namespace
}  // namespace parallax
