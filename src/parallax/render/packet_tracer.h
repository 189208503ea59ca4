// Traces 16 camera rays as one packet: closest hits, direct light through packets of shadow
// rays, mirror bounces and (with `bounces` > 0) diffuse path-tracing bounces as further packets
// (docs/path-tracing.md). Radiance is linear. The per-lane work is
// written as loops over structure-of-arrays packets (packet_types.h) so that it vectorises.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/core/random.h"
#include "parallax/render/light_sampler.h"
#include "parallax/render/packet_types.h"
#include "parallax/render/render_settings.h"
#include "parallax/render/splat_blend.h"
#include "parallax/render/surface.h"

namespace parallax {

class PacketTracer {
 public:
  // `bounces`: the diffuse bounces of a path (RenderSettings::bounces); 0 is direct light only.
  PacketTracer(const Scene& scene, const Accelerator& accelerator, const LightSampler& lights,
               int bounces = 0);

  // Adds weight[lane] * radiance(ray[lane]) to radiance[lane] for the active lanes. Each lane
  // draws its random numbers from its own generator, so results do not depend on packing.
  void trace(const RayPacket16& rays, const Color16& weight, std::array<Rng, 16>& rngs,
             Color16& radiance, int depth, RenderStats& stats) const;

 private:
  // Where a packet of rays is on its paths (the same for all its lanes).
  struct PathState {
    int mirrorDepth = 0;        // mirror reflections so far (limited by Scene::maxDepth)
    int diffuseDepth = 0;       // diffuse bounces so far (limited by bounces_)
    bool afterDiffuse = false;  // the rays left a diffuse bounce: light emitters are not counted
  };
  // `known`: the rays' closest hits when the caller has traced them already.
  void tracePath(const RayPacket16& rays, const Color16& weight, std::array<Rng, 16>& rngs,
                 Color16& radiance, const PathState& state, RenderStats& stats,
                 const HitPacket16* known = nullptr) const;
  // Camera rays in a scene with splats: the splats in front of each ray's first surface
  // blended over what the path sees there (splat_blend.h, docs/splats.md).
  void traceThroughSplats(const RayPacket16& rays, const Color16& weight, std::array<Rng, 16>& rngs,
                          Color16& radiance, RenderStats& stats) const;
  // Sends each lane's path on (bounces_ > 0): mirror reflections and diffuse bounces.
  void continuePaths(const RayPacket16& rays, const SurfacePacket16& sp, const Color16& weight,
                     std::array<Rng, 16>& rngs, Color16& radiance, const PathState& state,
                     RenderStats& stats) const;
  void addDirectLight(const SurfacePacket16& surfaces, const Color16& weight,
                      std::array<Rng, 16>& rngs, Color16& radiance, RenderStats& stats) const;

  const Scene& scene_;
  const Accelerator& accelerator_;
  const LightSampler& lights_;
  SurfaceShader surfaces_;
  SplatColours splats_;
  int bounces_ = 0;
  // Per Embree geometry: 1 if it is the surface of a light that next-event estimation samples
  // (a quad light's quad, an emissive mesh), so a diffuse bounce that hits it adds no emission.
  std::vector<uint8_t> sampledEmitter_;
};

}  // namespace parallax
