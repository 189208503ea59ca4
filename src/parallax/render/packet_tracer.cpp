#include "parallax/render/packet_tracer.h"

#include "parallax/render/surface.h"

namespace parallax {

void PacketTracer::trace(const RayPacket16& rays, const std::array<Vec3f, 16>& weight,
                         std::array<Rng, 16>& rngs, std::array<Vec3f, 16>& radiance, int depth,
                         RenderStats& stats) const {
  HitPacket16 hits;
  accelerator_.intersect16(rays, hits);

  std::array<SurfacePoint, 16> surfaces;
  bool shaded[16] = {};
  for (int lane = 0; lane < 16; ++lane) {
    if (!rays.active[lane]) continue;
    if (!hits.hit(lane).valid()) {
      radiance[size_t(lane)] += weight[size_t(lane)] * scene_.background;
      continue;
    }
    const SurfacePoint& sp = surfaces[size_t(lane)] =
        surfaces_.evaluate(rays.ray(lane), hits.hit(lane));
    // Emission seen directly, plus the ambient term: a uniform radiance L_a over the
    // hemisphere reflects albedo * L_a from a Lambertian surface.
    radiance[size_t(lane)] +=
        weight[size_t(lane)] * (sp.emission + sp.diffuse * scene_.ambient);
    shaded[lane] = maxComponent(sp.diffuse) > 0.0f;
  }

  // Direct light: one packet of shadow rays per light sample. Lambertian BRDF albedo / pi.
  RayPacket16 shadow;
  std::array<Vec3f, 16> contribution;
  for (size_t light = 0; light < lights_.lightCount(); ++light) {
    const int samples = lights_.samplesFor(light);
    const float perSample = 1.0f / (kPi * float(samples));
    for (int s = 0; s < samples; ++s) {
      bool any = false;
      for (int lane = 0; lane < 16; ++lane) {
        shadow.deactivate(lane);
        if (!shaded[lane]) continue;
        Rng& rng = rngs[size_t(lane)];
        const SurfacePoint& sp = surfaces[size_t(lane)];
        const float u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
        const LightSample ls = lights_.sample(light, sp.position, sp.shadingNormal, u1, u2, u3);
        // A light below the geometric surface cannot be seen even if the shading normal
        // faces it: skip it instead of letting the shadow ray start inside the object.
        if (!ls.valid || dot(ls.toLight, sp.geometricNormal) <= 0.0f) continue;
        const Vec3f origin = offsetAlong(sp.position, sp.geometricNormal);
        shadow.set(lane, {origin, ls.toLight + (sp.position - origin), 0.0f, ls.tMax});
        contribution[size_t(lane)] = weight[size_t(lane)] * sp.diffuse * ls.irradiance * perSample;
        any = true;
      }
      if (!any) continue;
      bool occluded[16];
      accelerator_.occluded16(shadow, occluded);
      for (int lane = 0; lane < 16; ++lane) {
        if (!shadow.active[lane]) continue;
        ++stats.shadowRays;
        if (!occluded[lane]) radiance[size_t(lane)] += contribution[size_t(lane)];
      }
    }
  }

  // Mirror bounces, still as a packet: neighbouring rays reflect off neighbouring points.
  if (depth >= scene_.maxDepth) return;
  RayPacket16 bounce;
  std::array<Vec3f, 16> bounceWeight;
  bool any = false;
  for (int lane = 0; lane < 16; ++lane) {
    bounce.deactivate(lane);
    if (!rays.active[lane] || !hits.hit(lane).valid()) continue;
    const SurfacePoint& sp = surfaces[size_t(lane)];
    if (!(maxComponent(sp.mirror) > 0.0f)) continue;
    const Vec3f d = normalize(rays.ray(lane).direction);
    const Vec3f reflected = d - sp.shadingNormal * (2.0f * dot(d, sp.shadingNormal));
    bounce.set(lane, {offsetAlong(sp.position, sp.geometricNormal), reflected});
    bounceWeight[size_t(lane)] = weight[size_t(lane)] * sp.mirror;
    ++stats.secondaryRays;
    any = true;
  }
  if (any) trace(bounce, bounceWeight, rngs, radiance, depth + 1, stats);
}

}  // namespace parallax
