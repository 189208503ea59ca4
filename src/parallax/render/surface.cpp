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
      const auto& n = g.mesh->normals;
      const auto& idx = g.mesh->indices;
      for (size_t t = 0; !n.empty() && t + 2 < idx.size() && !g.smoothNormals; t += 3)
        g.smoothNormals = !(n[idx[t]] == n[idx[t + 1]] && n[idx[t]] == n[idx[t + 2]]);
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
    if (g.smoothNormals) {
      const Vec3f n =
          mesh.normals[tri[0]] * w0 + mesh.normals[tri[1]] * hit.u + mesh.normals[tri[2]] * hit.v;
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
    if (g.texture)
      uv = {0.5f + std::atan2(ng.z, ng.x) / (2.0f * kPi), 0.5f + std::asin(ng.y) / kPi};
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

// The same as evaluate() for a whole packet, reading the SoA packets directly: the lane-wise
// arithmetic runs as SIMD loops, only the per-object lookups are scalar.
void SurfaceShader::evaluate16(const RayPacket16& rays, const HitPacket16& hits,
                               SurfacePacket16& out, Color16& emitted) const {
  out = SurfacePacket16{};  // lanes without a hit stay zero, so lane loops can skip masks
  {
    // Local copies tell the compiler that nothing aliases, so the loop becomes SIMD.
    alignas(64) float t[16], ngx[16], ngy[16], ngz[16];
    alignas(64) int32_t hit[16];
    for (int i = 0; i < 16; ++i) {
      hit[i] = rays.active[i] != 0 && hits.geometry[i] != kNoHit ? 1 : 0;
      t[i] = hits.t[i], ngx[i] = hits.ngx[i], ngy[i] = hits.ngy[i], ngz[i] = hits.ngz[i];
    }
    alignas(64) float px[16], py[16], pz[16], gx[16], gy[16], gz[16];
    for (int i = 0; i < 16; ++i) {
      const float ti = hit[i] ? t[i] : 0.0f;
      px[i] = rays.ox[i] + rays.dx[i] * ti;
      py[i] = rays.oy[i] + rays.dy[i] * ti;
      pz[i] = rays.oz[i] + rays.dz[i] * ti;
      const float len2 = ngx[i] * ngx[i] + ngy[i] * ngy[i] + ngz[i] * ngz[i];
      const float inv = hit[i] && len2 > 0.0f ? 1.0f / std::sqrt(len2) : 0.0f;
      gx[i] = ngx[i] * inv, gy[i] = ngy[i] * inv, gz[i] = ngz[i] * inv;
    }
    for (int i = 0; i < 16; ++i) {
      out.hit[i] = hit[i];
      out.px[i] = px[i], out.py[i] = py[i], out.pz[i] = pz[i];
      out.gx[i] = out.nx[i] = gx[i];
      out.gy[i] = out.ny[i] = gy[i];
      out.gz[i] = out.nz[i] = gz[i];
    }
  }
  int32_t front[16] = {};
  for (int i = 0; i < 16; ++i) {
    if (!out.hit[i]) continue;
    const Geometry& g = geometries_[hits.geometry[i]];
    const Vec3f position{out.px[i], out.py[i], out.pz[i]};
    Vec2f uv{hits.u[i], hits.v[i]};
    if (g.mesh) {
      const TriangleMesh& mesh = *g.mesh;
      const uint32_t* tri = &mesh.indices[size_t(hits.primitive[i]) * 3];
      const float b1 = hits.u[i], b2 = hits.v[i], b0 = 1.0f - b1 - b2;
      if (g.smoothNormals) {
        const Vec3f n =
            mesh.normals[tri[0]] * b0 + mesh.normals[tri[1]] * b1 + mesh.normals[tri[2]] * b2;
        const float len2 = dot(n, n);
        if (len2 > 0.0f) {
          const float inv = 1.0f / std::sqrt(len2);
          out.nx[i] = n.x * inv, out.ny[i] = n.y * inv, out.nz[i] = n.z * inv;
        }
      }
      if (!mesh.uvs.empty() && g.texture) {
        const Vec2f a = mesh.uvs[tri[0]], b = mesh.uvs[tri[1]], c = mesh.uvs[tri[2]];
        uv = {a.x * b0 + b.x * b1 + c.x * b2, a.y * b0 + b.y * b1 + c.y * b2};
      }
    } else {
      const Vec3f n = normalize(position - g.sphere->center);
      out.gx[i] = out.nx[i] = n.x, out.gy[i] = out.ny[i] = n.y, out.gz[i] = out.nz[i] = n.z;
      if (g.texture) uv = {0.5f + std::atan2(n.z, n.x) / (2.0f * kPi), 0.5f + std::asin(n.y) / kPi};
    }
    const Material& material = *g.material;
    Vec3f albedo = material.diffuse;
    if (g.texture) albedo = albedo * evaluateTexture(scene_, *g.texture, position, uv);
    out.mirror.set(i, material.mirror);
    out.diffuse.set(i, albedo * (Vec3f(1.0f) - material.mirror));
    front[i] = out.gx[i] * rays.dx[i] + out.gy[i] * rays.dy[i] + out.gz[i] * rays.dz[i] < 0.0f;
    if (front[i]) {
      emitted.r[i] += material.emission.x, emitted.g[i] += material.emission.y;
      emitted.b[i] += material.emission.z;
    }
  }
  // Both normals onto the side the ray came from.
  for (int i = 0; i < 16; ++i) {
    const float gs = out.hit[i] && !front[i] ? -1.0f : 1.0f;
    out.gx[i] *= gs, out.gy[i] *= gs, out.gz[i] *= gs;
    const float ns =
        out.nx[i] * out.gx[i] + out.ny[i] * out.gy[i] + out.nz[i] * out.gz[i] < 0.0f ? -1.0f : 1.0f;
    out.nx[i] *= ns, out.ny[i] *= ns, out.nz[i] *= ns;
    out.shade[i] = out.hit[i] &&
                   (out.diffuse.r[i] > 0.0f || out.diffuse.g[i] > 0.0f || out.diffuse.b[i] > 0.0f);
  }
}

}  // namespace parallax
