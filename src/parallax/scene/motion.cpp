#include "parallax/scene/motion.h"

#include <algorithm>
#include <array>
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

// Quaternion xyzw helpers for glTF rotations.
using Quat = std::array<float, 4>;

Quat slerp(Quat a, const Quat& b, float w) {
  double d = double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2] + double(a[3]) * b[3];
  if (d < 0) {  // the shorter way round: q and -q are one rotation
    for (float& c : a) c = -c;
    d = -d;
  }
  double wa = 1 - w, wb = w;
  if (d < 0.9995) {
    const double angle = std::acos(std::min(1.0, d)), s = std::sin(angle);
    wa = std::sin((1 - w) * angle) / s;
    wb = std::sin(w * angle) / s;
  }
  Quat q;
  double n = 0;
  for (int i = 0; i < 4; ++i) {
    q[size_t(i)] = float(wa * a[size_t(i)] + wb * b[size_t(i)]);
    n += double(q[size_t(i)]) * q[size_t(i)];
  }
  const auto inv = float(1 / std::sqrt(n));
  for (float& c : q) c *= inv;
  return q;
}

// A channel's value at `seconds`: held before the first key and after the last.
std::array<float, 4> channelAt(const NodeChannel& c, double seconds) {
  const auto after = std::upper_bound(c.times.begin(), c.times.end(), float(seconds));
  const size_t b = size_t(after - c.times.begin());
  if (b == 0) return c.values.front();
  if (b == c.times.size() || c.step) return c.values[b - 1];
  const size_t a = b - 1;
  const float span = c.times[b] - c.times[a];
  const float w = span > 0 ? float((seconds - c.times[a]) / span) : 1.0f;
  if (c.path == NodeChannel::Path::Rotation) return slerp(c.values[a], c.values[b], w);
  std::array<float, 4> v{};
  for (size_t i = 0; i < 3; ++i) v[i] = c.values[a][i] * (1 - w) + c.values[b][i] * w;
  return v;
}

// T * R * S of one node at `seconds` (glTF 2.0, "Transformations").
Mat4 localAt(const AnimatedNode& node, double seconds) {
  if (node.matrix && node.channels.empty()) return *node.matrix;
  Vec3f t = node.translation, s = node.scale;
  Quat r = node.rotation;
  for (const NodeChannel& c : node.channels) {
    const std::array<float, 4> v = channelAt(c, seconds);
    if (c.path == NodeChannel::Path::Translation) t = Vec3f(v[0], v[1], v[2]);
    if (c.path == NodeChannel::Path::Scale) s = Vec3f(v[0], v[1], v[2]);
    if (c.path == NodeChannel::Path::Rotation) r = v;
  }
  const float x = r[0], y = r[1], z = r[2], w = r[3];
  const float rot[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                           {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                           {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
  const float scale[3] = {s.x, s.y, s.z}, translation[3] = {t.x, t.y, t.z};
  Mat4 m = Mat4::identity();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m.m[size_t(i)][size_t(j)] = rot[i][j] * scale[j];
    m.m[size_t(i)][3] = translation[i];
  }
  return m;
}

// Each mesh's worldFromRest at `seconds`, or nothing where the mesh does not move: its node
// animation (worldFromFile * fileFromNode(t) * restMeshFromWorld), then the turntable.
std::vector<std::optional<Transform>> meshMoves(const Scene& rest, const SceneMotion& motion,
                                                double seconds) {
  std::vector<std::optional<Transform>> moves(rest.meshes.size());
  for (const AnimatedMesh& a : motion.nodeAnimation.meshes) {
    if (a.mesh >= moves.size()) continue;
    const Mat4 m = a.worldFromFile * fileFromNodeAt(motion.nodeAnimation, a.node, seconds) *
                   a.restMeshFromWorld;
    Mat4 inverse;
    if (invert(m, inverse)) moves[a.mesh] = Transform(m, inverse);
  }
  if (motion.turntable) {
    const Transform turn = turntableAt(*motion.turntable, seconds);
    const std::vector<bool> isLight = lightMeshes(rest);
    for (size_t m = 0; m < moves.size(); ++m)
      if (!isLight[m]) moves[m] = moves[m] ? turn * *moves[m] : turn;
  }
  return moves;
}

}  // namespace

Mat4 fileFromNodeAt(const NodeAnimation& animation, int node, double seconds) {
  Mat4 m = Mat4::identity();
  // Up the tree; kMaxDepth guards against a cycle a loader let through.
  constexpr int kMaxDepth = 4096;
  for (int depth = 0; node >= 0 && size_t(node) < animation.nodes.size() && depth < kMaxDepth;
       ++depth) {
    m = localAt(animation.nodes[size_t(node)], seconds) * m;
    node = animation.nodes[size_t(node)].parent;
  }
  return m;
}

double SceneMotion::keyedSeconds() const {
  double last = 0;
  if (!cameraKeys.empty()) last = std::max(last, cameraKeys.back().seconds);
  if (!displayKeys.empty()) last = std::max(last, displayKeys.back().seconds);
  if (!nodeAnimation.empty()) last = std::max(last, nodeAnimation.seconds);
  return last;
}

SceneMotion sceneMotion(const Scene& scene) {
  SceneMotion motion;
  motion.cameraKeys = scene.cameraKeys;
  motion.displayKeys = scene.displayKeys;
  motion.nodeAnimation = scene.nodeAnimation;
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
  if (motion.movesGeometry()) {
    const std::vector<std::optional<Transform>> moves = meshMoves(rest, motion, seconds);
    for (size_t m = 0; m < rest.meshes.size(); ++m) {
      if (!moves[m]) continue;
      const Transform& worldFromRest = *moves[m];
      const TriangleMesh& from = rest.meshes[m];
      TriangleMesh& to = posed.meshes[m];
      for (size_t i = 0; i < from.positions.size(); ++i)
        to.positions[i] = worldFromRest.point(from.positions[i]);
      // Normals by the inverse transpose, unit again (a node may scale).
      for (size_t i = 0; i < from.normals.size(); ++i)
        to.normals[i] = normalize(worldFromRest.normal(from.normals[i]));
    }
    if (motion.turntable) {
      const Transform worldFromRest = turntableAt(*motion.turntable, seconds);
      for (size_t s = 0; s < rest.spheres.size(); ++s)
        posed.spheres[s].center = worldFromRest.point(rest.spheres[s].center);
      // A splat set turns as a whole: its placement, not its Gaussians (scene.h, SplatSet).
      for (size_t s = 0; s < rest.splats.size(); ++s)
        posed.splats[s].worldFromFile = worldFromRest * rest.splats[s].worldFromFile;
    }
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
  if (!motion.movesGeometry()) return restBox;
  // A little slack so that vertices on the box's faces count as inside it.
  const Vec3f slack = (restBox.hi - restBox.lo) * 1e-5f + Vec3f(1e-6f);
  const Bounds3f box{restBox.lo - slack, restBox.hi + slack};
  const auto inside = [&box](const Vec3f& p) {
    return p.x >= box.lo.x && p.y >= box.lo.y && p.z >= box.lo.z && p.x <= box.hi.x &&
           p.y <= box.hi.y && p.z <= box.hi.z;
  };
  Bounds3f moved;
  for (double seconds : times) {
    const std::vector<std::optional<Transform>> moves = meshMoves(rest, motion, seconds);
    for (size_t m = 0; m < rest.meshes.size(); ++m)
      for (const Vec3f& p : rest.meshes[m].positions)
        if (inside(p)) moved.extend(moves[m] ? moves[m]->point(p) : p);
    const Transform turn = motion.turntable ? turntableAt(*motion.turntable, seconds) : Transform();
    for (const Sphere& s : rest.spheres)
      if (inside(s.center)) {
        const Vec3f c = turn.point(s.center);
        moved.extend(c - Vec3f(s.radius));
        moved.extend(c + Vec3f(s.radius));
      }
    // A splat set's framing box, clipped to the box framed at rest, by its corners.
    for (const SplatSet& set : rest.splats) {
      const Bounds3f framed = splatFramingBounds(set);
      for (int corner = 0; corner < 8; ++corner) {
        const Vec3f p{corner & 1 ? framed.hi.x : framed.lo.x,
                      corner & 2 ? framed.hi.y : framed.lo.y,
                      corner & 4 ? framed.hi.z : framed.lo.z};
        if (inside(p)) moved.extend(turn.point(p));
      }
    }
  }
  return moved.lo.x <= moved.hi.x ? moved : restBox;
}

void encloseMotion(Scene& scene, const SceneMotion& motion, const std::vector<double>& times) {
  DisplayPlacement& d = scene.display;
  if (!motion.displayKeys.empty()) {
    const DisplayKey first = displayAt(motion.displayKeys, 0.0);
    d.center = first.center, d.normal = first.normal, d.up = first.up;
  }
  if (!motion.movesGeometry()) return;
  d.contentHull.clear();
  if (d.fit) d.fit = movedBounds(scene, motion, *d.fit, times);
  d.content = movedBounds(scene, motion, d.content ? *d.content : scene.bounds(), times);
}

}  // namespace parallax
