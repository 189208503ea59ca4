#include "parallax/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "parallax/core/transform.h"

namespace parallax {

size_t Scene::triangleCount() const {
  size_t n = 0;
  for (const auto& m : meshes) n += m.triangleCount();
  return n;
}

size_t Scene::splatCount() const {
  size_t n = 0;
  for (const SplatSet& set : splats) n += set.cloud.size();
  return n;
}

namespace {

// The meshes' and spheres' bounds with each splat set's `splatBounds`.
Bounds3f boundsWith(const Scene& scene, Bounds3f (*splatBounds)(const SplatSet&)) {
  Bounds3f b;
  for (const SplatSet& set : scene.splats) b.extend(splatBounds(set));
  for (const auto& m : scene.meshes)
    for (const auto& p : m.positions) b.extend(p);
  for (const auto& s : scene.spheres) {
    b.extend(s.center - Vec3f(s.radius));
    b.extend(s.center + Vec3f(s.radius));
  }
  return b;
}

}  // namespace

Bounds3f Scene::framingBounds() const {
  return boundsWith(*this, splatFramingBounds);
}

Bounds3f Scene::bounds() const {
  return boundsWith(*this, splatCentreBounds);
}

namespace {
// Double-precision vector arithmetic for the one-ray intersection below.
Vec3d sub(const Vec3d& a, const Vec3d& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
double dotD(const Vec3d& a, const Vec3d& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
Vec3d crossD(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Vec3d toDouble(const Vec3f& v) {
  return {v.x, v.y, v.z};
}
}  // namespace

std::optional<float> firstHitDistance(const Scene& scene, const Vec3f& origin,
                                      const Vec3f& direction) {
  // Moller-Trumbore in double precision, both faces, t > 0; spheres by the quadratic's
  // nearer positive root. One ray over every primitive: no acceleration structure needed.
  const Vec3d o = toDouble(origin);
  Vec3d d = toDouble(direction);
  const double norm = std::sqrt(dotD(d, d));
  if (!(norm > 0)) return std::nullopt;
  d = {d.x / norm, d.y / norm, d.z / norm};
  double nearest = std::numeric_limits<double>::infinity();
  for (const TriangleMesh& mesh : scene.meshes)
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const Vec3d a = toDouble(mesh.positions[mesh.indices[t]]);
      const Vec3d e1 = sub(toDouble(mesh.positions[mesh.indices[t + 1]]), a);
      const Vec3d e2 = sub(toDouble(mesh.positions[mesh.indices[t + 2]]), a);
      const Vec3d p = crossD(d, e2);
      const double det = dotD(e1, p);
      if (std::abs(det) < 1e-300) continue;
      const Vec3d s = sub(o, a);
      const double u = dotD(s, p) / det;
      if (u < 0 || u > 1) continue;
      const Vec3d q = crossD(s, e1);
      const double v = dotD(d, q) / det;
      if (v < 0 || u + v > 1) continue;
      const double hit = dotD(e2, q) / det;
      if (hit > 0 && hit < nearest) nearest = hit;
    }
  for (const Sphere& sphere : scene.spheres) {
    const Vec3d oc = sub(o, toDouble(sphere.center));
    const double b = dotD(oc, d), c = dotD(oc, oc) - double(sphere.radius) * sphere.radius;
    const double disc = b * b - c;
    if (disc < 0) continue;
    const double root = std::sqrt(disc);
    for (const double hit : {-b - root, -b + root})
      if (hit > 0) {
        nearest = std::min(nearest, hit);
        break;
      }
  }
  if (!std::isfinite(nearest)) return std::nullopt;
  return float(nearest);
}

void addQuad(Scene& scene, const std::string& name, const Vec3f& corner, const Vec3f& edgeU,
             const Vec3f& edgeV, uint32_t material) {
  TriangleMesh mesh;
  mesh.name = name;
  mesh.material = material;
  mesh.positions = {corner, corner + edgeU, corner + edgeU + edgeV, corner + edgeV};
  const Vec3f n = normalize(cross(edgeU, edgeV));
  mesh.normals = {n, n, n, n};
  mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  scene.meshes.push_back(std::move(mesh));
}

void addBox(Scene& scene, const std::string& name, const Vec3f& lo, const Vec3f& hi,
            uint32_t material) {
  TriangleMesh mesh;
  mesh.name = name;
  mesh.material = material;
  const Vec3f size = hi - lo;
  // Each face gets its own four vertices so that normals stay flat. The faces are listed by
  // (corner, edgeU, edgeV) with cross(edgeU, edgeV) pointing outward.
  const Vec3f ex{size.x, 0, 0}, ey{0, size.y, 0}, ez{0, 0, size.z};
  const struct {
    Vec3f corner, u, v;
  } faces[6] = {
      {lo, ey, ex},       // -z
      {lo + ez, ex, ey},  // +z
      {lo, ez, ey},       // -x
      {lo + ex, ey, ez},  // +x
      {lo, ex, ez},       // -y
      {lo + ey, ez, ex},  // +y
  };
  for (const auto& f : faces) {
    const auto base = uint32_t(mesh.positions.size());
    const Vec3f n = normalize(cross(f.u, f.v));
    for (const Vec3f& p : {f.corner, f.corner + f.u, f.corner + f.u + f.v, f.corner + f.v}) {
      mesh.positions.push_back(p);
      mesh.normals.push_back(n);
    }
    mesh.uvs.insert(mesh.uvs.end(), {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
  scene.meshes.push_back(std::move(mesh));
}

Scene defaultScene() {
  Scene scene;
  scene.source = "<built-in>";
  // Scene units: the display is 4 units wide (a 527 mm panel, so 1 unit is about 132 mm),
  // centred at the origin and facing +z. The box floats in the display plane, inside the
  // depth of field of the default display; the floor recedes behind it.
  scene.display = DisplayPlacement{};
  scene.display.width = 4.0f;
  // The box is deeper than the default display's depth of field (-116 to +66 mm against +-27
  // mm): fit its depth into it by default (the framing's Depth mode: the picture as large as
  // the window allows and g' deepened), so that the first picture is sharp. `--fit none` shows
  // it as built.
  scene.display.fitMode = DisplayFit::Depth;

  Texture checker;
  checker.kind = Texture::Kind::Checker;
  checker.color = {0.75f, 0.75f, 0.75f};
  checker.color2 = {0.08f, 0.08f, 0.08f};
  checker.checkerSize = 0.5f;
  scene.textures.push_back(checker);

  Material floor;
  floor.name = "checkerboard";
  floor.diffuse = Vec3f(1.0f);
  floor.diffuseTexture = 0;
  Material box;
  box.name = "box";
  box.diffuse = {0.75f, 0.22f, 0.12f};
  Material lamp;
  lamp.name = "lamp";
  lamp.diffuse = Vec3f(0.0f);
  lamp.emission = Vec3f(60.0f);
  scene.materials = {floor, box, lamp};

  addQuad(scene, "floor", {-6, -1.1f, 1.5f}, {12, 0, 0}, {0, 0, -14}, 0);
  // A box turned 30 degrees about the vertical, levitating well above the floor.
  addBox(scene, "box", {-0.45f, -0.35f, -0.45f}, {0.45f, 0.45f, 0.45f}, 1);
  const Transform turn = Transform::translate({0.1f, 0.0f, -0.2f}) *
                         Transform::rotate(30.0f, {0, 1, 0}) * Transform::rotate(15.0f, {1, 0, 0});
  for (auto& p : scene.meshes.back().positions) p = turn.point(p);
  for (auto& n : scene.meshes.back().normals) n = normalize(turn.normal(n));
  // The framing measures the box (the subject); the floor recedes behind it on purpose.
  scene.display.content = Bounds3f{};
  for (const auto& p : scene.meshes.back().positions) scene.display.content->extend(p);

  // A square area light above and to the left, facing down: soft but clearly visible shadows.
  Light light;
  light.kind = Light::Kind::Quad;
  light.corner = {-2.2f, 3.2f, 0.4f};
  light.edgeU = {0.8f, 0, 0};
  light.edgeV = {0, 0, 0.8f};  // cross(edgeU, edgeV) = -y: emits downward
  light.intensity = lamp.emission;
  addQuad(scene, "lamp", light.corner, light.edgeU, light.edgeV, 2);
  light.mesh = int(scene.meshes.size()) - 1;
  scene.lights.push_back(light);

  scene.ambient = Vec3f(0.04f);
  scene.background = {0.02f, 0.025f, 0.035f};
  scene.camera = CameraSpec{{0.0f, 0.6f, 6.0f}, {0.0f, -0.2f, -0.5f}, {0, 1, 0}, 34.0f};
  return scene;
}

CameraSpec frameScene(const Scene& scene, float fovDegrees) {
  const Bounds3f b = scene.framingBounds();
  CameraSpec camera;
  camera.fovDegrees = fovDegrees;
  if (b.empty()) return camera;
  const Vec3f center = b.center();
  const float radius = std::max(0.5f * length(b.diagonal()), 1e-6f);
  // Distance at which the bounding sphere fits the vertical field of view, with a margin.
  const float halfFov = 0.5f * fovDegrees * kPi / 180.0f;
  const float distance = 1.1f * radius / std::sin(halfFov);
  const Vec3f up = normalize(scene.display.up);
  const Vec3f toViewer = normalize(scene.display.normal);
  // Look slightly down on the object, as a viewer in front of a display would.
  const Vec3f dir = normalize(toViewer + 0.25f * up);
  camera.eye = center + dir * distance;
  camera.lookAt = center;
  camera.up = up;
  return camera;
}

}  // namespace parallax
