// The render runner: checks, estimates, the display, then one picture set or a sequence.
#include "parallax/jobs/render_job.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

#include "parallax/accel/accelerator.h"
#include "parallax/cluster/process_group.h"
#include "parallax/core/error.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/distributed.h"
#include "parallax/jobs/layer_output.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/render_parts.h"
#include "parallax/layers/training.h"
#include "parallax/render/display_render.h"

namespace parallax::jobs {

std::string LayersRequest::errorMeasure() const {
  if (!error.empty()) return error;
  return method == "optimized-image" ? "srgb" : "linear";
}

void LayersRequest::check() const {
  if (method != "slits" && method != "optimized-image" && method != "nmf")
    throw RequestError("layers", "expected slits, optimized-image or nmf, got '" + method + "'");
  if (rank < 1 || rank > 16) throw RequestError("rank", "must be between 1 and 16 frames");
  if (rank > 1 && method != "nmf")
    throw RequestError("rank", "time-multiplexed frames need {layers} nmf");
  if (iterations < 0 || iterations > 1000)
    throw RequestError("iterations", "must be between 1 and 1000");
  if (!(brightness >= 0) || brightness > 100)
    throw RequestError("brightness", "must be between 0 (default) and 100");
  if (!error.empty() && error != "linear" && error != "srgb")
    throw RequestError("layer_error", "expected linear or srgb, got '" + error + "'");
  if (errorMeasure() == "srgb" && method != "optimized-image")
    throw RequestError("layer_error",
                       "srgb is for {layers} optimized-image (nmf's updates fit in linear light)");
  if (trainEyes < 1 || trainEyes > 16)
    throw RequestError("train_eyes", "must be between 1 and 16 eyes per view");
}

namespace {

// Everything the request asks that can be refused without the scene, refused in the order the
// command line has always refused it.
RenderPlan planRender(const RenderRequest& r, Reporter& reporter) {
  RenderPlan plan;
  plan.settings = r.sampling.settings();
  plan.filter = r.filter.filter();
  if ((r.quilt.width > 0 || r.quilt.height > 0) && !r.quilt.wanted)
    throw RequestError("size", "sets the size of one quilt view: needs {quilt}");
  if (r.quilt.wanted && (r.quilt.columns < 0 || r.quilt.rows < 0 || r.quilt.width < 0 ||
                         r.quilt.height < 0 || (r.quilt.columns == 0) != (r.quilt.rows == 0)))
    throw RequestError("quilt", "expected COLUMNSxROWS (both positive) or auto");
  plan.description = r.loaded ? *r.loaded : loadDisplay(r.display, reporter);
  r.layers.check();
  r.sequence.videoOptions();  // refuses bad video options before any work
  r.framing.check();
  if (r.sequence.video.wanted() && r.layers.rank > 1)
    throw RequestError("video",
                       "time-multiplexed frames ({rank}) have several image layers a frame");

  plan.camera.subpixels = r.subpixels;
  plan.camera.filter = plan.filter;
  plan.camera.viewDistanceMm = r.distance;
  const BuiltDisplay display = makeDisplay(plan.description, plan.camera);
  const bool layered = display->hasMaskLayer();
  if (r.directMapping && !layered)
    throw RequestError("direct_mapping",
                       "applies to barrier displays; for a lenticular display render a quilt "
                       "({quilt} auto) and interlace it");
  if (r.layers.solved() && !layered)
    throw RequestError("layers",
                       "a lenticular panel has one layer: only slits (its interlaced "
                       "image)");
  if (r.layers.solved() && (r.directMapping || r.quilt.wanted))
    throw RequestError("layers",
                       "optimised layers are made from the display camera's layers: not with "
                       "{direct_mapping} or {quilt}");
  checkFramingApplies(plan.description, r.framing);
  if (!layered && !r.quilt.wanted && r.sequence.given())
    throw RequestError("sequence",
                       "a lenticular panel's sequence is a sequence of quilts: add {quilt} auto");
  // The settings the display camera renders with (render/display_render.h): one sample per
  // pixel when each is the central ray.
  if (!r.directMapping && !r.quilt.wanted)
    plan.settings = displayRenderSettings(*display, plan.settings);

  const std::string subject =
      plan.description.source() == "<built-in>" ? "<built-in display>" : plan.description.source();
  if (r.quilt.wanted) {
    planQuilt(r, *display, plan, reporter);
  } else {
    checkPictureWork(*display, r.directMapping, plan.settings, subject);
  }
  plan.training.eyesPerView = r.layers.trainEyes;
  plan.training.srgbWeights = r.layers.errorMeasure() == "srgb";
  plan.training.threads = plan.settings.threads;
  plan.training.bounces = plan.settings.bounces;
  if (r.layers.solved()) {
    // The training targets and, per frame, two layers and their gradients.
    const DisplayDesign& design = *display->barrierDesign();
    const double layerBytes = double(design.spec.imagePanel.width) * design.spec.imagePanel.height *
                              sizeof(Vec3f) * (4.0 * r.layers.rank + 6.0);
    checkMemoryEstimate(trainingBytes(design, plan.training) + layerBytes,
                        r.display.empty() ? "the built-in display" : r.display,
                        "the training views of {layers} " + r.layers.method,
                        "use fewer {train_eyes} or a smaller display");
  }
  return plan;
}

// What a memory refusal names: the quilt's layout, else the display.
std::string memorySubject(const RenderRequest& r) {
  if (r.quilt.wanted) return "{quilt}";
  return r.display.empty() ? "<built-in display>" : r.display;
}

// Once every check has passed: the depth summary, and a warning if the content reaches beyond
// the budget.
void reportFraming(const BuiltDisplay& display, Reporter& reporter) {
  if (!display.framing || !writesJobOutputs()) return;  // under mpirun: once, from rank 0
  reporter.result(depthSummary(*display.framing));
  const std::string warning = depthWarning(*display.framing);
  if (!warning.empty()) reporter.warning(warning);
}

// DIR/frame-NNNN.
std::string frameFolder(const std::string& output, int frame) {
  return (std::filesystem::path(output.empty() ? "." : output) / frameName(frame)).string();
}

// Whether a frame's folder holds a finished frame (its record is written last, and the folder
// appears whole: OutputSet).
bool frameFinished(const std::string& output, int frame) {
  return std::filesystem::is_regular_file(std::filesystem::path(frameFolder(output, frame)) /
                                          "render.json");
}

// The frame's picture for the video: its quilt (whose name carries its layout) or image layer.
std::string framePicture(const RenderRequest& r, int frame) {
  const std::filesystem::path folder = frameFolder(r.output, frame);
  if (!r.quilt.wanted) return (folder / "image.png").string();
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("quilt_qs", 0) == 0 && entry.path().extension() == ".png")
      return entry.path().string();
  }
  return (folder / "quilt.png").string();  // not there: writeVideo names it
}

}  // namespace

void runRender(const RenderRequest& r, Reporter& reporter) {
  const RenderPlan plan = planRender(r, reporter);
  Scene scene = loadScene(r.scene, reporter);
  const SequencePlan sequence = planSequence(r.sequence, scene);
  if (r.sequence.given()) prepareFraming(scene, sequence);
  noteAnimation(r.sequence, scene, reporter);
  const BuiltDisplay display = makeFramedDisplay(plan.description, plan.camera, r.framing, scene);
  checkRenderMemory(r, plan, *display, scene, memorySubject(r), false);
  reportFraming(display, reporter);

  FrameTarget target{&r, &plan, &display, nullptr, 0, r.output};
  if (!r.sequence.given()) {
    const Accelerator accelerator(scene, cameraRayAccelerator(r, plan, *display));
    renderFrameToFiles(target, scene, accelerator, reporter);
    return;
  }
  FrameJob job;
  job.reporter = &reporter;
  job.accelerator = cameraRayAccelerator(r, plan, *display);
  job.finished = [&](int frame) { return frameFinished(r.output, frame); };
  job.render = [&](const Scene& posed, const Accelerator& accelerator, int frame) {
    FrameTarget one = target;
    one.sequence = &sequence;
    one.frame = frame;
    one.output = frameFolder(r.output, frame);
    renderFrameToFiles(one, posed, accelerator, reporter);
  };
  runSequence(sequence, scene, job);
  writeSequenceVideo(
      r.sequence, sequence, [&](int frame) { return framePicture(r, frame); }, reporter);
}

RenderResult renderInMemory(const RenderRequest& r, const Scene& loaded, Reporter& reporter) {
  if (r.sequence.given())
    throw RequestError("sequence", "a sequence is rendered to files: give an output folder");
  RenderRequest request = r;
  request.linear = true;  // a quilt in memory is the float quilt
  const RenderPlan plan = planRender(request, reporter);
  Scene scene = loaded;
  const BuiltDisplay display =
      makeFramedDisplay(plan.description, plan.camera, request.framing, scene);
  checkRenderMemory(request, plan, *display, scene, memorySubject(request), true);
  const Accelerator accelerator(scene, cameraRayAccelerator(request, plan, *display));
  const FrameTarget target{&request, &plan, &display, nullptr, 0, ""};
  return renderFrameInMemory(target, scene, accelerator, reporter);
}

}  // namespace parallax::jobs
