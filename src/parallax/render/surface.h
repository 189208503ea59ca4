// What a hit means for shading: position, normals facing the incoming ray, and the material's
// terms at that point (textures evaluated).
#pragma once

#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/render/packet_types.h"
#include "parallax/scene/scene.h"

namespace parallax {

struct SurfacePoint {
  Vec3f position;
  Vec3f geometricNormal;  // unit, on the side the ray came from
  Vec3f shadingNormal;    // unit, interpolated vertex normal, same side as geometricNormal
  Vec3f diffuse{0.0f};    // albedo times (1 - mirror)
  Vec3f mirror{0.0f};
  Vec3f emission{0.0f};  // only if the ray hit the emitting (front) face
};

// Turns hits into surface points. Built once per render: it resolves every Embree geometry to
// its mesh or sphere, material and texture up front, so that shading a hit is a table lookup.
class SurfaceShader {
 public:
  SurfaceShader(const Scene& scene, const Accelerator& accelerator);
  SurfacePoint evaluate(const Ray& ray, const Hit& hit) const;
  // All hits of a packet at once; emission seen by each ray is added to `emitted`.
  void evaluate16(const RayPacket16& rays, const HitPacket16& hits, SurfacePacket16& out,
                  Color16& emitted) const;

 private:
  struct Geometry {
    const TriangleMesh* mesh = nullptr;
    const Sphere* sphere = nullptr;
    const Material* material = nullptr;
    const Texture* texture = nullptr;
    // The mesh has vertex normals that differ within some triangle; flat-shaded meshes (every
    // triangle's three normals equal) use the geometric normal and skip the interpolation.
    bool smoothNormals = false;
    bool colors = false;  // the mesh has vertex colours (multiplied into the albedo)
  };
  const Scene& scene_;
  std::vector<Geometry> geometries_;
};

// The texture's colour at a world position with surface coordinates uv.
Vec3f evaluateTexture(const Scene& scene, const Texture& texture, const Vec3f& position,
                      const Vec2f& uv);

// A point just off the surface on the side of `normal`, far enough to avoid self-hits at the
// magnitude of `p` (floating-point error grows with it).
inline Vec3f offsetAlong(const Vec3f& p, const Vec3f& normal) {
  const float scale = 1.0f + std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z)));
  return p + normal * (2e-4f * scale);
}

}  // namespace parallax
