#include "parallax/render/packet_tracer.h"

namespace parallax {

namespace {

// A point just off the surface, as offsetAlong() in surface.h, for all lanes.
inline float offsetScale(float x, float y, float z) {
  return 2e-4f * (1.0f + std::max(std::abs(x), std::max(std::abs(y), std::abs(z))));
}

}  // namespace

void PacketTracer::trace(const RayPacket16& rays, const Color16& weight, std::array<Rng, 16>& rngs,
                         Color16& radiance, int depth, RenderStats& stats) const {
  HitPacket16 hits;
  accelerator_.intersect16(rays, hits);
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
    if (depth == 0) stats.cameraMisses += active;
    return;
  }
  SurfacePacket16 sp;
  Color16 emitted;
  emitted.fill(0.0f);
  surfaces_.evaluate16(rays, hits, sp, emitted);
  if (depth == 0) {
    uint64_t misses = 0;
    for (int i = 0; i < 16; ++i) misses += rays.active[i] != 0 && !sp.hit[i];
    stats.cameraMisses += misses;
  }

  // Escaped rays see the background; hits add what they emit and the ambient term (a uniform
  // radiance L_a over the hemisphere reflects albedo * L_a from a Lambertian surface).
  const Vec3f bg = scene_.background, amb = scene_.ambient;
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

  // Mirror bounces, still as a packet: neighbouring rays reflect off neighbouring points.
  if (depth >= scene_.maxDepth) return;
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
    const Vec3f n{sp.nx[lane], sp.ny[lane], sp.nz[lane]};
    const Vec3f g{sp.gx[lane], sp.gy[lane], sp.gz[lane]};
    const Vec3f p{sp.px[lane], sp.py[lane], sp.pz[lane]};
    const Vec3f d = normalize(rays.ray(lane).direction);
    const Vec3f reflected = d - n * (2.0f * dot(d, n));
    bounce.set(lane, {offsetAlong(p, g), reflected});
    bounceWeight.set(lane, weight.at(lane) * mirror);
    ++stats.secondaryRays;
    any = true;
  }
  if (any) trace(bounce, bounceWeight, rngs, radiance, depth + 1, stats);
}

// Direct light: one packet of shadow rays per light sample; Lambertian BRDF albedo / pi.
void PacketTracer::addDirectLight(const SurfacePacket16& sp, const Color16& weight,
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
