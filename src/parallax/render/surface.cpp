#include "parallax/render/surface.h"

#include "parallax/core/lane_kernel.h"

#include <bit>
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
      g.colors = g.mesh->colors.size() == g.mesh->positions.size() && !g.mesh->colors.empty();
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
  Vec3f vertexColor(1.0f);
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
    // Vertex colours, interpolated like the normals: c = w0 c0 + u c1 + v c2.
    if (g.colors)
      vertexColor =
          mesh.colors[tri[0]] * w0 + mesh.colors[tri[1]] * hit.u + mesh.colors[tri[2]] * hit.v;
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
  Vec3f albedo = material.diffuse * vertexColor;
  if (g.texture) albedo = albedo * evaluateTexture(scene_, *g.texture, sp.position, uv);
  sp.mirror = material.mirror;
  sp.diffuse = albedo * (Vec3f(1.0f) - material.mirror);
  if (frontFace) sp.emission = material.emission;
  return sp;
}

// The same as evaluate() for a whole packet, reading the SoA packets directly. The arithmetic
// runs as SIMD loops over the lanes; the scalar loop only looks up each hit's object and
// material, and does the rarer work (spheres, smooth normals, image textures) lane by lane.
PARALLAX_LANE_KERNEL void SurfaceShader::evaluate16(const RayPacket16& rays,
                                                    const HitPacket16& hits, SurfacePacket16& out,
                                                    Color16& emitted) const {
  // Local arrays tell the compiler that nothing aliases, so the lane loops vectorise; the
  // conditions use & and | (no short-circuit branches) for the same reason.
  alignas(64) int32_t hit[16];
  alignas(64) float px[16], py[16], pz[16], gx[16], gy[16], gz[16], nx[16], ny[16], nz[16];
  PARALLAX_SIMD
  for (int i = 0; i < 16; ++i) {
    hit[i] = int32_t(rays.active[i] != 0) & int32_t(hits.geometry[i] != kNoHit);
    const float t = hit[i] != 0 ? hits.t[i] : 0.0f;
    px[i] = rays.ox[i] + rays.dx[i] * t;
    py[i] = rays.oy[i] + rays.dy[i] * t;
    pz[i] = rays.oz[i] + rays.dz[i] * t;
    const float len2 =
        hits.ngx[i] * hits.ngx[i] + hits.ngy[i] * hits.ngy[i] + hits.ngz[i] * hits.ngz[i];
    const float inv = ((hit[i] != 0) & (len2 > 0.0f)) ? 1.0f / std::sqrt(len2) : 0.0f;
    nx[i] = gx[i] = hits.ngx[i] * inv;
    ny[i] = gy[i] = hits.ngy[i] * inv;
    nz[i] = gz[i] = hits.ngz[i] * inv;
  }

  // Material terms per lane. Lanes mostly share their object, so each distinct object is
  // looked up once and its terms are written to all its lanes by a masked SIMD loop (a solid
  // checkerboard evaluated there too); only spheres, smooth normals and image textures need
  // per-lane scalar work. `diffuse` is albedo * (1 - mirror) from the start: the texture, a
  // factor of the albedo, multiplies it afterwards.
  alignas(64) float diffuse[3][16] = {}, mirror[3][16] = {}, emission[3][16] = {};
  alignas(64) int32_t geometry[16];
  for (int i = 0; i < 16; ++i) geometry[i] = hit[i] ? int32_t(hits.geometry[i]) : -1;
  uint32_t pending = 0;
  for (int i = 0; i < 16; ++i) pending |= hit[i] ? 1u << i : 0u;
  while (pending != 0) {
    const int first = std::countr_zero(pending);
    const int32_t id = geometry[first];
    const Geometry& g = geometries_[size_t(id)];
    const Material& m = *g.material;
    const bool isChecker = g.texture && g.texture->kind == Texture::Kind::Checker;
    // Plain scalars, so that the loops below broadcast them (members read in a loop kept it
    // scalar).
    const float d0 = m.diffuse.x * (1.0f - m.mirror.x), d1 = m.diffuse.y * (1.0f - m.mirror.y),
                d2 = m.diffuse.z * (1.0f - m.mirror.z);
    const float m0 = m.mirror.x, m1 = m.mirror.y, m2 = m.mirror.z;
    const float e0 = m.emission.x, e1 = m.emission.y, e2 = m.emission.z;
    if (isChecker) {
      // evaluateTexture's Checker case for these lanes: the parity of the cell sum, in floats
      // so that the loop stays SIMD (exact for cell indices below 2^24); blend weights instead
      // of branches, odd squares taking colour B and even ones colour A.
      const Texture& t = *g.texture;
      const float k = 1.0f / t.checkerSize;
      const float a0 = t.color.x, a1 = t.color.y, a2 = t.color.z;
      const float b0 = t.color2.x, b1 = t.color2.y, b2 = t.color2.z;
      PARALLAX_SIMD
      for (int i = 0; i < 16; ++i) {
        const bool mine = geometry[i] == id;
        const float cells = std::floor(px[i] * k + 1e-3f) + std::floor(py[i] * k + 1e-3f) +
                            std::floor(pz[i] * k + 1e-3f);
        const float odd = cells - 2.0f * std::floor(0.5f * cells), even = 1.0f - odd;
        diffuse[0][i] = mine ? d0 * (odd * b0 + even * a0) : diffuse[0][i];
        diffuse[1][i] = mine ? d1 * (odd * b1 + even * a1) : diffuse[1][i];
        diffuse[2][i] = mine ? d2 * (odd * b2 + even * a2) : diffuse[2][i];
      }
    } else {
      PARALLAX_SIMD
      for (int i = 0; i < 16; ++i) {
        const bool mine = geometry[i] == id;
        diffuse[0][i] = mine ? d0 : diffuse[0][i];
        diffuse[1][i] = mine ? d1 : diffuse[1][i];
        diffuse[2][i] = mine ? d2 : diffuse[2][i];
      }
    }
    // Most materials neither reflect nor emit: their lanes keep the zeros.
    if (m0 != 0.0f || m1 != 0.0f || m2 != 0.0f || e0 != 0.0f || e1 != 0.0f || e2 != 0.0f) {
      PARALLAX_SIMD
      for (int i = 0; i < 16; ++i) {
        const bool mine = geometry[i] == id;
        mirror[0][i] = mine ? m0 : mirror[0][i];
        mirror[1][i] = mine ? m1 : mirror[1][i];
        mirror[2][i] = mine ? m2 : mirror[2][i];
        emission[0][i] = mine ? e0 : emission[0][i];
        emission[1][i] = mine ? e1 : emission[1][i];
        emission[2][i] = mine ? e2 : emission[2][i];
      }
    }
    uint32_t done = 0;
    for (int i = 0; i < 16; ++i) done |= geometry[i] == id ? 1u << i : 0u;
    pending &= ~done;
    if (!g.sphere && !g.smoothNormals && !g.colors && (!g.texture || isChecker)) continue;
    for (int i = first; i < 16; ++i) {
      if (geometry[i] != id) continue;
      if (g.sphere) {
        const Vec3f n = normalize(Vec3f{px[i], py[i], pz[i]} - g.sphere->center);
        gx[i] = nx[i] = n.x, gy[i] = ny[i] = n.y, gz[i] = nz[i] = n.z;
      }
      const uint32_t* tri = g.mesh ? &g.mesh->indices[size_t(hits.primitive[i]) * 3] : nullptr;
      const float b1 = hits.u[i], b2 = hits.v[i], b0 = 1.0f - b1 - b2;
      if (g.smoothNormals) {
        const auto& normals = g.mesh->normals;
        const Vec3f n = normals[tri[0]] * b0 + normals[tri[1]] * b1 + normals[tri[2]] * b2;
        const float len2 = dot(n, n);
        if (len2 > 0.0f) {
          const float inv = 1.0f / std::sqrt(len2);
          nx[i] = n.x * inv, ny[i] = n.y * inv, nz[i] = n.z * inv;
        }
      }
      if (g.colors) {
        const auto& colors = g.mesh->colors;
        const Vec3f c = colors[tri[0]] * b0 + colors[tri[1]] * b1 + colors[tri[2]] * b2;
        for (int k = 0; k < 3; ++k) diffuse[k][i] *= c[k];
      }
      if (!g.texture || isChecker) continue;
      Vec2f uv{b1, b2};
      if (g.sphere) {
        uv = {0.5f + std::atan2(gz[i], gx[i]) / (2.0f * kPi), 0.5f + std::asin(gy[i]) / kPi};
      } else if (!g.mesh->uvs.empty()) {
        const Vec2f ua = g.mesh->uvs[tri[0]], ub = g.mesh->uvs[tri[1]], uc = g.mesh->uvs[tri[2]];
        uv = {ua.x * b0 + ub.x * b1 + uc.x * b2, ua.y * b0 + ub.y * b1 + uc.y * b2};
      }
      const Vec3f tex = evaluateTexture(scene_, *g.texture, {px[i], py[i], pz[i]}, uv);
      for (int c = 0; c < 3; ++c) diffuse[c][i] *= tex[c];
    }
  }

  // Both normals onto the side the ray came from, and emission from front faces only.
  alignas(64) float frontFace[16];
  PARALLAX_SIMD
  for (int i = 0; i < 16; ++i) {
    const float facing = gx[i] * rays.dx[i] + gy[i] * rays.dy[i] + gz[i] * rays.dz[i];
    frontFace[i] = facing < 0.0f ? 1.0f : 0.0f;
    const float gs = facing < 0.0f ? 1.0f : -1.0f;
    gx[i] *= gs, gy[i] *= gs, gz[i] *= gs;
    const float ns = nx[i] * gx[i] + ny[i] * gy[i] + nz[i] * gz[i] < 0.0f ? -1.0f : 1.0f;
    nx[i] *= ns, ny[i] *= ns, nz[i] *= ns;
  }
  PARALLAX_SIMD
  for (int i = 0; i < 16; ++i) {
    out.hit[i] = hit[i];
    out.px[i] = px[i], out.py[i] = py[i], out.pz[i] = pz[i];
    out.gx[i] = gx[i], out.gy[i] = gy[i], out.gz[i] = gz[i];
    out.nx[i] = nx[i], out.ny[i] = ny[i], out.nz[i] = nz[i];
    const float dr = diffuse[0][i], dg = diffuse[1][i], db = diffuse[2][i];
    out.diffuse.r[i] = dr, out.diffuse.g[i] = dg, out.diffuse.b[i] = db;
    out.mirror.r[i] = mirror[0][i], out.mirror.g[i] = mirror[1][i], out.mirror.b[i] = mirror[2][i];
    out.shade[i] = hit[i] & int32_t((dr > 0.0f) | (dg > 0.0f) | (db > 0.0f));
    emitted.r[i] += frontFace[i] * emission[0][i];
    emitted.g[i] += frontFace[i] * emission[1][i];
    emitted.b[i] += frontFace[i] * emission[2][i];
  }
}

}  // namespace parallax
