#include "parallax/jobs/view_job.h"

#include <filesystem>

#include "parallax/accel/accelerator.h"
#include "parallax/camera/camera.h"
#include "parallax/camera/display_camera.h"
#include "parallax/camera/framing.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/io/image_file.h"
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
  const DisplayDescription description = r.loaded ? *r.loaded : loadDisplay(r.display, reporter);
  const Vec3d eye = *r.displayEye;
  Scene placed;
  placed.display = scene.display;
  if (!placed.display.content) placed.display.content = scene.bounds();
  const BuiltDisplay display = makeFramedDisplay(description, {}, r.framing, placed);
  int width = display->film().panelWidth, height = display->film().panelHeight;
  if (const DisplayDesign* barrier = display->barrierDesign()) {
    const DisplaySpec& spec = barrier->spec;
    const Panel& front = spec.order == LayerOrder::BarrierBack ? spec.imagePanel : spec.maskPanel;
    width = front.width, height = front.height;
  }
  if (r.width > 0) width = r.width, height = r.height;
  if (!(eye.z > 0)) throw RequestError("display_eye", "the eye must be in front (z > 0 mm)");
  return std::make_unique<WindowCamera>(eye, *display, placed.display, width, height);
}

}  // namespace

std::unique_ptr<Camera> viewCamera(const ViewRequest& r, const Scene& scene, Reporter& reporter) {
  if (r.displayEye) return displayEyeCamera(r, scene, reporter);
  CameraSpec spec = scene.camera ? *scene.camera : frameScene(scene);
  if (r.eye) spec.eye = *r.eye;
  if (r.lookAt) spec.lookAt = *r.lookAt;
  if (r.up) spec.up = *r.up;
  if (r.fov) {
    if (!(*r.fov > 0 && *r.fov < 180))
      throw RequestError("fov", "must be a number above 0 and below 180");
    spec.fovDegrees = *r.fov;
  }
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

}  // namespace

void runView(const ViewRequest& r, Reporter& reporter) {
  const RenderSettings settings = r.sampling.settings();
  r.sequence.videoOptions();  // refuses bad video options before any work
  Scene scene = loadScene(r.scene, reporter);
  noteAnimation(r.sequence, scene, reporter);
  const std::unique_ptr<Camera> camera = viewCamera(r, scene, reporter);
  checkViewWork(r, scene, *camera, false);
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
    reporter.result(printed("wrote %s (%dx%d, %d spp) in %.2f s, %s", output.c_str(),
                            frameCamera.width(), frameCamera.height(), r.sampling.spp,
                            stats.seconds,
                            formatRate(double(stats.totalRays()) / stats.seconds).c_str()));
  };
  if (!r.sequence.given()) {
    const Accelerator accelerator(scene, viewAccelerator(r, *camera));
    renderPicture(scene, accelerator, *camera, r.output, true);
    return;
  }
  const SequencePlan plan = planSequence(r.sequence, scene);
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
