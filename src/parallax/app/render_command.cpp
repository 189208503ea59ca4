// `parallax render`: the two layer images of the display, and a record of how they were made.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/camera/display_camera.h"
#include "parallax/camera/framing.h"
#include "parallax/cluster/process_group.h"
#include "parallax/core/error.h"
#include "parallax/core/parallel.h"
#include "parallax/io/display_file.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/io/lenticular_file.h"
#include "parallax/jobs/distributed.h"
#include "parallax/jobs/layer_output.h"
#include "parallax/jobs/sequence.h"
#include "parallax/layers/layer_solver.h"
#include "parallax/layers/training.h"
#include "parallax/render/display_render.h"
#include "parallax/render/quilt.h"

namespace parallax::app {

namespace {

struct RenderOptions {
  std::string scene, display;
  SceneLoadOptions load;  // --camera
  SamplingOptions sampling;
  std::string output = "out";
  bool linear = false;
  bool subpixels = false;
  bool directMapping = false;
  std::string quilt, size;  // --quilt CxR, --size WxH of one quilt view
  FilterOptions filter;
  FramingOptions framing;  // empty: the scene's (docs/display-geometry.md)
  // Content-adaptive layers (docs/content-adaptive.md).
  std::string layers = "slits";
  int rank = 1, iterations = 0;  // 0: the method's default
  double brightness = 0;         // 0: the method's default
  int trainEyesPerView = 2;
  std::string layerError;    // "": the method's default (srgb for optimized-image, linear for nmf)
  SequenceOptions sequence;  // --frames, --turntable, --duration, --fps (docs/animation.md)
  RgbdCliOptions rgbd;       // --rgbd COLOUR DEPTH instead of a scene (docs/rgbd.md)
};

// The scene file, or the RGB-D photo's scene.
Scene loadRenderScene(const RenderOptions& o) {
  return o.rgbd.given() ? loadRgbdFromOptions(o.rgbd) : loadSceneReportingWarnings(o.scene, o.load);
}

// The layer methods and their defaults.
// Measured (docs/content-adaptive.md): the image layer settles within 8 iterations.
int defaultIterations() {
  return 10;
}
std::string layerError(const RenderOptions& o) {
  if (!o.layerError.empty()) return o.layerError;
  return o.layers == "optimized-image" ? "srgb" : "linear";
}
// nmf aims 5 % above max(2, rank) times the slits' brightness: a least-squares fit comes out a
// little darker than its target (measured: 1.97x for a target of 2 on the built-in scene).
double defaultBrightness(const std::string& method, int rank) {
  return method == "nmf" ? 1.05 * std::max(2.0, double(rank)) : 1.0;
}

void checkLayerOptions(const RenderOptions& o, bool lenticular) {
  if (o.layers != "slits" && o.layers != "optimized-image" && o.layers != "nmf")
    throw InputError("command line", "--layers",
                     "expected slits, optimized-image or nmf, got '" + o.layers + "'");
  if (o.rank < 1 || o.rank > 16)
    throw InputError("command line", "--rank", "must be between 1 and 16 frames");
  if (o.rank > 1 && o.layers != "nmf")
    throw InputError("command line", "--rank", "time-multiplexed frames need --layers nmf");
  if (o.iterations < 0 || o.iterations > 1000)
    throw InputError("command line", "--iterations", "must be between 1 and 1000");
  if (!(o.brightness >= 0) || o.brightness > 100)
    throw InputError("command line", "--brightness", "must be between 0 (default) and 100");
  if (!o.layerError.empty() && o.layerError != "linear" && o.layerError != "srgb")
    throw InputError("command line", "--layer-error",
                     "expected linear or srgb, got '" + o.layerError + "'");
  if (layerError(o) == "srgb" && o.layers != "optimized-image")
    throw InputError("command line", "--layer-error",
                     "srgb is for --layers optimized-image (nmf's updates fit in linear light)");
  if (o.trainEyesPerView < 1 || o.trainEyesPerView > 16)
    throw InputError("command line", "--train-eyes", "must be between 1 and 16 eyes per view");
  if (o.layers == "slits") return;
  if (lenticular)
    throw InputError("command line", "--layers",
                     "a lenticular panel has one layer: only slits (its interlaced image)");
  if (o.directMapping || !o.quilt.empty())
    throw InputError("command line", "--layers",
                     "optimised layers are made from the display camera's layers: not with "
                     "--direct-mapping or --quilt");
}

// Frames the scene for the design (camera/framing.h) and returns the framing.
Framing frameForRender(const RenderOptions& o, Scene& scene, DisplayDesign& design) {
  o.framing.apply(scene.display);
  const Framing framing = frameForDisplay(scene, design);
  scene.display = framing.placement;
  design = framing.design;
  return framing;
}

// Once every check has passed: the depth summary, and a warning if the content reaches beyond
// the budget.
void reportFraming(const Framing& framing) {
  if (!writesJobOutputs()) return;  // under mpirun: once, from rank 0
  std::printf("%s\n", depthSummary(framing).c_str());
  const std::string warning = depthWarning(framing);
  if (!warning.empty()) std::fprintf(stderr, "warning: %s\n", warning.c_str());
}

}  // namespace

namespace {

// `render --quilt CxR|auto`: the C*R off-axis views of the display's window from eyes spread
// evenly across the view zone (a lenticular's cone), tiled from the bottom-left into
// DIR/quilt_qs{C}x{R}a{aspect}.png (docs/quilts.md), each view rendered straight into its tile.
// Tiles: --size, else a lenticular device's quilt divided by the layout, else the barrier's image
// layer.
// With a sequence, `accelerator` is the sequence's and `frame` is recorded; otherwise the quilt
// builds its own.
struct QuiltFrame {
  const Accelerator* accelerator = nullptr;
  const SequencePlan* plan = nullptr;
  int frame = 0;
  std::string output;
};

void runQuiltRender(const RenderOptions& o, QuiltLayout layout, const DisplayModel& display,
                    const Scene& scene, const RenderSettings& settings, const Framing* framing,
                    const std::string& displayText, const std::string& displayName,
                    const QuiltFrame& sequenceFrame = {}) {
  const LenticularDesign* lenticular = display.lenticularDesign();
  if (layout.columns == 0) {  // auto: the device's quilt, or one row of the barrier's views
    if (lenticular) {
      layout.columns = lenticular->calibration.quilt.columns;
      layout.rows = lenticular->calibration.quilt.rows;
    } else {
      layout.columns = display.viewCount();
      layout.rows = 1;
    }
  }
  int width = display.film().panelWidth, height = display.film().panelHeight;
  if (lenticular) {
    width = lenticular->calibration.quilt.width / layout.columns;
    height = lenticular->calibration.quilt.height / layout.rows;
  }
  if (!o.size.empty()) parseSize("--size", o.size, width, height);
  if (width < 1 || height < 1)
    throw InputError("command line", "--quilt",
                     "the device's quilt is too small for " + std::to_string(layout.columns) + "x" +
                         std::to_string(layout.rows) + " tiles");
  checkQuiltWork(layout.columns, layout.rows, width, height, settings.samplesPerPixel,
                 settings.threads, o.size, o.linear);
  layout.aspect = double(width) / height;
  const DisplayWindow window = display.window();
  const double windowAspect = window.widthMm / window.heightMm;
  if (std::abs(layout.aspect / windowAspect - 1.0) > 0.01 && writesJobOutputs())
    std::fprintf(stderr,
                 "note: tiles of %dx%d have aspect %.4f, the display's window %.4f: the views are "
                 "stretched to fill them, as Looking Glass quilts are\n",
                 width, height, layout.aspect, windowAspect);

  if (framing && !sequenceFrame.plan) reportFraming(*framing);
  std::optional<Accelerator> ownAccelerator;
  if (!sequenceFrame.accelerator)
    ownAccelerator.emplace(
        scene, acceleratorForCameraRays(double(layout.columns) * layout.rows * width * height *
                                        settings.samplesPerPixel));
  const Accelerator& accelerator =
      sequenceFrame.accelerator ? *sequenceFrame.accelerator : *ownAccelerator;
  RenderStats stats;
  // One quilt alone is split across mpirun's ranks by bands of every view's rows; a sequence's
  // quilts are whole frames of one rank (docs/distributed.md).
  const RenderSettings share = sequenceFrame.plan ? settings : frameShare(settings);
  // The quilt is kept as the PNG's 8-bit codes, a quarter of a float quilt's memory; a float
  // quilt only when --linear asks for one.
  Image quilt;
  const int quiltWidth = layout.columns * width, quiltHeight = layout.rows * height;
  std::vector<uint8_t> codes;
  {
    ProgressBar bar("render");
    const auto onProgress = [&bar](int done, int total) { bar.update(done, total); };
    if (o.linear) {
      quilt = renderQuilt(scene, accelerator, display, share, layout, width, height, &stats,
                          onProgress);
    } else {
      codes.resize(size_t(quiltWidth) * size_t(quiltHeight) * 3);
      const auto keepCodes = [&](int, int left, int top, const Image& view) {
        parallelFor(view.height(), 0, 16, [&](int64_t begin, int64_t end) {
          for (int64_t y = begin; y < end; ++y) {
            uint8_t* row = codes.data() + (size_t(top + y) * size_t(quiltWidth) + size_t(left)) * 3;
            linearToSrgb8(&view.at(0, int(y)).x, 3 * size_t(view.width()), row);
          }
        });
      };
      renderQuiltTiles(scene, accelerator, display, share, layout, width, height, keepCodes, &stats,
                       onProgress);
    }
  }
  if (!sequenceFrame.plan) {
    const bool writer = o.linear ? mergeFrameShares({&quilt}, stats, cliReporter())
                                 : mergeFrameShares(codes, stats, cliReporter());
    if (!writer) return;
  }
  const double raysPerSecond = double(stats.totalRays()) / stats.seconds;

  const std::string name = quiltFileName("quilt", layout, ".png");
  JsonWriter record;
  startRenderRecord(record, "quilt", o.display);
  record.set("/display_kind", displayKindName(display.kind()));
  record.set("/scene", scene.source);
  if (o.rgbd.given()) recordRgbd(record, o.rgbd, scene);
  if (!o.load.camera.empty()) record.set("/scene_camera", o.load.camera);  // docs/gltf.md
  record.set("/spp", o.sampling.spp);
  record.set("/bounces", settings.bounces);
  record.set("/seed", o.sampling.seed);
  record.set("/jitter", o.sampling.jitter);
  record.set("/threads", o.sampling.threads);
  record.set("/seconds", stats.seconds);
  record.set("/rays", stats.totalRays());
  record.set("/rays_per_second", raysPerSecond);
  record.set("/quilt/columns", layout.columns);
  record.set("/quilt/rows", layout.rows);
  record.set("/quilt/view_size", std::to_string(width) + "x" + std::to_string(height));
  record.set("/quilt/order", "view 0 = leftmost camera = bottom-left tile, rightward then upward");
  for (int k = 0; k < layout.views(); ++k) {
    const Vec3d eye = quiltEyePosition(display, k, layout.views());
    record.set("/quilt/eyes_mm/" + std::to_string(k),
               Vec3f(float(eye.x), float(eye.y), float(eye.z)));
  }
  record.set("/outputs/quilt", name);
  if (framing) recordFraming(record, *framing);
  if (const DisplayDesign* barrier = display.barrierDesign())
    writeDesignJson(record, "/design", *barrier);
  if (lenticular) writeLenticularDesignJson(record, "/design", *lenticular);
  const std::string linearName = quiltFileName("quilt", layout, ".pfm");
  if (o.linear) record.set("/outputs/quilt_linear", linearName);
  if (sequenceFrame.plan) recordSequence(record, *sequenceFrame.plan, sequenceFrame.frame);

  OutputSet set(sequenceFrame.plan ? sequenceFrame.output : o.output);
  const std::string dir = set.dir();
  if (o.linear) {
    writeImage(set.path(name), quilt);
    writeImage(set.path(linearName), quilt);
  } else {
    writeFileAtomically(set.path(name), pngBytesFromSrgb8(codes, quiltWidth, quiltHeight));
  }
  writeFileAtomically(set.path(displayName), displayText);
  writeFileAtomically(set.path("render.json"), record.dump() + "\n");
  set.commit();
  std::printf("wrote %s/%s (%d views of %dx%d), %s/render.json\n", dir.c_str(), name.c_str(),
              layout.views(), width, height, dir.c_str());
  std::printf("%d spp in %.2f s, %s\n", o.sampling.spp, stats.seconds,
              formatRate(raysPerSecond).c_str());
}

// DIR/frame-NNNN, and whether it holds a finished frame (its record is written last, and the
// folder appears whole: OutputSet).
std::string frameFolder(const std::string& output, int frame) {
  return (std::filesystem::path(output.empty() ? "." : output) / frameName(frame)).string();
}
bool frameFinished(const std::string& output, int frame) {
  return std::filesystem::is_regular_file(std::filesystem::path(frameFolder(output, frame)) /
                                          "render.json");
}

// render --quilt with a sequence: one quilt per frame in DIR/frame-NNNN.
void runQuiltSequence(const RenderOptions& o, const SequencePlan& plan, const QuiltLayout& layout,
                      const DisplayModel& display, const Scene& scene,
                      const RenderSettings& settings, const Framing* framing,
                      const std::string& displayText, const std::string& displayName) {
  FrameJob job;
  job.reporter = &cliReporter();
  job.accelerator = acceleratorForCameraRays(double(layout.views()) * display.film().panelWidth *
                                             display.film().panelHeight * settings.samplesPerPixel);
  job.finished = [&](int frame) { return frameFinished(o.output, frame); };
  job.render = [&](const Scene& posed, const Accelerator& accelerator, int frame) {
    runQuiltRender(o, layout, display, posed, settings, framing, displayText, displayName,
                   {&accelerator, &plan, frame, frameFolder(o.output, frame)});
  };
  runSequence(plan, scene, job);
  writeSequenceVideo(
      o.sequence, plan,
      [&](int frame) {
        // The quilt's name carries its layout and aspect: the frame's one quilt PNG.
        for (const auto& entry :
             std::filesystem::directory_iterator(frameFolder(o.output, frame))) {
          const std::string name = entry.path().filename().string();
          if (name.rfind("quilt_qs", 0) == 0 && entry.path().extension() == ".png")
            return entry.path().string();
        }
        return frameFolder(o.output, frame) + "/quilt.png";  // not there: writeVideo names it
      },
      cliReporter());
}

// `render --display visual.json|lkg:NAME`: the lenticular panel's picture, or its quilt.
void runLenticular(const RenderOptions& o, const LenticularCalibration& calibration,
                   const QuiltLayout& layout, RenderSettings settings) {
  if (o.subpixels)
    throw InputError("command line", "--subpixels",
                     "applies to barrier displays; a lenticular render always traces one ray per "
                     "subpixel");
  if (o.directMapping)
    throw InputError("command line", "--direct-mapping",
                     "applies to barrier displays; for a lenticular display render a quilt "
                     "(--quilt auto) and interlace it");
  if (o.framing.given())
    throw InputError("command line", "--fit/--focus/--depth-budget",
                     "apply to barrier displays (their depth budget is the virtual gap)");
  if (o.quilt.empty()) {
    if (o.sequence.given())
      throw InputError("command line", "--frames/--turntable",
                       "a lenticular panel's sequence is a sequence of quilts: add --quilt auto");
    return runLenticularRender(
        {calibration, o.scene, o.output, o.sampling, o.filter, 0.0, o.load, o.rgbd});
  }
  const LenticularDesign design = designLenticular(calibration);
  const std::unique_ptr<DisplayModel> display = makeLenticularDisplay(design);
  Scene scene = loadRenderScene(o);
  settings.samplesPerPixel = o.sampling.spp;
  if (!o.sequence.given())
    return runQuiltRender(o, layout, *display, scene, settings, nullptr,
                          lenticularCalibrationText(calibration), "visual.json");
  const SequencePlan plan = planSequence(o.sequence, scene);
  prepareFraming(scene, plan);
  runQuiltSequence(o, plan, layout, *display, scene, settings, nullptr,
                   lenticularCalibrationText(calibration), "visual.json");
}

// --layers optimized-image | nmf: the training views, then the solver, from the slit layers.
std::vector<LayerFrame> solveLayers(const RenderOptions& o, const Scene& scene,
                                    const Accelerator& accelerator, const DisplayDesign& design,
                                    TrainingOptions training, const DisplayLayers& slits,
                                    JsonWriter& out) {
  const auto start = std::chrono::steady_clock::now();
  const double slitMean = meanTransmittance(slits.mask);
  const double gain = o.brightness > 0 ? o.brightness : defaultBrightness(o.layers, o.rank);
  training.targetScale = slitMean * gain;
  std::vector<TrainingView> views;
  {
    ProgressBar bar("ideal views");
    views = trainingViews(scene, accelerator, design, training,
                          [&bar](int done, int total) { bar.update(done, total); });
  }
  const double trainSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int iterations = o.iterations > 0 ? o.iterations : defaultIterations();
  SolveReport report;
  std::vector<LayerFrame> frames;
  if (o.layers == "optimized-image") {
    frames.push_back(
        {optimizeImageLayer(views, slits.image, slits.mask, iterations, training.threads, &report),
         slits.mask});
  } else {
    // Start: T copies of the slit image; masks of T slit phases a period / T apart, their closed
    // pixels at 0.2 so that the updates can open them (a zero stays zero under them).
    const double period = design.slitPeriodPx;
    for (int t = 0; t < o.rank; ++t) {
      Image mask = slits.mask;
      const int shift = int(std::lround(period * t / o.rank));
      for (int y = 0; y < mask.height(); ++y)
        for (int x = 0; x < mask.width(); ++x) {
          const int from = std::clamp(x - shift, 0, mask.width() - 1);
          const Vec3f v = slits.mask.at(from, y);
          mask.at(x, y) = Vec3f(std::max(v.x, 0.2f), std::max(v.y, 0.2f), std::max(v.z, 0.2f));
        }
      frames.push_back({slits.image, std::move(mask)});
    }
    frames = factorizeLayers(views, std::move(frames), iterations, training.threads, &report);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double seen = 0;
  for (const LayerFrame& f : frames) seen += meanTransmittance(f.image) * meanTransmittance(f.mask);
  out.set("/layers/rank", int(frames.size()));
  out.set("/layers/iterations", report.iterations);
  out.set("/layers/brightness_gain", gain);
  // simulate divides what the eye sees by this (the slit mask's mean transmittance times the
  // gain), so that views compare with the ideal ones at the brightness the layers aimed at.
  out.set("/layers/normalisation", slitMean * gain);
  out.set("/layers/training_eyes", int(views.size()));
  out.set("/layers/error", layerError(o));
  out.set("/layers/training_seconds", trainSeconds);
  out.set("/layers/seconds", seconds);
  out.set("/layers/objective_first", report.objective.front());
  out.set("/layers/objective_last", report.objective.back());
  out.set("/layers/mean_layer_product", seen / double(frames.size()));
  std::printf(
      "%s: %zu frame(s), %d iterations, objective %.3g -> %.3g (per pixel and channel), "
      "%zu training eyes, %.1f s (ideal views %.1f s)\n",
      o.layers.c_str(), frames.size(), report.iterations, report.objective.front(),
      report.objective.back(), views.size(), seconds, trainSeconds);
  return frames;
}

// The display's layers of one (posed) scene into `output`: the render, the optional solver,
// the record. `plan` and `frame` are the sequence's, if any.
void renderLayers(const RenderOptions& o, const Scene& scene, const Accelerator& accelerator,
                  const DisplayDesign& design, const Framing& framing,
                  const RenderSettings& settings, const ViewFilter& filter,
                  const TrainingOptions& training, const std::string& output,
                  const SequencePlan* plan, int frame) {
  // One frame under mpirun: each rank renders its bands, rank 0 writes (docs/distributed.md).
  // The layer solvers need the whole slit layers and fit them globally: rank 0 alone runs them.
  const bool split = !plan && o.layers == "slits";
  if (!plan && !split && !writesJobOutputs()) return;
  if (!plan && !split && cluster::world().size() > 1)
    std::fprintf(stderr, "note: --layers %s is not split across ranks: rank 0 renders it alone\n",
                 o.layers.c_str());
  DisplayLayers layers;
  {
    ProgressBar bar("render");
    const auto onProgress = [&bar](int done, int total) { bar.update(done, total); };
    const RenderSettings share = split ? frameShare(settings) : settings;
    layers = o.directMapping ? renderDirectMapping(scene, accelerator, design, share, onProgress)
                             : renderDisplay(scene, accelerator, design, share, onProgress, filter);
  }
  if (split && !mergeFrameShares({&layers.image}, layers.stats, cliReporter())) return;
  const double raysPerSecond = double(layers.stats.totalRays()) / layers.stats.seconds;

  JsonWriter record;
  startRenderRecord(record, o.directMapping ? "direct-mapping" : "barrier-camera", o.display);
  record.set("/layers/method", o.layers);
  std::vector<LayerFrame> frames{{layers.image, layers.mask}};
  if (o.layers != "slits")
    frames = solveLayers(o, scene, accelerator, design, training, layers, record);
  record.set("/scene", scene.source);
  if (o.rgbd.given()) recordRgbd(record, o.rgbd, scene);
  if (!o.load.camera.empty()) record.set("/scene_camera", o.load.camera);  // docs/gltf.md
  record.set("/spp", settings.samplesPerPixel);
  record.set("/bounces", settings.bounces);
  record.set("/seed", o.sampling.seed);
  record.set("/jitter", o.sampling.jitter);
  record.set("/threads", o.sampling.threads);
  record.set("/adaptive", settings.adaptive);
  if (settings.adaptive) {
    record.set("/adaptive_threshold_8bit", settings.adaptiveThreshold * 255.0);
    record.set("/camera_rays", layers.stats.cameraRays);
    record.set("/mean_spp", double(layers.stats.cameraRays) /
                                (double(layers.image.width()) * layers.image.height() *
                                 (design.spec.subpixelRays ? 3.0 : 1.0)));
  }
  if (!o.directMapping) {
    record.set("/filter/kind", viewFilterName(filter.kind));
    record.set("/filter/width_views", filter.widthViews);
  }
  record.set("/seconds", layers.stats.seconds);
  record.set("/rays", layers.stats.totalRays());
  record.set("/rays_per_second", raysPerSecond);
  record.set("/scene_display/center", scene.display.center);
  record.set("/scene_display/normal", scene.display.normal);
  record.set("/scene_display/up", scene.display.up);
  record.set("/scene_display/width", double(fitDisplayWidth(scene.display, displayWindow(design))));
  recordFraming(record, framing);
  if (plan) recordSequence(record, *plan, frame);
  if (frames.size() == 1)
    cliReporter().result(
        writeDisplayLayers(output, frames[0].image, frames[0].mask, design, o.linear, record));
  else
    cliReporter().result(writeLayerFrames(output, frames, design, record));
  std::printf("%d spp in %.2f s, %s\n", settings.samplesPerPixel, layers.stats.seconds,
              formatRate(raysPerSecond).c_str());
}

void runRender(const RenderOptions& o) {
  RenderSettings settings = o.sampling.settings();
  const ViewFilter filter = o.filter.filter();
  // The central ray is one ray: more samples of it would all be the same.
  if (filter.kind == ViewFilterKind::None && !o.directMapping && o.quilt.empty())
    settings.samplesPerPixel = 1;
  if (!o.size.empty() && o.quilt.empty())
    throw InputError("command line", "--size", "sets the size of one quilt view: needs --quilt");
  QuiltLayout layout;
  if (o.quilt == "auto")
    layout.columns = layout.rows = 0;  // the display's own (runQuiltRender)
  else if (!o.quilt.empty() && !parseColumnsByRows(o.quilt, layout.columns, layout.rows))
    throw InputError("command line", "--quilt",
                     "expected COLUMNSxROWS or auto, got '" + o.quilt + "'");
  const DisplayDescription description = loadDisplayOrDefault(o.display);
  checkLayerOptions(o, description.kind == DisplayKind::Lenticular);
  o.sequence.videoOptions();  // refuses bad --video options before any work
  {
    DisplayPlacement probe;  // refuses bad --fit/--focus/--depth-budget before the scene loads
    o.framing.apply(probe);
  }
  if (o.sequence.video.wanted() && o.rank > 1)
    throw InputError("command line", "--video",
                     "time-multiplexed frames (--rank) have several image layers a frame");
  if (description.kind == DisplayKind::Lenticular)
    return runLenticular(o, description.lenticular, layout, settings);
  DisplayDesign design = designDisplay(description.barrier);
  if (o.subpixels) {
    DisplaySpec spec = design.spec;
    spec.subpixelRays = true;
    design = designDisplay(spec);
  }
  if (o.quilt.empty())
    checkLayerWork(design, o.directMapping, settings.samplesPerPixel, settings.threads, o.display);
  TrainingOptions training;
  training.eyesPerView = o.trainEyesPerView;
  training.srgbWeights = layerError(o) == "srgb";
  training.threads = settings.threads;
  training.bounces = settings.bounces;
  if (o.layers != "slits") {
    // The training targets and, per frame, two layers and their gradients.
    const double layerBytes = double(design.spec.imagePanel.width) * design.spec.imagePanel.height *
                              sizeof(Vec3f) * (4.0 * o.rank + 6.0);
    checkMemoryEstimate(trainingBytes(design, training) + layerBytes,
                        o.display.empty() ? "the built-in display" : o.display,
                        "the training views of --layers " + o.layers,
                        "use fewer --train-eyes or a smaller display");
  }
  Scene scene = loadRenderScene(o);
  const SequencePlan plan = planSequence(o.sequence, scene);
  if (o.sequence.given()) prepareFraming(scene, plan);
  noteAnimation(o.sequence, scene, cliReporter());

  const Framing framing = frameForRender(o, scene, design);
  if (!o.quilt.empty()) {
    const std::unique_ptr<DisplayModel> display = makeBarrierDisplay(design);
    if (!o.sequence.given())
      return runQuiltRender(o, layout, *display, scene, settings, &framing,
                            displayFileText(design.spec), "display.json");
    reportFraming(framing);
    return runQuiltSequence(o, plan, layout, *display, scene, settings, &framing,
                            displayFileText(design.spec), "display.json");
  }
  reportFraming(framing);
  const double filmColumns =
      design.spec.imagePanel.width * (design.spec.subpixelRays ? 3.0 : 1.0) *
      (o.directMapping ? std::max(1.0, std::round(design.screenPeriodPx)) : 1.0);
  const AcceleratorOptions acceleratorOptions = acceleratorForCameraRays(
      filmColumns * design.spec.imagePanel.height * settings.samplesPerPixel);
  const auto renderFrame = [&](const Scene& posed, const Accelerator& accelerator,
                               const std::string& output, int frame) {
    renderLayers(o, posed, accelerator, design, framing, settings, filter, training, output,
                 frame ? &plan : nullptr, frame);
  };
  if (!o.sequence.given()) {
    const Accelerator accelerator(scene, acceleratorOptions);
    renderFrame(scene, accelerator, o.output, 0);
    return;
  }
  FrameJob job;
  job.reporter = &cliReporter();
  job.accelerator = acceleratorOptions;
  job.finished = [&](int frame) { return frameFinished(o.output, frame); };
  job.render = [&](const Scene& posed, const Accelerator& accelerator, int frame) {
    renderFrame(posed, accelerator, frameFolder(o.output, frame), frame);
  };
  runSequence(plan, scene, job);
  writeSequenceVideo(
      o.sequence, plan,
      [&](int frame) {
        return (std::filesystem::path(frameFolder(o.output, frame)) / "image.png").string();
      },
      cliReporter());
}

}  // namespace

void registerRenderCommand(CLI::App& cli) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* cmd =
      cli.add_subcommand("render", "Render the image and mask layers of a parallax display");
  CLI::Option* sceneOption =
      cmd->add_option("scene", options->scene, "Scene or mesh file (built-in scene if omitted)");
  addRgbdOptions(*cmd, options->rgbd)->excludes(sceneOption);
  addSceneLoadOptions(*cmd, options->load);
  cmd->add_option("--display", options->display,
                  "Display: a barrier display file, a lenticular calibration (visual.json), or a "
                  "Looking Glass preset lkg:NAME (built-in barrier display if omitted)");
  addSamplingOptions(*cmd, options->sampling,
                     "Rays per pixel: n*n stratified over pixel and aperture");
  addFilterOptions(*cmd, options->filter, "", "one view: a pixel column's angle at the gap");
  addFramingOptions(*cmd, options->framing, "");
  cmd->add_option("-o,--output", options->output, "Output folder")->capture_default_str();
  cmd->add_flag("--linear", options->linear, "Also write image.pfm, linear float");
  CLI::Option* direct =
      cmd->add_flag("--direct-mapping", options->directMapping,
                    "The usual practice as a baseline: N ordinary views, interleaved (Fig. 2)");
  CLI::Option* subpixels = cmd->add_flag("--subpixels", options->subpixels,
                                         "One ray per R, G, B subpixel (three times the views)");
  cmd->add_option("--quilt", options->quilt,
                  "Instead of the layers: C*R off-axis views of the display's window, leftmost "
                  "camera first, as DIR/quilt_qs{C}x{R}a{aspect}.png (docs/quilts.md); auto: a "
                  "Looking Glass device's own quilt, or one row of a barrier's views")
      ->type_name("CxR|auto")
      ->excludes(direct)
      ->excludes(subpixels);
  cmd->add_option("--layers", options->layers,
                  "slits: the paper's slit mask and ray-traced image; optimized-image: the image "
                  "layer solved for eyes across the view zone behind the same slits; nmf: both "
                  "layers solved (docs/content-adaptive.md)")
      ->capture_default_str();
  cmd->add_option("--rank", options->rank,
                  "With --layers nmf: time-multiplexed frame pairs (image-K.png, mask-K.png)")
      ->capture_default_str();
  cmd->add_option("--iterations", options->iterations, "Solver iterations (default 10)");
  cmd->add_option("--brightness", options->brightness,
                  "Brightness the optimised layers aim at, times the slits' (default 1 for "
                  "optimized-image, 1.05 max(2, rank) for nmf)");
  cmd->add_option("--layer-error", options->layerError,
                  "The optimised image layer's error: srgb (on sRGB values, as the dense "
                  "measure's PSNR; its default) or linear (light; nmf's only)");
  cmd->add_option("--train-eyes", options->trainEyesPerView,
                  "Training eyes per view at 0.8, 1 and 1.25 D for optimised layers")
      ->capture_default_str();
  cmd->add_option("--size", options->size,
                  "With --quilt: the size of one view (default: the device quilt's tile, or the "
                  "image layer's resolution)")
      ->type_name("WxH");
  addSequenceOptions(*cmd, options->sequence,
                     "the frames' image layers (with --quilt: their quilts)");
  cmd->callback([options] { runRender(*options); });
}

}  // namespace parallax::app
