#include "parallax/scene/motion.h"

#include <algorithm>
#include <cmath>

#include "parallax/core/transform.h"

namespace parallax {

namespace {

// Meshes that are area lights stay put on a turntable, like the rest of the lighting.
std::vector<bool> lightMeshes(const Scene& scene) {
  std::vector<bool> isLight(scene.meshes.size(), false);
  for (const Light& light : scene.lights)
    if (light.kind == Light::Kind::Mesh && light.mesh >= 0 &&
        size_t(light.mesh) < scene.meshes.size())
      isLight[size_t(light.mesh)] = true;
  return isLight;
}

// worldFromRest of the turntable at `seconds`: a rotation about the axis through the pivot.
Transform turntableAt(const Turntable& t, double seconds) {
  const auto degrees = float(std::fmod(t.degreesPerSecond * seconds, 360.0));
  return Transform::translate(t.pivot) * Transform::rotate(degrees, t.axis) *
         Transform::translate(-t.pivot);
}

// The two keys around `seconds` and the weight of the second, keys sorted by time.
template <class Key>
void bracket(const std::vector<Key>& keys, double seconds, size_t& a, size_t& b, float& w) {
  const auto after = std::upper_bound(keys.begin(), keys.end(), seconds,
                                      [](double s, const Key& k) { return s < k.seconds; });
  b = size_t(after - keys.begin());
  if (b == 0) {
    a = b = 0, w = 0;
    return;
  }
  if (b == keys.size()) {
    a = b = keys.size() - 1, w = 0;
    return;
  }
  a = b - 1;
  const double span = keys[b].seconds - keys[a].seconds;
  w = span > 0 ? float((seconds - keys[a].seconds) / span) : 1.0f;
}

Vec3f lerp(const Vec3f& p, const Vec3f& q, float w) {
  return p * (1.0f - w) + q * w;
}

// Normalised linear interpolation, falling back to `p` where the two are opposite.
Vec3f nlerp(const Vec3f& p, const Vec3f& q, float w) {
  const Vec3f v = lerp(p, q, w);
  const float len = length(v);
  return len > 1e-6f ? v / len : p;
}

}  // namespace

double SceneMotion::keyedSeconds() const {
  double last = 0;
  if (!cameraKeys.empty()) last = std::max(last, cameraKeys.back().seconds);
  if (!displayKeys.empty()) last = std::max(last, displayKeys.back().seconds);
  return last;
}

SceneMotion sceneMotion(const Scene& scene) {
  SceneMotion motion;
  motion.cameraKeys = scene.cameraKeys;
  motion.displayKeys = scene.displayKeys;
  return motion;
}

Turntable contentTurntable(const Scene& scene, double degreesPerSecond) {
  const Bounds3f box = scene.display.content ? *scene.display.content
                       : scene.display.fit   ? *scene.display.fit
                                             : scene.bounds();
  Turntable t;
  t.pivot = box.lo.x <= box.hi.x ? (box.lo + box.hi) * 0.5f : Vec3f(0.0f);
  t.axis = normalize(scene.display.up);
  t.degreesPerSecond = degreesPerSecond;
  return t;
}

CameraSpec cameraAt(const std::vector<CameraKey>& keys, double seconds) {
  if (keys.empty()) return {};
  size_t a, b;
  float w;
  bracket(keys, seconds, a, b, w);
  const CameraSpec &p = keys[a].camera, &q = keys[b].camera;
  CameraSpec c;
  c.eye = lerp(p.eye, q.eye, w);
  c.lookAt = lerp(p.lookAt, q.lookAt, w);
  c.up = nlerp(p.up, q.up, w);
  c.fovDegrees = p.fovDegrees * (1.0f - w) + q.fovDegrees * w;
  return c;
}

DisplayKey displayAt(const std::vector<DisplayKey>& keys, double seconds) {
  if (keys.empty()) return {};
  size_t a, b;
  float w;
  bracket(keys, seconds, a, b, w);
  DisplayKey d;
  d.seconds = seconds;
  d.center = lerp(keys[a].center, keys[b].center, w);
  d.normal = nlerp(normalize(keys[a].normal), normalize(keys[b].normal), w);
  const Vec3f up = nlerp(normalize(keys[a].up), normalize(keys[b].up), w);
  // Gram-Schmidt: the placement's up must be perpendicular to its normal.
  const Vec3f perpendicular = up - d.normal * dot(up, d.normal);
  d.up = length(perpendicular) > 1e-6f ? normalize(perpendicular) : up;
  return d;
}

void poseScene(const Scene& rest, const SceneMotion& motion, double seconds, Scene& posed) {
  if (motion.turntable) {
    const Transform worldFromRest = turntableAt(*motion.turntable, seconds);
    const std::vector<bool> isLight = lightMeshes(rest);
    for (size_t m = 0; m < rest.meshes.size(); ++m) {
      if (isLight[m]) continue;
      const TriangleMesh& from = rest.meshes[m];
      TriangleMesh& to = posed.meshes[m];
      for (size_t i = 0; i < from.positions.size(); ++i)
        to.positions[i] = worldFromRest.point(from.positions[i]);
      // A rotation keeps lengths: the normals stay unit without renormalising.
      for (size_t i = 0; i < from.normals.size(); ++i)
        to.normals[i] = worldFromRest.vector(from.normals[i]);
    }
    for (size_t s = 0; s < rest.spheres.size(); ++s)
      posed.spheres[s].center = worldFromRest.point(rest.spheres[s].center);
  }
  if (!motion.cameraKeys.empty()) posed.camera = cameraAt(motion.cameraKeys, seconds);
  if (!motion.displayKeys.empty()) {
    const DisplayKey d = displayAt(motion.displayKeys, seconds);
    posed.display.center = d.center;
    posed.display.normal = d.normal;
    posed.display.up = d.up;
  }
}

Bounds3f movedBounds(const Scene& rest, const SceneMotion& motion, const Bounds3f& restBox,
                     const std::vector<double>& times) {
  if (!motion.turntable) return restBox;
  // A little slack so that vertices on the box's faces count as inside it.
  const Vec3f slack = (restBox.hi - restBox.lo) * 1e-5f + Vec3f(1e-6f);
  const Bounds3f box{restBox.lo - slack, restBox.hi + slack};
  const auto inside = [&box](const Vec3f& p) {
    return p.x >= box.lo.x && p.y >= box.lo.y && p.z >= box.lo.z && p.x <= box.hi.x &&
           p.y <= box.hi.y && p.z <= box.hi.z;
  };
  const std::vector<bool> isLight = lightMeshes(rest);
  Bounds3f moved;
  for (double seconds : times) {
    const Transform worldFromRest = turntableAt(*motion.turntable, seconds);
    for (size_t m = 0; m < rest.meshes.size(); ++m)
      for (const Vec3f& p : rest.meshes[m].positions)
        if (inside(p)) moved.extend(isLight[m] ? p : worldFromRest.point(p));
    for (const Sphere& s : rest.spheres)
      if (inside(s.center)) {
        const Vec3f c = worldFromRest.point(s.center);
        moved.extend(c - Vec3f(s.radius));
        moved.extend(c + Vec3f(s.radius));
      }
  }
  return moved.lo.x <= moved.hi.x ? moved : restBox;
}

}  // namespace parallax
