#include "parallax/render/surface.h"

#include <cmath>

namespace parallax {

Vec3f evaluateTexture(const Scene& scene, const Texture& texture, const Vec3f& position,
                      const Vec2f& uv) {
  switch (texture.kind) {
    case Texture::Kind::Constant:
      return texture.color;
    case Texture::Kind::Checker: {
      // A solid 3-D checkerboard: squares of checkerSize on any surface, no UVs needed. The
      // small offset keeps surfaces lying exactly on a cell boundary out of the parity flicker.
      const float inv = 1.0f / texture.checkerSize;
      const auto cell = [inv](float c) { return int64_t(std::floor(c * inv + 1e-3f)); };
      const bool odd = ((cell(position.x) + cell(position.y) + cell(position.z)) & 1) != 0;
      return odd ? texture.color2 : texture.color;
    }
    case Texture::Kind::Image:
      if (texture.image < 0 || size_t(texture.image) >= scene.images.size()) return Vec3f(1.0f);
      return scene.images[size_t(texture.image)].sampleBilinear(uv.x, uv.y);
  }
  return Vec3f(1.0f);
}

SurfaceShader::SurfaceShader(const Scene& scene, const Accelerator& accelerator) : scene_(scene) {
  const size_t count = scene.meshes.size() + scene.spheres.size();
  geometries_.resize(count);
  for (uint32_t id = 0; id < count; ++id) {
    Geometry& g = geometries_[id];
    const SurfaceRef ref = accelerator.surface(id);
    if (ref.kind == SurfaceRef::Kind::Mesh) {
      g.mesh = &scene.meshes[ref.index];
      g.material = &scene.materials[g.mesh->material];
    } else {
      g.sphere = &scene.spheres[ref.index];
      g.material = &scene.materials[g.sphere->material];
    }
    if (g.material->diffuseTexture >= 0)
      g.texture = &scene.textures[size_t(g.material->diffuseTexture)];
  }
}

SurfacePoint SurfaceShader::evaluate(const Ray& ray, const Hit& hit) const {
  const Geometry& g = geometries_[hit.geometry];
  SurfacePoint sp;
  sp.position = ray.at(hit.t);
  Vec3f ng = normalize(hit.geometricNormal);
  Vec3f ns = ng;
  Vec2f uv{hit.u, hit.v};
  if (g.mesh) {
    const TriangleMesh& mesh = *g.mesh;
    const uint32_t* tri = &mesh.indices[size_t(hit.primitive) * 3];
    const float w0 = 1.0f - hit.u - hit.v;
    if (!mesh.normals.empty()) {
      const Vec3f n = mesh.normals[tri[0]] * w0 + mesh.normals[tri[1]] * hit.u +
                      mesh.normals[tri[2]] * hit.v;
      const float len2 = dot(n, n);
      if (len2 > 0.0f) ns = n * (1.0f / std::sqrt(len2));
    }
    if (!mesh.uvs.empty() && g.texture) {
      const Vec2f a = mesh.uvs[tri[0]], b = mesh.uvs[tri[1]], c = mesh.uvs[tri[2]];
      uv = {a.x * w0 + b.x * hit.u + c.x * hit.v, a.y * w0 + b.y * hit.u + c.y * hit.v};
    }
  } else {
    ng = normalize(sp.position - g.sphere->center);
    ns = ng;
    // Spherical coordinates as texture coordinates.
    if (g.texture) uv = {0.5f + std::atan2(ng.z, ng.x) / (2.0f * kPi), 0.5f + std::asin(ng.y) / kPi};
  }
  const bool frontFace = dot(ng, ray.direction) < 0.0f;
  if (!frontFace) ng = -ng;
  if (dot(ns, ng) < 0.0f) ns = -ns;
  sp.geometricNormal = ng;
  sp.shadingNormal = ns;

  const Material& material = *g.material;
  Vec3f albedo = material.diffuse;
  if (g.texture) albedo = albedo * evaluateTexture(scene_, *g.texture, sp.position, uv);
  sp.mirror = material.mirror;
  sp.diffuse = albedo * (Vec3f(1.0f) - material.mirror);
  if (frontFace) sp.emission = material.emission;
  return sp;
}

}  // namespace parallax
