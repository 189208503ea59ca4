#include "parallax/render/light_sampler.h"

#include "parallax/core/lane_kernel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace parallax {

namespace {
constexpr float kShadowShorten = 1.0f - 1e-4f;  // stop shadow rays just before the light

// The spot falloff as a linear map of cos(theta) before the clamp and square (spotAttenuation);
// point and directional lights use scale 0 and offset 1, a factor of 1 everywhere.
struct SpotMap {
  float scale = 0.0f, offset = 1.0f;
};
SpotMap spotMap(const Light& light) {
  if (light.kind != Light::Kind::Spot) return {};
  const float scale =
      1.0f / std::max(0.001f, std::cos(light.innerCone) - std::cos(light.outerCone));
  return {scale, -std::cos(light.outerCone) * scale};
}
}  // namespace

float spotAttenuation(float cosTheta, float innerCone, float outerCone) {
  Light light;
  light.kind = Light::Kind::Spot;
  light.innerCone = innerCone;
  light.outerCone = outerCone;
  const SpotMap map = spotMap(light);
  const float a = std::clamp(cosTheta * map.scale + map.offset, 0.0f, 1.0f);
  return a * a;
}

LightSampler::LightSampler(const Scene& scene) {
  for (const Light& light : scene.lights) {
    Entry e;
    e.light = light;
    e.samples = std::max(1, light.samples);
    auto addTriangle = [&e](const Vec3f& a, const Vec3f& b, const Vec3f& c) {
      const Vec3f n = cross(b - a, c - a);
      const float area = 0.5f * length(n);
      if (!(area > 0.0f)) return;
      e.triangles.push_back({a, b - a, c - a, n / (2.0f * area), area});
      e.totalArea += area;
      e.cdf.push_back(e.totalArea);
    };
    if (light.kind == Light::Kind::Quad) {
      const Vec3f c = light.corner, u = light.edgeU, v = light.edgeV;
      addTriangle(c, c + u, c + u + v);
      addTriangle(c, c + u + v, c + v);
    } else if (light.kind == Light::Kind::Mesh && light.mesh >= 0 &&
               size_t(light.mesh) < scene.meshes.size()) {
      const TriangleMesh& m = scene.meshes[size_t(light.mesh)];
      for (size_t t = 0; t + 2 < m.indices.size(); t += 3)
        addTriangle(m.positions[m.indices[t]], m.positions[m.indices[t + 1]],
                    m.positions[m.indices[t + 2]]);
      e.light.intensity = scene.materials[m.material].emission;
    }
    const bool isArea = light.kind == Light::Kind::Quad || light.kind == Light::Kind::Mesh;
    if (isArea && e.triangles.empty()) continue;  // nothing to emit from
    lights_.push_back(std::move(e));
  }
}

// A point q on an area light (uniformly chosen, pdf 1 / A) as seen from p with normal n:
// E = L cos(theta) cos(theta_light) A / r^2.
LightSample LightSampler::areaSample(const Entry& e, const Vec3f& p, const Vec3f& n, const Vec3f& q,
                                     const Vec3f& lightNormal) {
  LightSample s;
  s.toLight = q - p;
  const float r2 = dot(s.toLight, s.toLight);
  const float invR = 1.0f / std::sqrt(r2);
  const float cosTheta = dot(n, s.toLight) * invR;
  float cosLight = -dot(lightNormal, s.toLight) * invR;
  if (e.light.twoSided) cosLight = std::abs(cosLight);
  if (!(cosTheta > 0.0f) || !(cosLight > 0.0f)) return s;
  s.irradiance = e.light.intensity * (cosTheta * cosLight * e.totalArea / r2);
  s.tMax = kShadowShorten;
  s.valid = true;
  return s;
}

LightSample LightSampler::sample(size_t index, const Vec3f& p, const Vec3f& n, float u1, float u2,
                                 float u3) const {
  const Entry& e = lights_[index];
  LightSample s;
  switch (e.light.kind) {
    case Light::Kind::Point:
    case Light::Kind::Spot: {
      // E = I cos(theta) / r^2, for a spot times its falloff at the angle from its axis.
      s.toLight = e.light.position - p;
      const float r2 = dot(s.toLight, s.toLight);
      const float invR = 1.0f / std::sqrt(r2);
      const float cosTheta = dot(n, s.toLight) * invR;
      if (!(cosTheta > 0.0f)) return s;
      float falloff = 1.0f;
      if (e.light.kind == Light::Kind::Spot) {
        falloff = spotAttenuation(-dot(e.light.direction, s.toLight) * invR, e.light.innerCone,
                                  e.light.outerCone);
        if (!(falloff > 0.0f)) return s;
      }
      s.irradiance = e.light.intensity * (cosTheta * falloff / r2);
      s.tMax = kShadowShorten;
      break;
    }
    case Light::Kind::Directional: {
      s.toLight = -e.light.direction;
      const float cosTheta = dot(n, s.toLight);
      if (!(cosTheta > 0.0f)) return s;
      s.irradiance = e.light.intensity * cosTheta;
      s.tMax = std::numeric_limits<float>::infinity();
      break;
    }
    case Light::Kind::Quad: {
      // Uniform on the parallelogram, pdf = 1 / A: E = L cos(theta) cos(theta_light) A / r^2.
      const Vec3f q = e.light.corner + e.light.edgeU * u1 + e.light.edgeV * u2;
      (void)u3;
      return areaSample(e, p, n, q, e.triangles.front().normal);
    }
    case Light::Kind::Mesh: {
      // Area sampling, pdf = 1 / A: E = L cos(theta) cos(theta_light) A / r^2.
      const float target = u1 * e.totalArea;
      const size_t t = size_t(std::upper_bound(e.cdf.begin(), e.cdf.end(), target) - e.cdf.begin());
      const Triangle& tri = e.triangles[std::min(t, e.triangles.size() - 1)];
      // Uniform point on a triangle (Osada et al. 2002).
      const float su = std::sqrt(u2);
      return areaSample(e, p, n, tri.p0 + tri.e1 * (su * (1.0f - u3)) + tri.e2 * (su * u3),
                        tri.normal);
    }
  }
  s.valid = true;
  return s;
}

namespace {

// The receivers of a packet as plain local arrays, and the lane results before they go into
// a LightPacket16: with nothing that can alias `out`, and & (not &&) in the conditions, the lane
// loops between them compile to SIMD.
struct Receivers16 {
  alignas(64) float px[16], py[16], pz[16], nx[16], ny[16], nz[16];
  alignas(64) int32_t shade[16];
  explicit Receivers16(const SurfacePacket16& sp) {
    for (int i = 0; i < 16; ++i) {
      px[i] = sp.px[i], py[i] = sp.py[i], pz[i] = sp.pz[i];
      nx[i] = sp.nx[i], ny[i] = sp.ny[i], nz[i] = sp.nz[i], shade[i] = sp.shade[i];
    }
  }
};

struct LightLanes16 {
  alignas(64) float tx[16], ty[16], tz[16], er[16], eg[16], eb[16];
  alignas(64) int32_t valid[16];
  void store(float tMax, LightPacket16& out) const {
    for (int i = 0; i < 16; ++i) {
      out.tx[i] = tx[i], out.ty[i] = ty[i], out.tz[i] = tz[i];
      out.tMax[i] = tMax;
      out.irradiance.r[i] = er[i], out.irradiance.g[i] = eg[i], out.irradiance.b[i] = eb[i];
      out.valid[i] = valid[i];
    }
  }
};

}  // namespace

PARALLAX_LANE_KERNEL void LightSampler::sample16(size_t index, const SurfacePacket16& sp,
                                                 const float u1[16], const float u2[16],
                                                 const float u3[16], LightPacket16& out) const {
  const Entry& e = lights_[index];
  const Light& light = e.light;
  if (light.kind == Light::Kind::Quad) {
    // The common case: a uniform point on the parallelogram, E = L cos(theta) cos(theta_light)
    // A / r^2. Plain scalars for the constants (struct members read in the loop kept it scalar).
    const Receivers16 r(sp);
    alignas(64) float a1[16], a2[16];
    for (int i = 0; i < 16; ++i) a1[i] = u1[i], a2[i] = u2[i];
    const Vec3f c = light.corner, eu = light.edgeU, ev = light.edgeV;
    const Vec3f ln = e.triangles.front().normal, L = light.intensity;
    const float cx = c.x, cy = c.y, cz = c.z, ux = eu.x, uy = eu.y, uz = eu.z;
    const float vx = ev.x, vy = ev.y, vz = ev.z, lx = ln.x, ly = ln.y, lz = ln.z;
    const float Lr = L.x, Lg = L.y, Lb = L.z, sign = light.twoSided ? -1.0f : 1.0f;
    const float area = e.totalArea;
    LightLanes16 lanes;
    PARALLAX_SIMD
    for (int i = 0; i < 16; ++i) {
      const float x = cx + ux * a1[i] + vx * a2[i] - r.px[i];
      const float y = cy + uy * a1[i] + vy * a2[i] - r.py[i];
      const float z = cz + uz * a1[i] + vz * a2[i] - r.pz[i];
      const float r2 = x * x + y * y + z * z;
      const float invR = 1.0f / std::sqrt(r2);
      const float cosTheta = (r.nx[i] * x + r.ny[i] * y + r.nz[i] * z) * invR;
      const float facing = -(lx * x + ly * y + lz * z) * invR;
      // Two-sided lights count either face: |facing| = max(facing, -facing).
      const float cosLight = std::max(facing, sign * facing);
      const int32_t ok =
          int32_t(r.shade[i] != 0) & int32_t(cosTheta > 0.0f) & int32_t(cosLight > 0.0f);
      const float scale = ok ? cosTheta * cosLight * area / r2 : 0.0f;
      lanes.tx[i] = x, lanes.ty[i] = y, lanes.tz[i] = z;
      lanes.er[i] = Lr * scale, lanes.eg[i] = Lg * scale, lanes.eb[i] = Lb * scale;
      lanes.valid[i] = ok;
    }
    lanes.store(kShadowShorten, out);
    (void)u3;
    return;
  }
  if (light.kind == Light::Kind::Directional || light.kind == Light::Kind::Point ||
      light.kind == Light::Kind::Spot) {
    // Lane loops of sample()'s first cases: E = I cos(theta) along a fixed direction, or
    // E = I cos(theta) / r^2 toward a point, times the spot falloff (1 for the others).
    const Receivers16 r(sp);
    const float point = light.kind != Light::Kind::Directional ? 1.0f : 0.0f;
    // toLight = at - point * p: the light's position, or the fixed direction.
    const Vec3f at = point > 0 ? light.position : -light.direction;
    const float ax = at.x, ay = at.y, az = at.z;
    const float Ir = light.intensity.x, Ig = light.intensity.y, Ib = light.intensity.z;
    const float sx = light.direction.x, sy = light.direction.y, sz = light.direction.z;
    const SpotMap spot = spotMap(light);
    const float spotScale = spot.scale, spotOffset = spot.offset;
    LightLanes16 lanes;
    PARALLAX_SIMD
    for (int i = 0; i < 16; ++i) {
      const float x = ax - point * r.px[i], y = ay - point * r.py[i], z = az - point * r.pz[i];
      const float r2 = point > 0 ? x * x + y * y + z * z : 1.0f;
      const float invR = 1.0f / std::sqrt(r2);
      const float cosTheta = (r.nx[i] * x + r.ny[i] * y + r.nz[i] * z) * invR;
      // The angle from the spot's axis: between the axis and light -> receiver (-toLight).
      const float cosAxis = -(sx * x + sy * y + sz * z) * invR;
      const float a = std::min(std::max(cosAxis * spotScale + spotOffset, 0.0f), 1.0f);
      const float falloff = a * a;
      const int32_t ok =
          int32_t(r.shade[i] != 0) & int32_t(cosTheta > 0.0f) & int32_t(falloff > 0.0f);
      const float scale = ok ? cosTheta * falloff / r2 : 0.0f;
      lanes.tx[i] = x, lanes.ty[i] = y, lanes.tz[i] = z;
      lanes.er[i] = Ir * scale, lanes.eg[i] = Ig * scale, lanes.eb[i] = Ib * scale;
      lanes.valid[i] = ok;
    }
    lanes.store(point > 0 ? kShadowShorten : std::numeric_limits<float>::infinity(), out);
    return;
  }
  PARALLAX_SIMD
  for (int i = 0; i < 16; ++i) {
    out.valid[i] = 0;
    if (!sp.shade[i]) continue;
    const LightSample s = sample(index, {sp.px[i], sp.py[i], sp.pz[i]},
                                 {sp.nx[i], sp.ny[i], sp.nz[i]}, u1[i], u2[i], u3[i]);
    out.tx[i] = s.toLight.x, out.ty[i] = s.toLight.y, out.tz[i] = s.toLight.z;
    out.tMax[i] = s.tMax;
    out.irradiance.set(i, s.irradiance);
    out.valid[i] = s.valid;
  }
}

int LightSampler::uniformsFor(size_t light) const {
  switch (lights_[light].light.kind) {
    case Light::Kind::Point:
    case Light::Kind::Spot:
    case Light::Kind::Directional:
      return 0;
    case Light::Kind::Quad:
      return 2;
    case Light::Kind::Mesh:
      return 3;
  }
  return 3;
}

Vec3f LightSampler::representativePoint(const Vec3f& fallback) const {
  if (lights_.empty()) return fallback;
  const Entry& e = lights_.front();
  switch (e.light.kind) {
    case Light::Kind::Point:
    case Light::Kind::Spot:
      return e.light.position;
    case Light::Kind::Directional:
      return fallback - e.light.direction * 1e4f;
    default: {
      const Triangle& t = e.triangles.front();
      return t.p0 + (t.e1 + t.e2) * (1.0f / 3.0f);
    }
  }
}

}  // namespace parallax
