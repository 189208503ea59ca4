// The test content's makers (jobs/splat_making.h) against what their definitions say: surface
// Gaussians lie on the surface, flat across it, coloured by the lit albedo there; the capture-like
// cloud has the count, degree and distributions it promises; both are the same for the same seed.
#include "parallax/jobs/splat_making.h"

#include <gtest/gtest.h>

#include <cmath>

#include "parallax/core/error.h"
#include "parallax/image/image.h"

namespace parallax::jobs {
namespace {

constexpr float kC0 = 0.28209479177387814f;

// One 2 x 1 quad in the plane z = 0.5, facing +z, of albedo (0.6, 0.3, 0.1).
Scene quadScene() {
  Scene scene;
  Material material;
  material.diffuse = {0.6f, 0.3f, 0.1f};
  scene.materials.push_back(material);
  addQuad(scene, "quad", {-1, -0.5f, 0.5f}, {2, 0, 0}, {0, 1, 0}, 0);
  return scene;
}

// The file frame back to the world: 180 degrees about X, its own inverse.
Vec3f toWorld(const Vec3f& v) {
  return {v.x, -v.y, -v.z};
}

TEST(SplatMaking, SurfaceGaussiansLieOnTheSurfaceFlatAcrossItInItsLitColour) {
  SurfaceSplatOptions options;
  options.count = 500;
  const GaussianCloud cloud = surfaceGaussians(quadScene(), options);
  ASSERT_EQ(cloud.size(), 500u);
  EXPECT_EQ(cloud.shDegree, 0);
  // The spacing sqrt(area / count): each is 0.9 of it across and 5 % of that through.
  const float spacing = std::sqrt(2.0f / 500.0f);
  // The bare-mesh scene's light on a surface facing +z: key 2.5 / pi cos, ambient 0.15.
  const Vec3f toLight = normalize(Vec3f(-0.4f, 1.0f, 0.6f));
  const float lit = 2.5f / kPi * toLight.z + 0.15f;
  for (size_t g = 0; g < cloud.size(); ++g) {
    const Vec3f centre = toWorld(cloud.centres[g]);
    EXPECT_NEAR(centre.z, 0.5f, 1e-6f);
    EXPECT_LE(std::abs(centre.x), 1.0f + 1e-6f);
    EXPECT_LE(std::abs(centre.y), 0.5f + 1e-6f);
    EXPECT_NEAR(cloud.scales[g].x, 0.9f * spacing, 1e-6f);
    EXPECT_NEAR(cloud.scales[g].z, 0.05f * 0.9f * spacing, 1e-7f);
    // The thin axis (the rotation's third column) along the quad's normal.
    Vec3f rows[3];
    rotationRows(cloud.rotations[g], rows);
    const Vec3f thin = toWorld({rows[0].z, rows[1].z, rows[2].z});
    EXPECT_NEAR(std::abs(thin.z), 1.0f, 1e-5f);
    const Vec3f dc = cloud.sh[g];
    const Vec3f albedo{0.6f, 0.3f, 0.1f};
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(dc[c], (linearToSrgb(albedo[c] * lit) - 0.5f) / kC0, 2e-3f) << c;
  }
}

TEST(SplatMaking, TheCaptureLikeCloudIsDistributedAsPromisedAndTheSameForTheSameSeed) {
  const GaussianCloud cloud = captureLikeGaussians({20000, 7});
  ASSERT_EQ(cloud.size(), 20000u);
  EXPECT_EQ(cloud.shDegree, 3);
  EXPECT_EQ(cloud.sh.size(), 20000u * 16);
  size_t nearlyOpaque = 0, faint = 0;
  for (float o : cloud.opacities) {
    ASSERT_GT(o, 0.0f);
    ASSERT_LE(o, 1.0f);
    nearlyOpaque += o > 0.9f;
    faint += o < 0.3f;
  }
  // 35 % of all but the floaters (95 %) above 0.9: 33 %; 40 % of them drawn below 0.3, and every
  // floater: 43 %.
  EXPECT_NEAR(double(nearlyOpaque) / 20000.0, 0.3325, 0.015);
  EXPECT_NEAR(double(faint) / 20000.0, 0.43, 0.015);
  // The higher bands carry view dependence, weaker with the band.
  double band1 = 0, band3 = 0;
  for (size_t g = 0; g < cloud.size(); ++g) {
    band1 += std::abs(cloud.sh[g * 16 + 1].x);
    band3 += std::abs(cloud.sh[g * 16 + 12].x);
  }
  EXPECT_GT(band1, 2.0 * band3);
  EXPECT_GT(band3, 0.0);
  const GaussianCloud again = captureLikeGaussians({20000, 7});
  for (size_t g = 0; g < cloud.size(); g += 997) {
    EXPECT_EQ(again.centres[g], cloud.centres[g]);
    EXPECT_EQ(again.sh[g * 16 + 5], cloud.sh[g * 16 + 5]);
  }
  EXPECT_NE(captureLikeGaussians({20000, 8}).centres[0], cloud.centres[0]);
}

TEST(SplatMaking, AnEmptySceneOrAZeroCountIsRefused) {
  EXPECT_THROW(surfaceGaussians(Scene{}, SurfaceSplatOptions{}), RequestError);
  SurfaceSplatOptions none;
  none.count = 0;
  EXPECT_THROW(surfaceGaussians(quadScene(), none), RequestError);
  EXPECT_THROW(captureLikeGaussians({0, 1}), RequestError);
}

}  // namespace
}  // namespace parallax::jobs
