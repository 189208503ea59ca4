// Sampling points on the scene's lights for direct illumination with shadow rays.
#pragma once

#include <vector>

#include "parallax/core/math.h"
#include "parallax/render/packet_types.h"
#include "parallax/scene/scene.h"

namespace parallax {

// One light sample as seen from a shading point: the unoccluded irradiance it delivers
// (already divided by the sample's pdf and weighted by the receiver's cosine) and the segment a
// shadow ray must test. `toLight` is unnormalised: the light point is origin + toLight * 1.
struct LightSample {
  Vec3f irradiance{0.0f};
  Vec3f toLight;
  float tMax = 0.0f;  // just short of the light point; infinity for directional lights
  bool valid = false;
};

// KHR_lights_punctual's spot falloff (the extension's README, "Spot"): with
// scale = 1 / max(0.001, cos(inner) - cos(outer)) and offset = -cos(outer) * scale, the
// intensity factor at angle theta from the axis is clamp(cos(theta) * scale + offset, 0, 1)^2.
float spotAttenuation(float cosTheta, float innerCone, float outerCone);

class LightSampler {
 public:
  explicit LightSampler(const Scene& scene);

  size_t lightCount() const { return lights_.size(); }
  int samplesFor(size_t light) const { return lights_[light].samples; }
  // How many of a sample's uniform numbers (u1, u2, u3) `light` reads: 0 for point, spot and
  // directional lights, 2 for quads, 3 for meshes (the triangle, then the point on it).
  int uniformsFor(size_t light) const;
  // A sample of `light` for the point `p` with unit normal `n`; (u1, u2, u3) uniform in [0,1).
  LightSample sample(size_t light, const Vec3f& p, const Vec3f& n, float u1, float u2,
                     float u3) const;
  // Samples of `light` for the shading lanes of a packet, with uniform numbers u1..u3 per lane.
  void sample16(size_t light, const SurfacePacket16& surfaces, const float u1[16],
                const float u2[16], const float u3[16], LightPacket16& out) const;
  // A representative point of the first light (for the benchmark's raw limit).
  Vec3f representativePoint(const Vec3f& fallback) const;

 private:
  struct Triangle {
    Vec3f p0, e1, e2, normal;  // normal: unit
    float area;
  };
  struct Entry {
    Light light;
    int samples = 1;
    std::vector<Triangle> triangles;  // Quad: two; Mesh: all of the mesh
    std::vector<float> cdf;           // cumulative area
    float totalArea = 0.0f;
  };
  static LightSample areaSample(const Entry& e, const Vec3f& p, const Vec3f& n, const Vec3f& q,
                                const Vec3f& lightNormal);
  std::vector<Entry> lights_;
};

}  // namespace parallax
