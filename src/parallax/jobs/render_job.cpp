// The render runner: checks, estimates, the display, then one picture set or a sequence.
#include "parallax/jobs/render_job.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "parallax/accel/accelerator.h"
#include "parallax/core/error.h"
#include "parallax/core/output_path.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/distributed.h"
#include "parallax/jobs/layer_output.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/render_parts.h"
#include "parallax/layers/training.h"
#include "parallax/render/display_render.h"

namespace parallax::jobs {

namespace {

// The sequence as its video is written: a quilt video's name carries the quilt's layout
// (_qs{C}x{R}a{aspect}), by which Looking Glass Studio imports it.
SequenceRequest videoOfFrames(const RenderRequest& r, const RenderPlan& plan) {
  SequenceRequest sequence = r.sequence;
  if (!r.quilt.wanted || !sequence.video.wanted()) return sequence;
  try {
    sequence.video.file = quiltVideoPath(sequence.video.file, plan.layout);
  } catch (const std::invalid_argument& e) {
    throw RequestError("video", e.what(), sequence.video.file);
  }
  return sequence;
}

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
  const DisplayDescription description = r.display.describe(reporter);
  r.layers.check();
  r.sequence.videoOptions();  // refuses bad video options before any work
  r.framing.check();
  if (r.sequence.video.wanted() && r.layers.rank > 1)
    throw RequestError("video",
                       "time-multiplexed frames ({rank}) have several image layers a frame");

  plan.display = buildDisplay(r.display, description, plan.filter);
  const BuiltDisplay& display = plan.display;
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
  if (!layered && !r.quilt.wanted && r.sequence.given())
    throw RequestError("sequence",
                       "a lenticular panel's sequence is a sequence of quilts: add {quilt} auto");
  // The settings the display camera renders with (render/display_render.h): one sample per
  // pixel when each is the central ray.
  if (!r.directMapping && !r.quilt.wanted) {
    plan.settings = displayRenderSettings(*display, plan.settings);
    if (plan.settings.samplesPerPixel < r.sampling.spp && writesJobOutputs())
      reporter.note(printed(
          "{filter} none casts each film pixel's central ray only (on a lenticular panel the "
          "formula's one ray a subpixel), so {spp} %d renders as 1 sample a pixel: every "
          "sample would be that ray; another filter (view, tent, gaussian, period) spreads the "
          "%d samples over the pixel and its view window",
          r.sampling.spp, r.sampling.spp));
  }

  const std::string subject =
      display->source() == "<built-in>" ? "<built-in display>" : display->source();
  if (r.quilt.wanted) {
    planQuilt(r, *display, plan, reporter);
  } else {
    checkPictureWork(*display, r.directMapping, plan.settings, subject);
  }
  if (r.quilt.wanted) {
    plan.pictureWidth = plan.layout.columns * plan.tileWidth;
    plan.pictureHeight = plan.layout.rows * plan.tileHeight;
  } else {  // the panel's (a barrier's image layer)
    plan.pictureWidth = display->film().panelWidth;
    plan.pictureHeight = display->film().panelHeight;
  }
  if (r.sequence.video.wanted())  // the encoder's limits, before the frames are rendered
    checkVideoFrames(r.sequence.videoOptions(), plan.pictureWidth, plan.pictureHeight);
  if (r.quilt.wanted) {
    videoOfFrames(r, plan);  // a video named for another quilt, refused before any work
    plan.outputNames = {quiltFileName("quilt", plan.layout, ".png")};
    if (r.linear) plan.outputNames.push_back(quiltFileName("quilt", plan.layout, ".pfm"));
    if (display.file.written()) plan.outputNames.push_back(display.file.name);
    plan.outputNames.push_back("render.json");
  } else {
    plan.outputNames = pictureSetNames(size_t(r.layers.solved() ? r.layers.rank : 1), layered,
                                       r.linear, display.file.name);
  }
  plan.training =
      trainingOptions(r.layers, plan.settings.threads, plan.settings.bounces, plan.settings.seed);
  if (r.layers.solved()) {
    checkMemoryEstimate(layerSolveBytes(solvedBarrier(*display), r.layers, plan.training),
                        r.display.named("the built-in display"),
                        "the training views of {layers} " + r.layers.method,
                        "use fewer {train_eyes} or {train_distances}, or a smaller display");
  }
  return plan;
}

// What a memory refusal names: the quilt's layout, else the display.
std::string memorySubject(const RenderRequest& r) {
  if (r.quilt.wanted) return "{quilt}";
  return r.display.named();
}

// Once every check has passed: the depth summary, and a warning if the content reaches beyond
// the budget.
void reportFraming(const BuiltDisplay& display, Reporter& reporter) {
  if (!display.framing || !writesJobOutputs()) return;  // under mpirun: once, from rank 0
  reporter.result(depthSummary(*display.framing));
  const std::string warning = depthWarning(*display.framing);
  if (!warning.empty()) reporter.warning(warning);
}

// Every setting that changes a sequence's pictures (SequenceRequest's frames and chunk choose
// frames, threads and the video change none), and the contents of the files they come from.
MadeFrom renderMadeFrom(const RenderRequest& r, const Scene& scene) {
  MadeFrom made = sceneMadeFrom(r.scene, scene);
  made.insert(
      made.end(),
      {{"{display}", r.display.named("<built-in>")},
       {"{filter}", r.filter.kind},
       {"{filter_width}", madeFromNumber(r.filter.widthViews)},
       {"{fit}", r.framing.fit},
       {"{focus}", r.framing.focus},
       {"{depth_budget}", r.framing.depthBudget},
       {"{subpixels}", r.display.subpixels ? "on" : "off"},
       {"{direct_mapping}", r.directMapping ? "on" : "off"},
       {"{linear}", r.linear ? "on" : "off"},
       {"{distance}", madeFromNumber(r.display.distance)},
       {"{quilt}", r.quilt.wanted
                       ? std::to_string(r.quilt.columns) + "x" + std::to_string(r.quilt.rows)
                       : "off"},
       {"{size}", std::to_string(r.quilt.width) + "x" + std::to_string(r.quilt.height)},
       {"{layers}", r.layers.method},
       {"{rank}", std::to_string(r.layers.rank)},
       {"{iterations}", std::to_string(r.layers.iterations.value_or(kDefaultLayerIterations))},
       {"{brightness}", madeFromNumber(r.layers.brightness)},
       {"{train_eyes}", std::to_string(r.layers.trainEyes)},
       {"{train_distances}", r.layers.trainDistances},
       {"{train_spp}", std::to_string(r.layers.trainSpp.value_or(kDefaultTrainingSpp))},
       {"{layer_error}", r.layers.error},
       {"{diffuser}", r.layers.diffuser ? madeFromNumber(*r.layers.diffuser) : "display"},
       {"{color_filters}", r.layers.colorFilters ? "on" : "off"},
       {"{pupil}", madeFromNumber(r.layers.pupil)},
       {"{pupil_samples}", std::to_string(r.layers.pupil > 0 ? r.layers.pupilSamples : 1)}});
  addSamplingMadeFrom(made, r.sampling);
  addSequenceMadeFrom(made, r.sequence);
  addFileContent(made, r.display.path);
  return made;
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

// Before any frame is rendered: every finished frame of the folder was made from `made`, and
// the folders of the frames to render take the set (OutputSet::check).
void checkSequenceFolder(const RenderRequest& r, const RenderPlan& plan,
                         const SequencePlan& sequence, const MadeFrom& made) {
  namespace fs = std::filesystem;
  const std::string folder = r.output.empty() ? "." : r.output;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const fs::path record = it->path() / "render.json";
    if (name.rfind("frame-", 0) == 0 && fs::is_regular_file(record, ec))
      checkMadeFrom(record.string(), it->path().string(), made, folder);
  }
  for (int frame = sequence.first; frame <= sequence.last; ++frame)
    if (!frameFinished(r.output, frame))
      OutputSet::check(frameFolder(r.output, frame), plan.outputNames);
}

}  // namespace

void runRender(const RenderRequest& request, Reporter& reporter) {
  RenderRequest r = request;
  // --video alone: whether it is the scene's animation is known once the scene is loaded, so
  // then the scene comes first (adoptAnimation).
  std::optional<Scene> loaded;
  if (r.sequence.video.wanted() && !r.sequence.given()) {
    r.sequence.videoOptions();  // bad video options before the load
    loaded = loadScene(r.scene, reporter);
    adoptAnimation(r.sequence, *loaded);
  }
  RenderPlan plan = planRender(r, reporter);
  // Before the scene is loaded: where the files go can take them (docs/inputs.md, "Outputs").
  if (r.sequence.given())
    checkOutputFolder(r.output.empty() ? "." : r.output);
  else
    OutputSet::check(r.output, plan.outputNames);
  Scene scene = loaded ? std::move(*loaded) : loadScene(r.scene, reporter);
  const SequencePlan sequence = planSequence(r.sequence, scene);
  const MadeFrom made = r.sequence.given() ? renderMadeFrom(r, scene) : MadeFrom{};
  if (r.sequence.given()) checkSequenceFolder(r, plan, sequence, made);
  if (r.sequence.given()) prepareFraming(scene, sequence);
  noteAnimation(r.sequence, scene, reporter);
  const BuiltDisplay display = frameDisplay(std::move(plan.display), r.framing, scene);
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
    one.madeFrom = &made;
    renderFrameToFiles(one, posed, accelerator, reporter);
  };
  runSequence(sequence, scene, job);
  writeSequenceVideo(
      videoOfFrames(r, plan), sequence, [&](int frame) { return framePicture(r, frame); },
      reporter);
}

RenderResult renderInMemory(const RenderRequest& r, const Scene& loaded, Reporter& reporter) {
  if (r.sequence.given())
    throw RequestError("sequence", "a sequence is rendered to files: give an output folder");
  RenderRequest request = r;
  request.linear = true;  // a quilt in memory is the float quilt
  RenderPlan plan = planRender(request, reporter);
  Scene scene = loaded;
  const BuiltDisplay display = frameDisplay(std::move(plan.display), request.framing, scene);
  checkRenderMemory(request, plan, *display, scene, memorySubject(request), true);
  const Accelerator accelerator(scene, cameraRayAccelerator(request, plan, *display));
  const FrameTarget target{&request, &plan, &display, nullptr, 0, ""};
  return renderFrameInMemory(target, scene, accelerator, reporter);
}

}  // namespace parallax::jobs
