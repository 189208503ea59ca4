// The splat walk (Accelerator::nextSplats) against brute force: every Gaussian's response along
// the ray, those reaching kMinSplatAlpha kept and sorted by (t, index). The walk, a buffer at a
// time, must give that list, whatever the buffer's size.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/core/random.h"
#include "parallax/scene/gaussians.h"
#include "parallax/scene/scene.h"

namespace parallax {
namespace {

// `count` Gaussians of random position, size (over two decades), orientation and opacity,
// some of them too faint ever to be seen.
GaussianCloud randomCloud(size_t count, uint64_t seed) {
  Rng rng(seed);
  GaussianCloud cloud;
  for (size_t g = 0; g < count; ++g) {
    cloud.centres.push_back({4 * rng.uniform() - 2, 4 * rng.uniform() - 2, 4 * rng.uniform() - 2});
    cloud.scales.push_back({0.02f * std::pow(10.0f, 1.5f * rng.uniform()),
                            0.02f * std::pow(10.0f, 1.5f * rng.uniform()),
                            0.02f * std::pow(10.0f, 1.5f * rng.uniform())});
    cloud.rotations.push_back(
        {rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f});
    cloud.opacities.push_back(g % 17 == 0 ? 0.5f * kMinSplatAlpha : rng.uniform());
    cloud.sh.push_back({0.1f, 0.2f, 0.3f});
  }
  return cloud;
}

// Two sets, the second moved by a transform that shears and scales unevenly.
Scene splatScene() {
  Scene scene;
  scene.splats.push_back({"a", randomCloud(300, 1), Transform()});
  const Transform skewed = Transform::translate({0.5f, -0.25f, 0.3f}) *
                           Transform::rotate(30.0f, normalize(Vec3f(1, 2, 3))) *
                           Transform::scale({1.5f, 0.5f, 1.0f}) *
                           Transform::rotate(-50.0f, normalize(Vec3f(-2, 1, 0.5f)));
  scene.splats.push_back({"b", randomCloud(200, 2), skewed});
  return scene;
}

std::vector<SplatHit> bruteForce(const Scene& scene, const Ray& ray) {
  std::vector<SplatHit> hits;
  uint32_t index = 0;
  for (const SplatSet& set : scene.splats)
    for (size_t g = 0; g < set.cloud.size(); ++g, ++index) {
      const RayResponse response = gaussianRayResponse(
          gaussianFrame(set.cloud, g, set.worldFromFile), ray.origin, ray.direction);
      const float alpha = response.alpha(set.cloud.opacities[g]);
      if (response.t >= ray.tMin && response.t < ray.tMax && alpha >= kMinSplatAlpha)
        hits.push_back({response.t, index, alpha});
    }
  std::sort(hits.begin(), hits.end(), [](const SplatHit& a, const SplatHit& b) {
    return a.t < b.t || (a.t == b.t && a.gaussian < b.gaussian);
  });
  return hits;
}

std::vector<SplatHit> walk(const Accelerator& accelerator, const Ray& ray, int capacity) {
  std::vector<SplatHit> all;
  std::vector<SplatHit> part(static_cast<size_t>(capacity));
  SplatCursor cursor;
  for (;;) {
    const int count = accelerator.nextSplats(ray, cursor, part.data(), capacity);
    all.insert(all.end(), part.begin(), part.begin() + count);
    if (count < capacity) return all;
    cursor = {part[size_t(count - 1)].t, part[size_t(count - 1)].gaussian, true};
  }
}

TEST(SplatTrace, TheWalkFindsWhatBruteForceFindsInTheSameOrder) {
  const Scene scene = splatScene();
  const Accelerator accelerator(scene);
  EXPECT_EQ(accelerator.splatCount(), 500u);
  Rng rng(7);
  size_t seen = 0;
  for (int r = 0; r < 200; ++r) {
    Ray ray;
    ray.origin = {6 * rng.uniform() - 3, 6 * rng.uniform() - 3, 5};
    ray.direction = Vec3f{rng.uniform() - 0.5f, rng.uniform() - 0.5f, -1} * (0.5f + rng.uniform());
    ray.tMin = r % 3 == 0 ? 1.0f : 0.0f;  // some rays start inside the cloud
    ray.tMax = r % 5 == 0 ? 4.0f : std::numeric_limits<float>::infinity();  // an opaque hit
    const std::vector<SplatHit> expected = bruteForce(scene, ray);
    seen += expected.size();
    for (int capacity : {1, 4, 16, 64}) {
      const std::vector<SplatHit> found = walk(accelerator, ray, capacity);
      ASSERT_EQ(found.size(), expected.size()) << "ray " << r << ", buffer " << capacity;
      for (size_t i = 0; i < found.size(); ++i) {
        EXPECT_EQ(found[i].gaussian, expected[i].gaussian) << "ray " << r << " hit " << i;
        // The walk's responses are computed for a packet's lanes together, where the compiler
        // may fuse multiplies and adds: the same to float rounding.
        EXPECT_NEAR(found[i].t, expected[i].t, 1e-5f * std::abs(expected[i].t));
        EXPECT_NEAR(found[i].alpha, expected[i].alpha, 1e-5f);
      }
    }
  }
  EXPECT_GT(seen, 1000u);  // the rays do cross the cloud, many Gaussians each
}

TEST(SplatTrace, FaintGaussiansAreNeverReturnedAndASceneWithoutSplatsHasNone) {
  Scene scene;
  GaussianCloud faint;
  faint.centres = {{0, 0, 0}};
  faint.scales = {{1, 1, 1}};
  faint.rotations = {Quatf{}};
  faint.opacities = {0.9f * kMinSplatAlpha};
  faint.sh = {{0, 0, 0}};
  scene.splats.push_back({"faint", faint, Transform()});
  const Ray ray{{0, 0, 5}, {0, 0, -1}};
  SplatHit hit;
  EXPECT_EQ(Accelerator(scene).nextSplats(ray, {}, &hit, 1), 0);
  EXPECT_EQ(Accelerator(Scene{}).nextSplats(ray, {}, &hit, 1), 0);
  EXPECT_EQ(Accelerator(Scene{}).splatCount(), 0u);
}

TEST(SplatTrace, AGaussianOnTheRayPeaksWhereItsCentreIsNearest) {
  Scene scene;
  GaussianCloud one;
  one.centres = {{0.1f, 0, -2}};
  one.scales = {{0.2f, 0.2f, 0.2f}};
  one.rotations = {Quatf{}};
  one.opacities = {0.8f};
  one.sh = {{0, 0, 0}};
  scene.splats.push_back({"one", one, Transform()});
  const Accelerator accelerator(scene);
  SplatHit hit;
  ASSERT_EQ(accelerator.nextSplats(Ray{{0, 0, 3}, {0, 0, -2}}, {}, &hit, 1), 1);
  EXPECT_FLOAT_EQ(hit.t, 2.5f);  // z = 3 - 2 t = -2
  // 0.1 off the axis is half a deviation: alpha = 0.8 exp(-0.125).
  EXPECT_NEAR(hit.alpha, 0.8f * std::exp(-0.125f), 1e-6f);
  // Behind the origin, or past an opaque hit, it is not met.
  EXPECT_EQ(accelerator.nextSplats(Ray{{0, 0, -3}, {0, 0, -1}}, {}, &hit, 1), 0);
  EXPECT_EQ(accelerator.nextSplats(Ray{{0, 0, 3}, {0, 0, -2}, 0.0f, 2.0f}, {}, &hit, 1), 0);
}

}  // namespace
}  // namespace parallax
