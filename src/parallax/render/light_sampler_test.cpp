// Light samples against closed forms, and the packet path against the scalar one.
#include "parallax/render/light_sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "parallax/core/random.h"

namespace parallax {
namespace {

TEST(LightSampler, PointLightIrradianceIsCosineOverDistanceSquared) {
  Scene scene;
  Light l;
  l.kind = Light::Kind::Point;
  l.position = {0, 2, 0};
  l.intensity = Vec3f(8.0f);
  scene.lights.push_back(l);
  const LightSampler sampler(scene);
  const LightSample s = sampler.sample(0, {1, 0, 0}, {0, 1, 0}, 0, 0, 0);
  ASSERT_TRUE(s.valid);
  const float r2 = 5.0f, cosine = 2.0f / std::sqrt(5.0f);
  EXPECT_NEAR(s.irradiance.x, 8.0f * cosine / r2, 1e-6f);
  EXPECT_FALSE(sampler.sample(0, {1, 0, 0}, {0, -1, 0}, 0, 0, 0).valid);  // light behind
}

TEST(LightSampler, MeshLightAveragesToTheQuadLight) {
  // An emissive mesh quad and a quad light of the same shape deliver the same mean
  // irradiance (both unbiased estimators of one integral).
  Scene quad, mesh;
  Material lamp;
  lamp.emission = Vec3f(5.0f);
  for (Scene* s : {&quad, &mesh}) s->materials.push_back(lamp);
  Light q;
  q.kind = Light::Kind::Quad;
  q.corner = {-1, 2, -1}, q.edgeU = {2, 0, 0}, q.edgeV = {0, 0, 2};
  q.intensity = lamp.emission;
  quad.lights.push_back(q);
  addQuad(mesh, "lamp", q.corner, q.edgeU, q.edgeV, 0);
  Light m;
  m.kind = Light::Kind::Mesh;
  m.mesh = 0;
  mesh.lights.push_back(m);
  const LightSampler a(quad), b(mesh);
  Rng rng(9);
  double sumA = 0, sumB = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const float u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
    sumA += a.sample(0, {0.3f, 0, 0.2f}, {0, 1, 0}, u1, u2, u3).irradiance.x;
    sumB += b.sample(0, {0.3f, 0, 0.2f}, {0, 1, 0}, u1, u2, u3).irradiance.x;
  }
  EXPECT_NEAR(sumA / n, sumB / n, 0.01 * sumA / n);
}

TEST(LightSampler, PacketMatchesScalar) {
  Scene scene;
  Light q;
  q.kind = Light::Kind::Quad;
  q.corner = {-1, 2, -1}, q.edgeU = {2, 0, 0}, q.edgeV = {0, 0, 2};
  q.intensity = Vec3f(3.0f);
  scene.lights.push_back(q);
  Light p;
  p.kind = Light::Kind::Point;
  p.position = {0.5f, 1, 0};
  p.intensity = Vec3f(2.0f);
  scene.lights.push_back(p);
  Light d;
  d.kind = Light::Kind::Directional;
  d.direction = normalize(Vec3f{0.3f, -1.0f, 0.2f});
  d.intensity = {1.0f, 2.0f, 3.0f};
  scene.lights.push_back(d);
  Light spot;  // a narrow cone: some lanes fall outside it, some in the falloff
  spot.kind = Light::Kind::Spot;
  spot.position = {0.2f, 2, -0.3f};
  spot.direction = normalize(Vec3f{0.2f, -1.0f, 0.1f});
  spot.innerCone = 0.2f, spot.outerCone = 0.6f;
  spot.intensity = {4.0f, 5.0f, 6.0f};
  scene.lights.push_back(spot);
  const LightSampler sampler(scene);
  Rng rng(3);
  SurfacePacket16 sp{};
  alignas(64) float u1[16], u2[16], u3[16];
  for (int i = 0; i < 16; ++i) {
    sp.px[i] = rng.uniform() * 4 - 2, sp.py[i] = 0, sp.pz[i] = rng.uniform() * 4 - 2;
    const Vec3f n = normalize(Vec3f{rng.uniform() - 0.5f, 1.0f, rng.uniform() - 0.5f});
    sp.nx[i] = n.x, sp.ny[i] = n.y, sp.nz[i] = n.z;
    sp.hit[i] = sp.shade[i] = i % 5 != 0;
    u1[i] = rng.uniform(), u2[i] = rng.uniform(), u3[i] = rng.uniform();
  }
  for (size_t light = 0; light < sampler.lightCount(); ++light) {
    LightPacket16 out;
    sampler.sample16(light, sp, u1, u2, u3, out);
    for (int i = 0; i < 16; ++i) {
      if (!sp.shade[i]) {
        EXPECT_FALSE(out.valid[i]);
        continue;
      }
      const LightSample s = sampler.sample(light, {sp.px[i], sp.py[i], sp.pz[i]},
                                           {sp.nx[i], sp.ny[i], sp.nz[i]}, u1[i], u2[i], u3[i]);
      ASSERT_EQ(bool(out.valid[i]), s.valid) << i;
      if (!s.valid) continue;
      EXPECT_NEAR(out.irradiance.r[i], s.irradiance.x, 1e-5f * (1 + s.irradiance.x));
      EXPECT_NEAR(out.irradiance.b[i], s.irradiance.z, 1e-5f * (1 + s.irradiance.z));
      EXPECT_NEAR(out.tx[i], s.toLight.x, 1e-5f);
      EXPECT_NEAR(out.tz[i], s.toLight.z, 1e-5f);
      EXPECT_EQ(out.tMax[i], s.tMax);
    }
  }
}

// The spot's irradiance against KHR_lights_punctual's falloff, written out here from the
// extension's README in double precision: E = I cos(theta_receiver) / r^2 times
// clamp(cd * scale + offset, 0, 1)^2, scale = 1 / max(0.001, cos(inner) - cos(outer)),
// offset = -cos(outer) * scale, cd the cosine between the axis and light -> point.
TEST(LightSampler, SpotFalloffFollowsTheGltfFormula) {
  const double inner = 0.25, outer = 0.5;
  Scene scene;
  Light spot;
  spot.kind = Light::Kind::Spot;
  spot.position = {0, 2, 0};
  spot.direction = {0, -1, 0};
  spot.innerCone = float(inner), spot.outerCone = float(outer);
  spot.intensity = Vec3f(10.0f);
  scene.lights.push_back(spot);
  const LightSampler sampler(scene);
  const double scale = 1.0 / std::max(0.001, std::cos(inner) - std::cos(outer));
  const double offset = -std::cos(outer) * scale;
  int inCone = 0, inFalloff = 0, outside = 0;
  for (int k = 0; k <= 60; ++k) {
    // Receivers on the floor y = 0 at angles 0 .. 0.6 rad from the axis.
    const double angle = 0.01 * k;
    const Vec3f p{float(2 * std::tan(angle)), 0, 0};
    const double r2 = 4 + double(p.x) * p.x;
    const double cd = 2 / std::sqrt(r2);  // the axis is -y; light -> p has y component -2
    const double a = std::clamp(cd * scale + offset, 0.0, 1.0);
    const double expected = 10.0 * (2 / std::sqrt(r2)) / r2 * a * a;
    const LightSample s = sampler.sample(0, p, {0, 1, 0}, 0, 0, 0);
    EXPECT_NEAR(s.irradiance.x, expected, 1e-5 * (1 + expected)) << "angle " << angle;
    EXPECT_NEAR(spotAttenuation(float(cd), float(inner), float(outer)), a * a, 1e-5);
    if (angle < inner - 0.005) {
      EXPECT_NEAR(a, 1.0, 1e-12);  // full intensity inside the inner cone
      ++inCone;
    } else if (angle > outer + 0.005) {
      EXPECT_FALSE(s.valid);  // nothing beyond the outer cone
      ++outside;
    } else if (angle > inner + 0.005 && angle < outer - 0.005) {
      EXPECT_GT(a, 0.0);
      EXPECT_LT(a, 1.0);
      ++inFalloff;
    }
  }
  EXPECT_GT(inCone, 10);
  EXPECT_GT(inFalloff, 10);
  EXPECT_GT(outside, 5);
}

// uniformsFor() says which of (u1, u2, u3) a light reads (the tracer draws only those): a
// sample must not change when the others do.
TEST(LightSampler, ReadsOnlyTheUniformsItDeclares) {
  Scene scene;
  Material lamp;
  lamp.emission = Vec3f(5.0f);
  scene.materials.push_back(lamp);
  Light point, directional, quad, mesh;
  point.kind = Light::Kind::Point, point.position = {0.5f, 3, 0}, point.intensity = Vec3f(4);
  directional.kind = Light::Kind::Directional, directional.direction = {0.3f, -1, 0.2f};
  quad.kind = Light::Kind::Quad;
  quad.corner = {-1, 2, -1}, quad.edgeU = {2, 0, 0}, quad.edgeV = {0, 0, 2};
  quad.intensity = lamp.emission;
  addQuad(scene, "lamp", {-1, 2.5f, -1}, {2, 0, 0}, {0, 0, 2}, 0);
  addQuad(scene, "lamp2", {1, 2.5f, -1}, {1, 0, 0}, {0, 0, 1}, 0);
  mesh.kind = Light::Kind::Mesh, mesh.mesh = 0;
  scene.lights = {point, directional, quad, mesh};
  const LightSampler sampler(scene);
  const int expected[] = {0, 0, 2, 3};
  Rng rng(3);
  for (size_t light = 0; light < 4; ++light) {
    EXPECT_EQ(sampler.uniformsFor(light), expected[light]) << "light " << light;
    for (int trial = 0; trial < 50; ++trial) {
      float u[3] = {rng.uniform(), rng.uniform(), rng.uniform()};
      const LightSample a = sampler.sample(light, {0.2f, 0, 0.1f}, {0, 1, 0}, u[0], u[1], u[2]);
      // Change every number the light says it does not read.
      for (int k = sampler.uniformsFor(light); k < 3; ++k) u[k] = 1.0f - u[k] * 0.5f;
      const LightSample b = sampler.sample(light, {0.2f, 0, 0.1f}, {0, 1, 0}, u[0], u[1], u[2]);
      EXPECT_EQ(a.valid, b.valid);
      EXPECT_EQ(a.irradiance, b.irradiance) << "light " << light;
      EXPECT_EQ(a.toLight, b.toLight) << "light " << light;
    }
  }
}

}  // namespace
}  // namespace parallax
