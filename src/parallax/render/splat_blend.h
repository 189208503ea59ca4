// What a ray sees of the Gaussian splats in front of whatever it meets (docs/splats.md,
// "Blending"): their colours for the ray's own direction, composited front to back as 3DGS's
// rasteriser composites them, in display values.
#pragma once

#include <cstdint>
#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/core/math.h"
#include "parallax/core/ray.h"
#include "parallax/scene/scene.h"

namespace parallax {

// The Gaussians of every splat set, indexed as the accelerator indexes them, with what their
// colour needs: the coefficients, and each set's map of world directions into its file's frame.
class SplatColours {
 public:
  explicit SplatColours(const Scene& scene);
  bool empty() const { return count_ == 0; }
  // Gaussian `gaussian`'s colour (display values) seen along the world direction `direction`
  // (any length): its harmonics at that direction taken into its file's frame.
  Vec3f colour(uint32_t gaussian, const Vec3f& direction) const;

  // The colours of many Gaussians along one ray: the basis at the ray's direction is the same
  // for every Gaussian of a set, so it is evaluated once a set, not once a Gaussian.
  class AlongRay {
   public:
    AlongRay(const SplatColours& colours, const Vec3f& direction)
        : colours_(colours), direction_(direction) {}
    Vec3f colour(uint32_t gaussian);

   private:
    const SplatColours& colours_;
    Vec3f direction_;
    size_t set_ = size_t(-1);  // the set whose basis `basis_` holds
    int count_ = 0;
    // The basis repeated for the three channels (basis_[3 k + c] = Y_k), to multiply a
    // Gaussian's coefficient-major floats as they lie in memory.
    alignas(64) float basis_[3 * shCoefficientCount(kMaxShDegree)];
  };

 private:
  size_t setOf(uint32_t gaussian) const;
  struct Set {
    uint32_t first = 0;
    const GaussianCloud* cloud = nullptr;
    Vec3f fileFromWorld[3];  // rows of the inverse of the linear part of worldFromFile
  };
  std::vector<Set> sets_;
  uint32_t count_ = 0;
};

// A ray's splats, composited: colour = sum_i c_i a_i T_i (display values), the transmittance T
// left after them, and how many Gaussians it blended. As 3DGS's rasteriser, the walk stops at
// the first Gaussian that would bring T below kMinTransmittance, without it; `opaque` then
// says that what lies behind is not worth shading (it adds at most T < 1e-4 of its value).
struct SplatBlend {
  Vec3f colour{0.0f};
  float transmittance = 1.0f;
  bool opaque = false;
  uint32_t blended = 0;
  uint64_t evaluated = 0;  // responses the walk evaluated
};

// The k-buffer's size: the Gaussians a query gathers before the walk blends them and goes on.
inline constexpr int kSplatBatch = 64;

// The splats along `ray` within [ray.tMin, ray.tMax) (tMax: the opaque surface's hit).
SplatBlend blendSplats(const Accelerator& accelerator, const SplatColours& colours, const Ray& ray);
// The same for the active lanes of a packet, walked together (Accelerator::nextSplats16):
// blends[lane] is what blendSplats gives for rays.ray(lane).
void blendSplats16(const Accelerator& accelerator, const SplatColours& colours,
                   const RayPacket16& rays, SplatBlend blends[16]);

// The pixel's linear value when `blend` lies over something of linear radiance `behind`: the
// display values composited, C + T encode(behind), taken back to linear light (the film's
// values). One opaque Gaussian's pixel then has its file's colour exactly.
Vec3f overBehind(const SplatBlend& blend, const Vec3f& behind);

}  // namespace parallax
