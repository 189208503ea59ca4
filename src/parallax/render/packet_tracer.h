// Traces 16 camera rays as one packet: closest hits, direct light through packets of shadow
// rays, and mirror bounces as further packets. Radiance is linear. The per-lane work is
// written as loops over structure-of-arrays packets (packet_types.h) so that it vectorises.
#pragma once

#include <array>

#include "parallax/accel/accelerator.h"
#include "parallax/core/random.h"
#include "parallax/render/light_sampler.h"
#include "parallax/render/packet_types.h"
#include "parallax/render/render.h"
#include "parallax/render/surface.h"

namespace parallax {

class PacketTracer {
 public:
  PacketTracer(const Scene& scene, const Accelerator& accelerator, const LightSampler& lights)
      : scene_(scene), accelerator_(accelerator), lights_(lights), surfaces_(scene, accelerator) {}

  // Adds weight[lane] * radiance(ray[lane]) to radiance[lane] for the active lanes. Each lane
  // draws its random numbers from its own generator, so results do not depend on packing.
  void trace(const RayPacket16& rays, const Color16& weight, std::array<Rng, 16>& rngs,
             Color16& radiance, int depth, RenderStats& stats) const;

 private:
  void addDirectLight(const SurfacePacket16& surfaces, const Color16& weight,
                      std::array<Rng, 16>& rngs, Color16& radiance, RenderStats& stats) const;

  const Scene& scene_;
  const Accelerator& accelerator_;
  const LightSampler& lights_;
  SurfaceShader surfaces_;
};

}  // namespace parallax
