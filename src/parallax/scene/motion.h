// How a scene moves over a sequence of frames (docs/animation.md): a turntable of the loaded
// content, and the scene file's camera and display keys. A sequence loads its scene once and
// poses a copy of it per frame; poseScene only rewrites what moves (vertex positions and
// normals, sphere centres, the camera, the display placement), so the topology, materials and
// textures stay shared in meaning and the accelerator can refit instead of rebuilding.
#pragma once

#include <optional>
#include <vector>

#include "parallax/scene/scene.h"

namespace parallax {

// The content turning about an axis: `degreesPerSecond` about `axis` (unit, right-handed)
// through `pivot`. Lights stay where they are (a turntable under studio lights), and so do
// emissive meshes that are lights.
struct Turntable {
  Vec3f pivot{0.0f};
  Vec3f axis{0, 1, 0};
  double degreesPerSecond = 0;
};

struct SceneMotion {
  std::optional<Turntable> turntable;
  // Copies of the scene's keys (Scene::cameraKeys, Scene::displayKeys, Scene::nodeAnimation).
  std::vector<CameraKey> cameraKeys;
  std::vector<DisplayKey> displayKeys;
  NodeAnimation nodeAnimation;

  bool movesGeometry() const { return turntable.has_value() || !nodeAnimation.empty(); }
  bool empty() const { return !movesGeometry() && cameraKeys.empty() && displayKeys.empty(); }
  // The time of the last key (0 without keys).
  double keyedSeconds() const;
};

// A glTF node's transform at `seconds`: translation * rotation * scale (glTF 2.0,
// "Transformations"), each channel interpolated between its keys (LINEAR: lerp, rotations by slerp;
// STEP: the earlier key) and held outside them, times the parent's, up to the file's root.
Mat4 fileFromNodeAt(const NodeAnimation& animation, int node, double seconds);

// The scene's own motion (its keys and node animation), with no turntable.
SceneMotion sceneMotion(const Scene& scene);

// The turntable a user means by "turn the content": about the display's up axis, through the
// centre of the content's bounds (DisplayPlacement::content, else the scene's bounds).
Turntable contentTurntable(const Scene& scene, double degreesPerSecond);

// `posed` becomes `rest` at time `seconds`. `posed` must be a copy of `rest` (the same meshes
// and spheres); only moving parts are written, so posing every frame into one copy costs
// a pass over the vertices and no allocation.
void poseScene(const Scene& rest, const SceneMotion& motion, double seconds, Scene& posed);

// The camera at `seconds`: keys interpolated linearly (eye, look-at point, up, field of
// view), held before the first key and after the last.
CameraSpec cameraAt(const std::vector<CameraKey>& keys, double seconds);
// The display placement's centre, normal and up at `seconds`: centre linear, normal and up
// normalised linear interpolation (exact for the small turns between keys of a camera move),
// up made perpendicular to the normal.
DisplayKey displayAt(const std::vector<DisplayKey>& keys, double seconds);

// The bounds, over all `times`, of what lies inside `restBox` at rest (the content a framing
// measures: DisplayPlacement::fit or ::content), moved by the motion. A sequence frames these
// once, so that the content keeps its size and depth on the display from frame to frame.
// Exact: each time's moved vertices (and sphere extremes) are measured, not the box's corners.
Bounds3f movedBounds(const Scene& rest, const SceneMotion& motion, const Bounds3f& restBox,
                     const std::vector<double>& times);

// Before a sequence's one framing: the display placed at its first key, and the framing's
// bounds (DisplayPlacement::fit and ::content) replaced by their envelope over `times` (every
// frame of the whole animation), so that one framing holds for every frame and the content
// does not pump. A content hull is dropped when the geometry moves (it would not move along).
void encloseMotion(Scene& scene, const SceneMotion& motion, const std::vector<double>& times);

}  // namespace parallax
