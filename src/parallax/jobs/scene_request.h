// The scene a request names (docs/architecture.md, "Requests"): a scene or mesh file, the
// built-in scene, or an RGB-D photo, with how it is imported; loaded and recorded as every
// runner loads and records it.
#pragma once

#include <string>
#include <vector>

#include "parallax/importer/scene_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/jobs/reporter.h"
#include "parallax/scene/rgbd.h"
#include "parallax/scene/scene.h"

namespace parallax::jobs {

// rgbd (COLOUR DEPTH), depth_convention, depth_range, rgbd_edges, rgbd_fov (docs/rgbd.md).
struct RgbdRequest {
  std::vector<std::string> files;  // empty: not given
  std::string convention = depthConventionName(RgbdOptions{}.convention);
  std::string range = "1:3";  // NEAR:FAR (RgbdOptions' default)
  std::string edges = rgbdEdgesName(RgbdOptions{}.edges);
  double fovDegrees = RgbdOptions{}.fovDegrees;

  bool given() const { return !files.empty(); }
  // The parsed options; throws RequestError naming depth_convention, depth_range, rgbd_edges
  // or rgbd_fov.
  RgbdOptions options() const;
};

// The scene: a scene or mesh file (empty: the built-in scene), with the glTF camera to use and
// how meshes are imported, or an RGB-D photo instead.
struct SceneRequest {
  std::string path;
  SceneLoadOptions load;  // load.camera: a glTF camera by name or index
  RgbdRequest rgbd;
};
// Loads it; its notes and warnings go to `reporter` (once, from rank 0, under mpirun). A photo
// is loaded within the memory limit.
Scene loadScene(const SceneRequest& request, Reporter& reporter);
// The same without reporting.
Scene loadSceneQuietly(const SceneRequest& request);
// /scene, /scene_camera and /rgbd of a render record.
void recordScene(JsonWriter& record, const SceneRequest& request, const Scene& scene);
// The RGB-D choices under /rgbd: colour, depth, convention, near, far, fov_degrees, edges (and
// edge_jump, background_offset, background_radius_px when layered), width_px, height_px and
// triangles (of `scene`, the loaded photo).
void recordRgbd(JsonWriter& record, const RgbdRequest& request, const Scene& scene);

}  // namespace parallax::jobs
