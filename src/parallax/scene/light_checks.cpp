#include "parallax/scene/light_checks.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace parallax {
namespace {

// Every object the light could shine on, as a box, except the light's own surface.
std::vector<Bounds3f> objectBounds(const Scene& scene, int ownMesh) {
  std::vector<Bounds3f> boxes;
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    if (int(i) == ownMesh) continue;
    Bounds3f b;
    for (const Vec3f& p : scene.meshes[i].positions) b.extend(p);
    if (!b.empty()) boxes.push_back(b);
  }
  for (const Sphere& s : scene.spheres) {
    Bounds3f b;
    b.extend(s.center - Vec3f(s.radius));
    b.extend(s.center + Vec3f(s.radius));
    boxes.push_back(b);
  }
  return boxes;
}

Vec3f boxCorner(const Bounds3f& b, int i) {
  return {i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z};
}

// Some corner of `b` lies strictly in front of the plane through `p` with normal `n`; a box
// with no such corner lies wholly behind the plane (the plane's half-space is convex).
bool inFront(const Bounds3f& b, const Vec3f& p, const Vec3f& n) {
  // A tolerance relative to the box's size keeps objects touching the plane (a lamp set into a
  // ceiling) from counting as lit.
  const float tolerance = 1e-5f * (1.0f + maxComponent(b.diagonal()));
  for (int i = 0; i < 8; ++i)
    if (dot(boxCorner(b, i) - p, n) > tolerance * length(n)) return true;
  return false;
}

// The triangles (corner, edge, edge) a one-sided area light emits from.
std::vector<std::array<Vec3f, 3>> emitters(const Scene& scene, const Light& light) {
  std::vector<std::array<Vec3f, 3>> triangles;
  if (light.kind == Light::Kind::Quad) {
    triangles.push_back({light.corner, light.edgeU, light.edgeV});
  } else if (light.mesh >= 0 && size_t(light.mesh) < scene.meshes.size()) {
    const TriangleMesh& m = scene.meshes[size_t(light.mesh)];
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
      const Vec3f a = m.positions[m.indices[t]];
      triangles.push_back(
          {a, m.positions[m.indices[t + 1]] - a, m.positions[m.indices[t + 2]] - a});
    }
  }
  return triangles;
}

// Whether some point of `box` may lie within the spot's outer cone. A sphere of radius r
// whose centre is d away, at angle a from the axis, lies wholly outside the cone if
// a - asin(r / d) > outer; a box's bounding sphere is loose (a flat floor under the lamp holds
// the lamp in its sphere), so a box that the test cannot rule out is split into eight, down
// to `depth` levels. Conservative: it never rules out a box the cone reaches.
constexpr int kConeDepth = 5;
bool coneMayReach(const Light& spot, const Bounds3f& box, int depth) {
  const Vec3f toCenter = box.center() - spot.position;
  const float d = length(toCenter);
  const float r = 0.5f * length(box.diagonal());
  if (d > r) {
    const float cosAxis = std::clamp(dot(toCenter, spot.direction) / d, -1.0f, 1.0f);
    if (std::acos(cosAxis) - std::asin(r / d) > spot.outerCone) return false;
  }
  if (depth == 0) return true;
  const Vec3f mid = box.center();
  for (int i = 0; i < 8; ++i) {
    Bounds3f child;
    child.extend(boxCorner(box, i));
    child.extend(mid);
    if (coneMayReach(spot, child, depth - 1)) return true;
  }
  return false;
}

std::string describe(const Scene& scene, const Light& light, size_t index) {
  std::string name = "light " + std::to_string(index);
  if (light.mesh >= 0 && size_t(light.mesh) < scene.meshes.size())
    name += " ('" + scene.meshes[size_t(light.mesh)].name + "')";
  return name;
}

}  // namespace

std::vector<std::string> lightFacingWarnings(const Scene& scene) {
  std::vector<std::string> warnings;
  for (size_t index = 0; index < scene.lights.size(); ++index) {
    const Light& light = scene.lights[index];
    const bool area = light.kind == Light::Kind::Quad || light.kind == Light::Kind::Mesh;
    if (area && !light.twoSided) {
      const std::vector<Bounds3f> boxes = objectBounds(scene, light.mesh);
      const auto triangles = emitters(scene, light);
      if (boxes.empty() || triangles.empty()) continue;
      // Lit if some object has a corner in front of some emitting triangle's plane.
      const bool reaches = std::any_of(triangles.begin(), triangles.end(), [&](const auto& t) {
        const Vec3f n = cross(t[1], t[2]);
        if (!(length(n) > 0)) return false;
        return std::any_of(boxes.begin(), boxes.end(),
                           [&](const Bounds3f& b) { return inFront(b, t[0], n); });
      });
      if (!reaches)
        warnings.push_back(describe(scene, light, index) +
                           " emits from its front face, and everything else in the scene lies "
                           "behind it: it lights nothing (flip its normals or make it two-sided)");
    } else if (light.kind == Light::Kind::Spot) {
      const std::vector<Bounds3f> boxes = objectBounds(scene, -1);
      if (boxes.empty()) continue;
      const bool reaches = std::any_of(boxes.begin(), boxes.end(), [&](const Bounds3f& b) {
        return coneMayReach(light, b, kConeDepth);
      });
      if (!reaches)
        warnings.push_back(describe(scene, light, index) +
                           " (a spot) points away from everything "
                           "in the scene: no object lies within its cone");
    }
  }
  return warnings;
}

}  // namespace parallax
