#include "parallax/render/packet_tracer.h"

#include "parallax/core/lane_kernel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace parallax {

namespace {

// A point just off the surface, as offsetAlong() in surface.h, for all lanes.
inline float offsetScale(float x, float y, float z) {
  return 2e-4f * (1.0f + std::max(std::abs(x), std::max(std::abs(y), std::abs(z))));
}

// The mirror reflection of a lane's ray about its shading normal, from just off the surface.
Ray mirrorRay(const RayPacket16& rays, const SurfacePacket16& sp, int lane) {
  const Vec3f n{sp.nx[lane], sp.ny[lane], sp.nz[lane]};
  const Vec3f g{sp.gx[lane], sp.gy[lane], sp.gz[lane]};
  const Vec3f p{sp.px[lane], sp.py[lane], sp.pz[lane]};
  const Vec3f d = normalize(rays.ray(lane).direction);
  const Vec3f reflected = d - n * (2.0f * dot(d, n));
  return {offsetAlong(p, g), reflected};
}

}  // namespace

PacketTracer::PacketTracer(const Scene& scene, const Accelerator& accelerator,
                           const LightSampler& lights, int bounces)
    : scene_(scene),
      accelerator_(accelerator),
      lights_(lights),
      surfaces_(scene, accelerator),
      splats_(scene),
      bounces_(bounces) {
  // Each bounce is one level of recursion (a few KiB of packets on the stack): the range is
  // RenderSettings's, which the command line checks (--bounces).
  if (bounces < 0 || bounces > RenderSettings::kMaxBounces)
    throw std::invalid_argument("PacketTracer: bounces " + std::to_string(bounces) +
                                " outside 0.." + std::to_string(RenderSettings::kMaxBounces));
  // The meshes whose emission next-event estimation already samples (light_sampler.h): a quad
  // light's visible quad and every emissive mesh light. A diffuse bounce that reaches one of
  // them adds nothing, or the light would be counted twice (docs/path-tracing.md).
  std::vector<uint8_t> lightMesh(scene.meshes.size(), 0);
  for (const Light& light : scene.lights)
    if ((light.kind == Light::Kind::Quad || light.kind == Light::Kind::Mesh) && light.mesh >= 0 &&
        size_t(light.mesh) < scene.meshes.size())
      lightMesh[size_t(light.mesh)] = 1;
  sampledEmitter_.assign(scene.meshes.size() + scene.spheres.size(), 0);
  for (uint32_t id = 0; id < sampledEmitter_.size(); ++id) {
    const SurfaceRef ref = accelerator.surface(id);
    sampledEmitter_[id] = ref.kind == SurfaceRef::Kind::Mesh && lightMesh[ref.index];
  }
}

void PacketTracer::trace(const RayPacket16& rays, const Color16& weight, std::array<Rng, 16>& rngs,
                         Color16& radiance, int depth, RenderStats& stats) const {
  if (!splats_.empty() && depth == 0)
    return traceThroughSplats(rays, weight, rngs, radiance, stats);
  tracePath(rays, weight, rngs, radiance, PathState{depth, 0, false}, stats);
}

// Splats are seen by camera rays (docs/splats.md, "Blending"): the mesh hit bounds each ray's
// walk through them, and the path behind is traced with unit weight, so that the two can be
// composited in display values as 3DGS composites (not additive in radiance). Lanes whose
// splats are opaque skip the path behind. Mirrors and diffuse bounces see the meshes alone,
// and splats cast no shadows.
void PacketTracer::traceThroughSplats(const RayPacket16& rays, const Color16& weight,
                                      std::array<Rng, 16>& rngs, Color16& radiance,
                                      RenderStats& stats) const {
  HitPacket16 hits;
  accelerator_.intersect16(rays, hits);
  SplatBlend blends[16];
  RayPacket16 walked = rays;
  for (int lane = 0; lane < 16; ++lane)
    if (hits.geometry[lane] != kNoHit) walked.tMax[lane] = hits.t[lane];
  blendSplats16(accelerator_, splats_, walked, blends);
  RayPacket16 behindRays = rays;
  for (int lane = 0; lane < 16; ++lane) {
    if (!rays.active[lane]) continue;
    stats.splatsEvaluated += blends[lane].evaluated;
    stats.splatsBlended += blends[lane].blended;
    if (blends[lane].opaque) {
      behindRays.deactivate(lane);
      hits.geometry[lane] = kNoHit;
    }
  }
  Color16 behind, unit;
  behind.fill(0.0f);
  unit.fill(1.0f);
  tracePath(behindRays, unit, rngs, behind, PathState{0, 0, false}, stats, &hits);
  for (int lane = 0; lane < 16; ++lane) {
    if (!rays.active[lane]) continue;
    const Vec3f seen = overBehind(blends[lane], behind.at(lane));
    radiance.r[lane] += weight.r[lane] * seen.x;
    radiance.g[lane] += weight.g[lane] * seen.y;
    radiance.b[lane] += weight.b[lane] * seen.z;
  }
}

PARALLAX_LANE_KERNEL void PacketTracer::tracePath(const RayPacket16& rays, const Color16& weight,
                                                  std::array<Rng, 16>& rngs, Color16& radiance,
                                                  const PathState& state, RenderStats& stats,
                                                  const HitPacket16* known) const {
  const bool cameraRays = state.mirrorDepth == 0 && state.diffuseDepth == 0;
  HitPacket16 traced;
  if (!known) accelerator_.intersect16(rays, traced);
  const HitPacket16& hits = known ? *known : traced;
  // A packet that met nothing (the sky around the subject: half the camera rays of the
  // built-in scene) only sees the background; it needs no surfaces and no light.
  int hitCount = 0;
  PARALLAX_SIMD_SUM(hitCount)
  for (int i = 0; i < 16; ++i)
    hitCount += int32_t(rays.active[i] != 0) & int32_t(hits.geometry[i] != kNoHit);
  if (hitCount == 0) {
    const Vec3f bg = scene_.background;
    uint64_t active = 0;
    PARALLAX_SIMD_SUM(active)
    for (int i = 0; i < 16; ++i) {
      const float on = rays.active[i] != 0 ? 1.0f : 0.0f;
      radiance.r[i] += weight.r[i] * (on * bg.x);
      radiance.g[i] += weight.g[i] * (on * bg.y);
      radiance.b[i] += weight.b[i] * (on * bg.z);
      active += rays.active[i] != 0;
    }
    if (cameraRays) stats.cameraMisses += active;
    return;
  }
  SurfacePacket16 sp;
  Color16 emitted;
  emitted.fill(0.0f);
  surfaces_.evaluate16(rays, hits, sp, emitted);
  if (state.afterDiffuse) {
    // Next-event estimation at the previous vertex already counted the lights' own surfaces.
    for (int i = 0; i < 16; ++i) {
      const bool drop = sp.hit[i] && sampledEmitter_[hits.geometry[i]] != 0;
      emitted.r[i] = drop ? 0.0f : emitted.r[i];
      emitted.g[i] = drop ? 0.0f : emitted.g[i];
      emitted.b[i] = drop ? 0.0f : emitted.b[i];
    }
  }
  if (cameraRays) {
    uint64_t misses = 0;
    for (int i = 0; i < 16; ++i) misses += rays.active[i] != 0 && !sp.hit[i];
    stats.cameraMisses += misses;
  }

  // Escaped rays see the background; hits add what they emit and the ambient term (a uniform
  // radiance L_a over the hemisphere reflects albedo * L_a from a Lambertian surface). The
  // ambient term stands in for the diffuse light no path goes on to gather, so it is added
  // only where the diffuse bounces end (docs/path-tracing.md, "Ambient"); with bounces 0 that
  // is every hit, as it always was.
  const Vec3f bg = scene_.background;
  const Vec3f amb = state.diffuseDepth == bounces_ ? scene_.ambient : Vec3f(0.0f);
  PARALLAX_SIMD
  for (int i = 0; i < 16; ++i) {
    const bool active = rays.active[i] != 0;
    const float r = sp.hit[i] ? emitted.r[i] + sp.diffuse.r[i] * amb.x : (active ? bg.x : 0.f);
    const float g = sp.hit[i] ? emitted.g[i] + sp.diffuse.g[i] * amb.y : (active ? bg.y : 0.f);
    const float b = sp.hit[i] ? emitted.b[i] + sp.diffuse.b[i] * amb.z : (active ? bg.z : 0.f);
    radiance.r[i] += weight.r[i] * r;
    radiance.g[i] += weight.g[i] * g;
    radiance.b[i] += weight.b[i] * b;
  }

  addDirectLight(sp, weight, rngs, radiance, stats);

  if (bounces_ > 0) {
    continuePaths(rays, sp, weight, rngs, radiance, state, stats);
    return;
  }

  // Mirror bounces, still as a packet: neighbouring rays reflect off neighbouring points.
  if (state.mirrorDepth >= scene_.maxDepth) return;
  int mirrors = 0;
  PARALLAX_SIMD_SUM(mirrors)
  for (int i = 0; i < 16; ++i)
    mirrors += sp.hit[i] & int32_t(sp.mirror.r[i] + sp.mirror.g[i] + sp.mirror.b[i] > 0.0f);
  if (mirrors == 0) return;
  // Every lane of the bounce packet is defined: an inactive lane's weight multiplies its zero
  // radiance below, and uninitialised memory there (NaN, inf) turned whole channels into NaN
  // (red and yellow speckles on the bunny's mirror porcelain).
  RayPacket16 bounce{};
  Color16 bounceWeight;
  bounceWeight.fill(0.0f);
  bool any = false;
  for (int lane = 0; lane < 16; ++lane) {
    bounce.deactivate(lane);
    if (!sp.hit[lane]) continue;
    const Vec3f mirror = sp.mirror.at(lane);
    if (!(maxComponent(mirror) > 0.0f)) continue;
    bounce.set(lane, mirrorRay(rays, sp, lane));
    bounceWeight.set(lane, weight.at(lane) * mirror);
    ++stats.secondaryRays;
    any = true;
  }
  if (any)
    tracePath(bounce, bounceWeight, rngs, radiance,
              PathState{state.mirrorDepth + 1, state.diffuseDepth, false}, stats);
}

// Path tracing (docs/path-tracing.md): after the direct light, each lane's path goes on by a
// mirror reflection, a cosine-weighted diffuse bounce, or both. Until a path's first diffuse
// bounce it splits as the direct renderer always did (the mirror chain is followed whole, and
// every diffuse hit also starts a diffuse path); after it, a path follows one of the two,
// chosen with probability proportional to the largest channel of each reflectance and
// weighted by the inverse of that probability, so that the work per camera ray stays linear in
// the number of bounces. Mirror and diffuse continuations go out as two packets.
PARALLAX_LANE_KERNEL void PacketTracer::continuePaths(const RayPacket16& rays,
                                                      const SurfacePacket16& sp,
                                                      const Color16& weight,
                                                      std::array<Rng, 16>& rngs, Color16& radiance,
                                                      const PathState& state,
                                                      RenderStats& stats) const {
  const bool mirrorAllowed = state.mirrorDepth < scene_.maxDepth;
  const bool diffuseAllowed = state.diffuseDepth < bounces_;
  if (!mirrorAllowed && !diffuseAllowed) return;
  const bool split = state.diffuseDepth == 0;
  // Three numbers per lane at every vertex that may go on, whether a lane needs them or not:
  // the choice, then the two of the direction. Every lane of every such packet draws them, so
  // a lane's stream depends only on its own pixel sample and the packet's fixed layout.
  alignas(64) float choice[16], u1[16], u2[16];
  for (int i = 0; i < 16; ++i) {
    choice[i] = rngs[size_t(i)].uniform();
    u1[i] = rngs[size_t(i)].uniform();
    u2[i] = rngs[size_t(i)].uniform();
  }
  // Per lane: the weight factor of a mirror (wm) and of a diffuse (wd) continuation, 0 for
  // none.
  alignas(64) float wm[16], wd[16];
  int mirrorCount = 0, diffuseCount = 0;
  for (int i = 0; i < 16; ++i) {
    const float m = sp.hit[i] && mirrorAllowed ? maxComponent(sp.mirror.at(i)) : 0.0f;
    const float d = sp.shade[i] && diffuseAllowed ? maxComponent(sp.diffuse.at(i)) : 0.0f;
    wm[i] = m > 0.0f ? 1.0f : 0.0f;
    wd[i] = d > 0.0f ? 1.0f : 0.0f;
    if (!split && m > 0.0f && d > 0.0f) {
      // One of the two, with probability p_m = m / (m + d) for the mirror: each estimate is
      // divided by its probability (unbiased, docs/path-tracing.md, eq. 4).
      const float pm = m / (m + d);
      const bool mirror = choice[i] < pm;
      wm[i] = mirror ? 1.0f / pm : 0.0f;
      wd[i] = mirror ? 0.0f : 1.0f / (1.0f - pm);
    }
    mirrorCount += wm[i] > 0.0f;
    diffuseCount += wd[i] > 0.0f;
  }

  if (mirrorCount > 0) {
    RayPacket16 bounce{};
    Color16 bounceWeight;
    bounceWeight.fill(0.0f);
    for (int lane = 0; lane < 16; ++lane) {
      bounce.deactivate(lane);
      if (!(wm[lane] > 0.0f)) continue;
      bounce.set(lane, mirrorRay(rays, sp, lane));
      bounceWeight.set(lane, weight.at(lane) * sp.mirror.at(lane) * wm[lane]);
      ++stats.secondaryRays;
    }
    tracePath(bounce, bounceWeight, rngs, radiance,
              PathState{state.mirrorDepth + 1, state.diffuseDepth, false}, stats);
  }
  if (diffuseCount == 0) return;

  // Cosine-weighted directions about the shading normal (pdf cos(theta) / pi), in the frame of
  // Duff et al. 2017 ("Building an orthonormal basis, revisited"): the Lambertian BRDF
  // rho / pi times cos(theta) over the pdf leaves the throughput times rho (eq. 3).
  RayPacket16 bounce{};
  Color16 bounceWeight;
  alignas(64) int32_t go[16];
  int count = 0;
  PARALLAX_SIMD_SUM(count)
  for (int i = 0; i < 16; ++i) {
    const float nx = sp.nx[i], ny = sp.ny[i], nz = sp.nz[i];
    const float sign = nz >= 0.0f ? 1.0f : -1.0f;
    const float a = -1.0f / (sign + nz), b = nx * ny * a;
    const float tx = 1.0f + sign * nx * nx * a, ty = sign * b, tz = -sign * nx;
    const float bx = b, by = sign + ny * ny * a, bz = -ny;
    const float r = std::sqrt(u1[i]), phi = 2.0f * kPi * u2[i];
    const float x = r * std::cos(phi), y = r * std::sin(phi);
    const float z = std::sqrt(std::max(0.0f, 1.0f - u1[i]));
    const float dx = tx * x + bx * y + nx * z, dy = ty * x + by * y + ny * z,
                dz = tz * x + bz * y + nz * z;
    // A direction below the geometric surface (possible with interpolated normals) would
    // start inside the object: that lane's path ends.
    const bool above = dx * sp.gx[i] + dy * sp.gy[i] + dz * sp.gz[i] > 0.0f;
    const bool on = (wd[i] > 0.0f) & above;
    const float o = offsetScale(sp.px[i], sp.py[i], sp.pz[i]);
    bounce.ox[i] = sp.px[i] + sp.gx[i] * o;
    bounce.oy[i] = sp.py[i] + sp.gy[i] * o;
    bounce.oz[i] = sp.pz[i] + sp.gz[i] * o;
    bounce.dx[i] = on ? dx : 0.0f;
    bounce.dy[i] = on ? dy : 0.0f;
    bounce.dz[i] = on ? dz : 1.0f;
    bounce.tMin[i] = 0.0f;
    bounce.tMax[i] = std::numeric_limits<float>::infinity();
    bounce.active[i] = on ? -1 : 0;
    go[i] = on ? 1 : 0;
    const float f = on ? wd[i] : 0.0f;
    bounceWeight.r[i] = weight.r[i] * sp.diffuse.r[i] * f;
    bounceWeight.g[i] = weight.g[i] * sp.diffuse.g[i] * f;
    bounceWeight.b[i] = weight.b[i] * sp.diffuse.b[i] * f;
    count += go[i];
  }
  if (count == 0) return;
  stats.secondaryRays += uint64_t(count);
  stats.bounceRays += uint64_t(count);
  tracePath(bounce, bounceWeight, rngs, radiance,
            PathState{state.mirrorDepth, state.diffuseDepth + 1, true}, stats);
}

// Direct light: one packet of shadow rays per light sample; Lambertian BRDF albedo / pi.
PARALLAX_LANE_KERNEL void PacketTracer::addDirectLight(const SurfacePacket16& sp,
                                                       const Color16& weight,
                                                       std::array<Rng, 16>& rngs, Color16& radiance,
                                                       RenderStats& stats) const {
  int shading = 0;
  for (int i = 0; i < 16; ++i) shading += sp.shade[i];
  if (shading == 0) return;
  alignas(64) float u1[16], u2[16], u3[16];
  LightPacket16 light;
  RayPacket16 shadow;
  for (size_t index = 0; index < lights_.lightCount(); ++index) {
    const int samples = lights_.samplesFor(index);
    const float perSample = 1.0f / (kPi * float(samples));
    // Every sample moves each lane's stream by three draws, whatever the light reads, so the
    // numbers a lane gets do not depend on which lights came before; only those read are made.
    const int uniforms = lights_.uniformsFor(index);
    for (int s = 0; s < samples; ++s) {
      if (uniforms == 3) {
        PARALLAX_SIMD
        for (int i = 0; i < 16; ++i) {
          u1[i] = rngs[size_t(i)].uniform();
          u2[i] = rngs[size_t(i)].uniform();
          u3[i] = rngs[size_t(i)].uniform();
        }
      } else if (uniforms == 2) {
        PARALLAX_SIMD
        for (int i = 0; i < 16; ++i) {
          u1[i] = rngs[size_t(i)].uniform();
          u2[i] = rngs[size_t(i)].uniform();
          rngs[size_t(i)].skip(1);
        }
      } else {
        for (int i = 0; i < 16; ++i) rngs[size_t(i)].skip(3);
      }
      lights_.sample16(index, sp, u1, u2, u3, light);
      int count = 0;
      PARALLAX_SIMD_SUM(count)
      for (int i = 0; i < 16; ++i) {
        // A light below the geometric surface cannot be seen even if the shading normal
        // faces it: skip it rather than start the shadow ray inside the object.
        const bool above =
            sp.gx[i] * light.tx[i] + sp.gy[i] * light.ty[i] + sp.gz[i] * light.tz[i] > 0.0f;
        const bool trace = light.valid[i] && above;
        const float o = offsetScale(sp.px[i], sp.py[i], sp.pz[i]);
        // Origin lifted off the surface; the direction still ends on the light point.
        shadow.ox[i] = sp.px[i] + sp.gx[i] * o;
        shadow.oy[i] = sp.py[i] + sp.gy[i] * o;
        shadow.oz[i] = sp.pz[i] + sp.gz[i] * o;
        shadow.dx[i] = light.tx[i] - sp.gx[i] * o;
        shadow.dy[i] = light.ty[i] - sp.gy[i] * o;
        shadow.dz[i] = light.tz[i] - sp.gz[i] * o;
        shadow.tMin[i] = 0.0f;
        shadow.tMax[i] = light.tMax[i];
        shadow.active[i] = trace ? -1 : 0;
        count += trace;
      }
      if (count == 0) continue;
      bool occluded[16];
      accelerator_.occluded16(shadow, occluded);
      stats.shadowRays += uint64_t(count);
      // The lit lanes' weights as floats first: a bool array in the arithmetic loop below kept
      // it from vectorising.
      alignas(64) float lit[16];
      for (int i = 0; i < 16; ++i) lit[i] = shadow.active[i] && !occluded[i] ? perSample : 0.0f;
      PARALLAX_SIMD
      for (int i = 0; i < 16; ++i) {
        // Selects, not products with 0: an unlit lane's irradiance may be unset.
        const bool on = lit[i] > 0.0f;
        radiance.r[i] += on ? weight.r[i] * sp.diffuse.r[i] * light.irradiance.r[i] * lit[i] : 0.f;
        radiance.g[i] += on ? weight.g[i] * sp.diffuse.g[i] * light.irradiance.g[i] * lit[i] : 0.f;
        radiance.b[i] += on ? weight.b[i] * sp.diffuse.b[i] * light.irradiance.b[i] * lit[i] : 0.f;
      }
    }
  }
}

}  // namespace parallax
