#include "parallax/jobs/view_job.h"

#include <cmath>
#include <filesystem>
#include <utility>

#include "parallax/accel/accelerator.h"
#include "parallax/camera/camera.h"
#include "parallax/camera/display_camera.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/core/output_path.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/distributed.h"
#include "parallax/jobs/limits.h"
#include "parallax/render/render.h"

namespace parallax::jobs {

namespace {

// The ideal window view: the display's front panel's size unless given, the scene framed as
// `render` frames it (camera/framing.h), so that this is what the render shows.
std::unique_ptr<Camera> displayEyeCamera(const ViewRequest& r, const Scene& scene,
                                         Reporter& reporter) {
  const DisplayDescription description = r.display.describe(reporter);
  const Vec3d eye = *r.displayEye;
  if (!(std::isfinite(eye.x) && std::isfinite(eye.y) && std::isfinite(eye.z)))
    throw RequestError("display_eye", "must be three finite numbers (display mm)");
  Scene placed;
  placed.display = scene.display;
  if (!placed.display.content) placed.display.content = scene.framingBounds();
  const BuiltDisplay display =
      frameDisplay(buildDisplay(r.display, description), r.framing, placed);
  int width = display->viewerPanel().width, height = display->viewerPanel().height;
  if (r.width > 0) width = r.width, height = r.height;
  if (!(eye.z > 0)) throw RequestError("display_eye", "the eye must be in front (z > 0 mm)");
  return std::make_unique<WindowCamera>(eye, *display, placed.display, width, height);
}

}  // namespace

std::unique_ptr<Camera> viewCamera(const ViewRequest& r, const Scene& scene, Reporter& reporter) {
  // The two cameras' settings do not mix: refused, not ignored.
  if (r.displayEye && (r.eye || r.lookAt || r.up || r.fov))
    throw RequestError(r.eye      ? "eye"
                       : r.lookAt ? "look_at"
                       : r.up     ? "up"
                                  : "fov",
                       "places the pinhole camera: not with {display_eye}, whose view looks "
                       "through the display's window");
  if (!r.displayEye && (!r.display.path.empty() || r.display.loaded))
    throw RequestError("display", "is the display of {display_eye}: add {display_eye}");
  if (!r.displayEye && r.framing.given())
    throw RequestError("framing", "frames the scene for {display_eye}: add {display_eye}");
  if (r.displayEye) return displayEyeCamera(r, scene, reporter);
  for (const auto& [field, v] : {std::pair{"eye", r.eye}, {"look_at", r.lookAt}, {"up", r.up}})
    if (v && !isFinite(*v)) throw RequestError(field, "must be three finite numbers");
  CameraSpec spec = scene.camera ? *scene.camera : frameScene(scene);
  if (r.eye) spec.eye = *r.eye;
  if (r.lookAt) spec.lookAt = *r.lookAt;
  if (r.up) spec.up = *r.up;
  if (r.fov) {
    if (!(*r.fov > 0 && *r.fov < 180))
      throw RequestError("fov", "must be a number above 0 and below 180");
    spec.fovDegrees = *r.fov;
  }
  if (spec.lookAt == spec.eye)
    throw RequestError(r.lookAt ? "look_at" : "eye",
                       "the camera would look at its own position (eye and look-at coincide)");
  if (length(cross(spec.lookAt - spec.eye, spec.up)) == 0.0f)
    throw RequestError("up", "must not be parallel to the view direction");
  return std::make_unique<PinholeCamera>(spec.eye, spec.lookAt, spec.up, spec.fovDegrees,
                                         r.width > 0 ? r.width : 960,
                                         r.height > 0 ? r.height : 540);
}

namespace {

// Before anything is allocated, the scene loaded: Embree's BVH, the film, the writer's 8-bit
// codes and its filtered rows (the compressed PNG is small beside them), or in memory the
// caller's copy of the film (Python's array), and the time.
void checkViewWork(const ViewRequest& r, const Scene& scene, const Camera& camera, bool inMemory) {
  const std::string size = std::to_string(camera.width()) + "x" + std::to_string(camera.height());
  const double perPixel =
      kFloatRgbPixelBytes + (inMemory ? kFloatRgbPixelBytes : 2 * kRgb8PixelBytes);
  checkPeakMemory(acceleratorBytes(scene) + imageBytes(camera.width(), camera.height(), perPixel),
                  (r.width > 0 ? "{size} " : "image ") + size, "the scene's BVH and the film",
                  "use a smaller size");
  checkPixelCount(double(camera.width()) * camera.height(), "{size} " + size);
  r.sampling.checkWork(camera.width(), camera.height());
}

AcceleratorOptions viewAccelerator(const ViewRequest& r, const Camera& camera) {
  return acceleratorForCameraRays(double(camera.width()) * camera.height() * r.sampling.spp);
}

std::string optionalText(const std::optional<Vec3f>& v) {
  return v ? printed("%.9g,%.9g,%.9g", v->x, v->y, v->z) : std::string();
}

// A view sequence's record, OUTPUT's stem + ".sequence.json" (out/view.sequence.json): what
// every numbered picture beside it is made from. Its pictures have no record of their own, so
// the one record covers them all: a run whose settings differ is refused before it writes one.
std::string sequenceRecordPath(const std::string& output) {
  const std::filesystem::path p(output);
  return (p.parent_path() / (p.stem().string() + ".sequence.json")).string();
}

// Before the first frame: finished pictures were made from this request (else refused), and the
// record says so from now on.
void checkViewSequence(const ViewRequest& r, const Scene& scene, const SequencePlan& plan) {
  MadeFrom made = sceneMadeFrom(r.scene, scene);
  made.insert(made.end(),
              {{"{eye}", optionalText(r.eye)},
               {"{look_at}", optionalText(r.lookAt)},
               {"{up}", optionalText(r.up)},
               {"{fov}", r.fov ? madeFromNumber(*r.fov) : ""},
               {"{size}", std::to_string(r.width) + "x" + std::to_string(r.height)},
               {"{display_eye}", r.displayEye ? printed("%.9g,%.9g,%.9g", r.displayEye->x,
                                                        r.displayEye->y, r.displayEye->z)
                                              : ""},
               {"{display}", r.display.path},
               {"{fit}", r.framing.fit},
               {"{focus}", r.framing.focus},
               {"{depth_budget}", r.framing.depthBudget}});
  addSamplingMadeFrom(made, r.sampling);
  addSequenceMadeFrom(made, r.sequence);
  if (r.displayEye) addFileContent(made, r.display.path);
  const std::string record = sequenceRecordPath(r.output);
  int finished = 0;
  std::string first;
  for (int frame = 1; frame <= plan.total; ++frame) {
    const std::string picture = numberedPicture(r.output, frame);
    checkOutputFile(picture);
    if (!std::filesystem::is_regular_file(picture)) continue;
    if (++finished == 1) first = picture;
  }
  if (finished > 0) {
    checkMadeFrom(record, first, made, "the numbered pictures");
    return;
  }
  // No finished picture: the record of a run killed before its first is replaced.
  if (!writesJobOutputs()) return;
  JsonWriter json;
  json.set("/program", "parallax");
  json.set("/about", "what the numbered pictures beside this file are made from");
  recordMadeFrom(json, made);
  writeFileAtomically(record, json.dump() + "\n");
}

}  // namespace

void runView(const ViewRequest& request, Reporter& reporter) {
  ViewRequest r = request;
  const RenderSettings settings = r.sampling.settings();
  r.sequence.videoOptions();  // refuses bad video options before any work
  checkOutputFile(r.output);  // and a place the picture cannot go (docs/inputs.md, "Outputs")
  Scene scene = loadScene(r.scene, reporter);
  adoptAnimation(r.sequence, scene);  // --video alone: the scene's animation
  noteAnimation(r.sequence, scene, reporter);
  const std::unique_ptr<Camera> camera = viewCamera(r, scene, reporter);
  checkViewWork(r, scene, *camera, false);
  checkVideoFrames(r.sequence.videoOptions(), camera->width(), camera->height());
  // One picture under mpirun: each rank renders its bands, rank 0 writes (docs/distributed.md);
  // a sequence's pictures are whole frames of one rank.
  const auto renderPicture = [&](const Scene& posed, const Accelerator& accelerator,
                                 const Camera& frameCamera, const std::string& output, bool split) {
    RenderStats stats;
    Image image;
    {
      const auto progress = reporter.progress("view");
      image = render(posed, accelerator, frameCamera, split ? frameShare(settings) : settings,
                     &stats, progress->callback());
    }
    if (split && !mergeFrameShares({&image}, stats, reporter)) return;
    writeImage(output, image);
    reporter.result(
        printed("wrote %s (%dx%d, %d spp) in %.2f s, %s%s", output.c_str(), frameCamera.width(),
                frameCamera.height(), r.sampling.spp, stats.seconds,
                formatRate(double(stats.totalRays()) / stats.seconds).c_str(),
                splatClause(stats.splatsEvaluated, stats.splatsBlended, stats.cameraRays).c_str()));
  };
  if (!r.sequence.given()) {
    const Accelerator accelerator(scene, viewAccelerator(r, *camera));
    renderPicture(scene, accelerator, *camera, r.output, true);
    return;
  }
  const SequencePlan plan = planSequence(r.sequence, scene);
  checkViewSequence(r, scene, plan);
  prepareFraming(scene, plan);
  FrameJob job;
  job.reporter = &reporter;
  job.accelerator = viewAccelerator(r, *camera);
  job.finished = [&](int frame) {
    return std::filesystem::is_regular_file(numberedPicture(r.output, frame));
  };
  job.render = [&](const Scene& posed, const Accelerator& accelerator, int frame) {
    renderPicture(posed, accelerator, *viewCamera(r, posed, silentReporter()),
                  numberedPicture(r.output, frame), false);
  };
  runSequence(plan, scene, job);
  writeSequenceVideo(
      r.sequence, plan, [&](int frame) { return numberedPicture(r.output, frame); }, reporter);
}

Image viewInMemory(const ViewRequest& r, const Scene& scene, Reporter& reporter) {
  const RenderSettings settings = r.sampling.settings();
  const std::unique_ptr<Camera> camera = viewCamera(r, scene, reporter);
  checkViewWork(r, scene, *camera, true);
  const Accelerator accelerator(scene, viewAccelerator(r, *camera));
  return render(scene, accelerator, *camera, settings);
}

}  // namespace parallax::jobs
