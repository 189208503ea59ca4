// The scene a request names (scene_request.h): a file, the built-in scene or an RGB-D photo.
#include "parallax/jobs/scene_request.h"

#include <cmath>

#include "parallax/cluster/process_group.h"
#include "parallax/core/error.h"
#include "parallax/io/rgbd_file.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/requests.h"

namespace parallax::jobs {

RgbdOptions RgbdRequest::options() const {
  RgbdOptions o;
  if (convention == "disparity")
    o.convention = DepthConvention::Disparity;
  else if (convention == "depth")
    o.convention = DepthConvention::Depth;
  else if (convention == "inverse")
    o.convention = DepthConvention::Inverse;
  else
    throw RequestError("depth_convention",
                       "expected disparity, depth or inverse, got '" + convention + "'");

  const size_t colon = range.find(':');
  double nearZ = 0, farZ = 0;
  if (colon == std::string::npos || !parseNumber(range.substr(0, colon), nearZ) ||
      !parseNumber(range.substr(colon + 1), farZ))
    throw RequestError("depth_range",
                       "expected NEAR:FAR (two numbers, scene units), got '" + range + "'");
  if (!(nearZ > 0 && farZ > nearZ && farZ <= 1e6 * nearZ))
    throw RequestError("depth_range", "needs 0 < NEAR < FAR <= 1e6 NEAR, got '" + range + "'");
  o.nearDistance = float(nearZ);
  o.farDistance = float(farZ);

  if (edges == "stretch")
    o.edges = RgbdEdges::Stretch;
  else if (edges == "layered")
    o.edges = RgbdEdges::Layered;
  else
    throw RequestError("rgbd_edges", "expected stretch or layered, got '" + edges + "'");

  if (!(fovDegrees >= 1.0 && fovDegrees <= 170.0))
    throw RequestError(
        "rgbd_fov", "must be a number of degrees in [1, 170], got " + std::to_string(fovDegrees));
  o.fovDegrees = float(fovDegrees);
  return o;
}

namespace {

Scene loadRgbd(const RgbdRequest& request) {
  if (request.files.size() != 2) throw RequestError("rgbd", "expected two files: COLOUR DEPTH");
  const RgbdOptions rgbd = request.options();
  try {
    return loadRgbdScene(request.files[0], request.files[1], rgbd, memoryLimitBytes());
  } catch (const InputError& e) {
    // The loader names the file; the field that gave it is rgbd. InputError's text is
    // "file: message" when it has no key.
    if (!e.path().empty()) throw;
    std::string message = e.what();
    const std::string prefix = e.file() + ": ";
    if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
    throw InputError(e.file(), "{rgbd}", message);
  }
}

// --exposure and --view-transform over the scene's own look.
void applyLookOptions(const SceneLoadOptions& load, Scene& scene) {
  if (load.exposureStops) {
    if (!(std::abs(*load.exposureStops) <= 20))
      throw RequestError("exposure", "expected stops in [-20, 20]");
    scene.look.exposureStops = *load.exposureStops;
  }
  if (!load.viewTransform.empty()) {
    const auto transform = parseViewTransform(load.viewTransform);
    if (!transform)
      throw RequestError("view_transform",
                         "unknown view transform '" + load.viewTransform + "' (standard or filmic)",
                         load.viewTransform);
    scene.look.transform = *transform;
  }
}

}  // namespace

Scene loadSceneQuietly(const SceneRequest& request) {
  applyImporterLimits();
  if (!request.rgbd.given() && request.path.empty() && !request.load.camera.empty())
    throw RequestError("camera", "the built-in scene has no cameras");
  Scene scene = request.rgbd.given()   ? loadRgbd(request.rgbd)
                : request.path.empty() ? defaultScene()
                                       : loadScene(request.path, request.load);
  if (request.path.empty() && !request.load.focusOn.empty())
    focusOnObject(scene, request.load.focusOn);
  applyLookOptions(request.load, scene);
  return scene;
}

Scene loadScene(const SceneRequest& request, Reporter& reporter) {
  cluster::failIfAskedForTest(cluster::world());
  Scene scene = loadSceneQuietly(request);
  // Under mpirun every rank loads the scene: its notes once.
  if (!cluster::world().isRoot()) return scene;
  for (const auto& n : scene.notes) reporter.note(n);
  for (const auto& w : scene.warnings) reporter.warning(w);
  return scene;
}

void recordRgbd(JsonWriter& record, const RgbdRequest& request, const Scene& scene) {
  const RgbdOptions o = request.options();
  if (request.files.size() == 2) {
    record.set("/rgbd/colour", request.files[0]);
    record.set("/rgbd/depth", request.files[1]);
  }
  record.set("/rgbd/convention", depthConventionName(o.convention));
  record.set("/rgbd/near", double(o.nearDistance));
  record.set("/rgbd/far", double(o.farDistance));
  record.set("/rgbd/fov_degrees", double(o.fovDegrees));
  record.set("/rgbd/edges", rgbdEdgesName(o.edges));
  if (o.edges == RgbdEdges::Layered) {
    record.set("/rgbd/edge_jump", double(o.edgeJump));
    record.set("/rgbd/background_offset", double(o.backgroundOffset));
  }
  if (!scene.images.empty()) {
    const Image& photo = scene.images[0];
    record.set("/rgbd/width_px", photo.width());
    record.set("/rgbd/height_px", photo.height());
    if (o.edges == RgbdEdges::Layered)
      record.set("/rgbd/background_radius_px", backgroundRadiusPx(o, photo.width()));
  }
  record.set("/rgbd/triangles", uint64_t(scene.triangleCount()));
}

void recordScene(JsonWriter& record, const SceneRequest& request, const Scene& scene) {
  record.set("/scene", scene.source);
  // The look every picture of the render got; simulate's ideal views take it from here.
  if (!scene.look.identity()) {
    record.set("/look/exposure", scene.look.exposureStops);
    record.set("/look/view_transform", viewTransformName(scene.look.transform));
  }
  if (request.rgbd.given()) recordRgbd(record, request.rgbd, scene);
  if (!request.load.camera.empty()) record.set("/scene_camera", request.load.camera);
  if (!request.load.focusOn.empty()) record.set("/scene_focus_on", request.load.focusOn);
}

}  // namespace parallax::jobs
