// One frame of the render runner: the display camera's layers (or direct mapping, or a lenticular
// panel's picture, or solved layers) and quilts, each with its render.json record.
#include "parallax/jobs/render_parts.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "parallax/camera/display_camera.h"
#include "parallax/cluster/process_group.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/core/parallel.h"
#include "parallax/io/image_file.h"
#include "parallax/jobs/distributed.h"
#include "parallax/jobs/layer_output.h"
#include "parallax/jobs/limits.h"
#include "parallax/layers/training.h"
#include "parallax/render/display_render.h"

namespace parallax::jobs {

namespace {

// What the display file was recognised as, where that decides the default quilt.
void noteDevice(const DisplayModel& display, Reporter& reporter) {
  if (!writesJobOutputs()) return;
  if (const std::string note = display.deviceNote(); !note.empty()) reporter.note(note);
}

}  // namespace

void planQuilt(const RenderRequest& r, const DisplayModel& display, RenderPlan& plan,
               Reporter& reporter) {
  QuiltLayout& layout = plan.layout;
  layout.columns = r.quilt.columns, layout.rows = r.quilt.rows;
  if (layout.columns == 0) {  // auto: the device's quilt, or one row of the barrier's views
    noteDevice(display, reporter);
    layout.columns = display.defaultQuilt().columns;
    layout.rows = display.defaultQuilt().rows;
  }
  int width = display.quiltTile(layout.columns, layout.rows).width;
  int height = display.quiltTile(layout.columns, layout.rows).height;
  const bool sized = r.quilt.width > 0;
  if (sized) width = r.quilt.width, height = r.quilt.height;
  if (width < 1 || height < 1)
    throw RequestError("quilt", "the device's quilt is too small for " +
                                    std::to_string(layout.columns) + "x" +
                                    std::to_string(layout.rows) + " tiles");
  checkQuiltWork(layout.columns, layout.rows, width, height, plan.settings.samplesPerPixel,
                 plan.settings.threads,
                 sized ? std::to_string(width) + "x" + std::to_string(height) : "", r.linear);
  plan.tileWidth = width, plan.tileHeight = height;
  const DisplayWindow window = display.window();
  const double windowAspect = window.widthMm / window.heightMm;
  // The name's aspect is the display's (Looking Glass's convention), whatever the tiles' shape.
  layout.aspect = windowAspect;
  const double tileAspect = double(width) / height;
  if (std::abs(tileAspect / windowAspect - 1.0) > 0.01 && writesJobOutputs())
    reporter.note(
        printed("tiles of %dx%d have aspect %.4f, the display's window %.4f: the views "
                "are stretched to fill them, as Looking Glass quilts are (the name says a%s, "
                "the display's aspect)",
                width, height, tileAspect, windowAspect, formatQuiltAspect(windowAspect).c_str()));
}

void checkPictureWork(const DisplayModel& display, bool directMapping,
                      const RenderSettings& settings, const std::string& subject) {
  if (const DisplayDesign* design = display.barrierDesign())
    return checkLayerWork(*design, directMapping, settings.samplesPerPixel, settings.threads,
                          subject == "<built-in display>" ? "" : subject);
  // One panel picture: the film, the picture and its 8-bit copy.
  const FilmLayout film = display.film();
  checkMemoryEstimate(imageBytes(film.columns, film.rows) +
                          imageBytes(film.panelWidth, film.panelHeight) +
                          imageBytes(film.panelWidth, film.panelHeight, kRgba8PixelBytes),
                      display.source(), "the panel image", "use a smaller panel");
  checkTimeEstimate(double(film.columns) * film.rows * settings.samplesPerPixel, settings.threads,
                    "spp", std::to_string(settings.samplesPerPixel), "use fewer samples");
}

namespace {

// What one frame's pictures hold at their peak, in bytes, and what that is.
std::pair<double, std::string> framePictureBytes(const RenderRequest& r, const RenderPlan& plan,
                                                 const DisplayModel& display, bool inMemory) {
  // Per pixel of a finished picture: a PNG's 8-bit codes and the encoder's filtered rows, or the
  // caller's float copy.
  const double handedOver = inMemory ? kFloatRgbPixelBytes : 2 * kRgb8PixelBytes;
  if (r.quilt.wanted) {
    // The quilt's 8-bit codes and the PNG encoder's filtered rows; with --linear the float quilt
    // and, as it is written, the PFM's bytes (the PNG's codes and rows are freed before). Beside
    // them, one view's film and its copy in the tile.
    const double views = plan.layout.views(), w = plan.tileWidth, h = plan.tileHeight;
    const double perPixel = r.linear ? 2 * kFloatRgbPixelBytes : 2 * kRgb8PixelBytes;
    return {imageBytes(w, h, perPixel, views) + imageBytes(w, h, kFloatRgbPixelBytes, 2),
            "the quilt"};
  }
  const FilmLayout film = display.film();
  const DisplayDesign* design = display.barrierDesign();
  if (!design) {
    // A lenticular panel: the film, then the panel picture, its 8-bit codes and the encoder's
    // rows.
    return {
        std::max(imageBytes(film.columns, film.rows),
                 imageBytes(film.panelWidth, film.panelHeight, kFloatRgbPixelBytes + handedOver)) +
            imageBytes(film.panelWidth, film.panelHeight),
        "the panel image"};
  }
  const Panel &image = design->spec.imagePanel, &mask = design->spec.maskPanel;
  const double subpixel = design->camera.subpixelRays ? 3.0 : 1.0;
  const double views =
      r.directMapping ? std::max(1.0, std::round(design->screenPeriodPx * subpixel)) : 1.0;
  // While rendering: the film (one per view with direct mapping) and the image layer made from
  // it. Then each layer as rendered, its copy in the frame set, its 8-bit codes and the PNG
  // encoder's rows, and the image layer's picture once more (72 bytes a pixel of a display
  // without subpixel rays, measured at 480x270 to 4000x4000, whatever the film).
  // In memory the same, measured: the caller's copy is made once the frame set's copies are gone.
  const double perLayerPixel = 2 * kFloatRgbPixelBytes + 2 * kRgb8PixelBytes;
  const double layers =
      std::max(imageBytes(film.columns, film.rows, kFloatRgbPixelBytes, views) +
                   imageBytes(image.width, image.height, kFloatRgbPixelBytes,
                              r.directMapping ? 2.0 : 1.0),  // direct mapping: interleaved too
               imageBytes(image.width, image.height, perLayerPixel + kFloatRgbPixelBytes) +
                   imageBytes(mask.width, mask.height, perLayerPixel));
  if (!r.layers.solved()) return {layers, "the layers"};
  // Solved layers: the slits' layers stay while the solver holds its training views (their
  // ideal images and the eyes' sampling tables) and per frame two layers and their gradients.
  const double solver =
      trainingHeldBytes(*design, plan.training, r.layers.methodKind()) +
      imageBytes(image.width, image.height, kFloatRgbPixelBytes, 4.0 * r.layers.rank + 6.0) +
      imageBytes(image.width, image.height) + imageBytes(mask.width, mask.height);
  return {std::max(layers, solver), "the training views of {layers} " + r.layers.method};
}

}  // namespace

void checkRenderMemory(const RenderRequest& r, const RenderPlan& plan, const DisplayModel& display,
                       const Scene& scene, const std::string& subject, bool inMemory) {
  const auto [bytes, what] = framePictureBytes(r, plan, display, inMemory);
  checkPeakMemory(acceleratorBytes(scene) + bytes, subject, "the scene's BVH and " + what,
                  r.quilt.wanted ? "use fewer views or a smaller {size}"
                                 : "use a smaller display or a simpler scene");
}

AcceleratorOptions cameraRayAccelerator(const RenderRequest& r, const RenderPlan& plan,
                                        const DisplayModel& display) {
  const double spp = plan.settings.samplesPerPixel;
  if (r.quilt.wanted)
    return acceleratorForCameraRays(double(plan.layout.views()) * plan.tileWidth * plan.tileHeight *
                                    spp);
  const FilmLayout film = display.film();
  const double views = r.directMapping ? display.directMappingViews() : 1.0;
  return acceleratorForCameraRays(double(film.columns) * film.rows * views * spp);
}

namespace {

// The top of every record: program, version, method, display, imports.
void startRecord(JsonWriter& record, const FrameTarget& t, const std::string& method,
                 const Scene& scene) {
  const RenderRequest& r = *t.request;
  // A display made in code has no file: the record names it by its model's source.
  const std::string displayFile =
      t.display->file.written() ? r.display.path : (*t.display)->source();
  startRenderRecord(record, method, displayFile, r.scene.load.import, scene.imports);
}

void recordSampling(JsonWriter& record, const RenderRequest& r, const RenderSettings& settings) {
  record.set("/spp", settings.samplesPerPixel);
  record.set("/bounces", settings.bounces);
  record.set("/seed", r.sampling.seed);
  record.set("/jitter", r.sampling.jitter);
  record.set("/threads", r.sampling.threads);
}

void recordSpeed(JsonWriter& record, const RenderStats& stats) {
  record.set("/seconds", stats.seconds);
  record.set("/rays", stats.totalRays());
  record.set("/rays_per_second", double(stats.totalRays()) / stats.seconds);
  if (stats.splatsEvaluated) {
    record.set("/splats_evaluated", stats.splatsEvaluated);
    record.set("/splats_blended", stats.splatsBlended);
  }
}

std::string speedLine(int spp, const RenderStats& stats) {
  return printed("%d spp in %.2f s, %s%s", spp, stats.seconds,
                 formatRate(double(stats.totalRays()) / stats.seconds).c_str(),
                 splatClause(stats.splatsEvaluated, stats.splatsBlended, stats.cameraRays).c_str());
}

// A frame's pictures and record, before they are written or handed over.
struct FramePictures {
  std::vector<LayerFrame> frames;
  Image quilt;                 // a float quilt (linear or in memory)
  std::vector<uint8_t> codes;  // a quilt as its PNG's 8-bit codes (files, not linear)
  JsonWriter record;
  RenderStats stats;
  int spp = 0;
  double solveSeconds = 0;  // the layer solver's, ideal views included (0: not solved)
};

// The display camera's layers of one (posed) scene, solved if asked. False when this rank does
// not write them (mpirun).
bool renderLayers(const FrameTarget& t, const Scene& scene, const Accelerator& accelerator,
                  Reporter& reporter, FramePictures& out) {
  const RenderRequest& r = *t.request;
  const RenderPlan& plan = *t.plan;
  const BuiltDisplay& display = *t.display;
  const RenderSettings& settings = plan.settings;
  // One frame under mpirun: each rank renders its bands, rank 0 writes (docs/distributed.md).
  // The layer solvers need the whole slit layers and fit them globally: rank 0 alone runs them.
  const bool split = !t.sequence && !r.layers.solved();
  if (!t.sequence && !split && !writesJobOutputs()) return false;
  if (!t.sequence && !split && cluster::world().size() > 1)
    reporter.note("{layers} " + r.layers.method +
                  " is not split across ranks: rank 0 renders it alone");
  const bool layered = display->hasMaskLayer();
  DisplayLayers layers;
  {
    const auto progress = reporter.progress(layered ? "render" : "lenticular render");
    const RenderSettings share = split ? frameShare(settings) : settings;
    layers = r.directMapping
                 ? renderDirectMapping(scene, accelerator, *display, share, progress->callback())
                 : renderDisplay(scene, accelerator, *display, share, progress->callback());
  }
  if (split && !mergeFrameShares({&layers.image}, layers.stats, reporter)) return false;

  const std::string method = !layered          ? "lenticular: rays per subpixel around its view"
                             : r.directMapping ? "direct-mapping"
                                               : "barrier-camera";
  JsonWriter& record = out.record;
  startRecord(record, t, method, scene);
  if (layered) record.set("/layers/method", r.layers.method);
  out.frames = {{layers.image, layers.mask}};
  if (r.layers.solved()) {
    const auto solveStart = std::chrono::steady_clock::now();
    out.frames = solveLayers(r.layers, scene, accelerator, solvedBarrier(*display), plan.training,
                             out.frames[0], record, reporter);
    out.solveSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - solveStart).count();
  }
  recordScene(record, r.scene, scene);
  recordSampling(record, r, settings);
  record.set("/adaptive", settings.adaptive);
  if (settings.adaptive) {
    const FilmLayout film = display->film();
    record.set("/adaptive_threshold_8bit", settings.adaptiveThreshold * 255.0);
    record.set("/camera_rays", layers.stats.cameraRays);
    record.set("/mean_spp",
               double(layers.stats.cameraRays) / (double(film.columns) * double(film.rows)));
  }
  if (!r.directMapping) {
    record.set("/filter/kind", viewFilterName(plan.filter.kind));
    record.set("/filter/width_views", plan.filter.widthViews);
  }
  recordSpeed(record, layers.stats);
  record.set("/scene_display/center", scene.display.center);
  record.set("/scene_display/normal", scene.display.normal);
  record.set("/scene_display/up", scene.display.up);
  record.set("/scene_display/width", double(fitDisplayWidth(scene.display, display->window())));
  if (display.framing) recordFraming(record, *display.framing);
  if (t.sequence) recordSequence(record, *t.sequence, t.frame);
  if (t.madeFrom) recordMadeFrom(record, *t.madeFrom);
  display.recordDesign(record, "/design");
  out.stats = layers.stats;
  out.spp = settings.samplesPerPixel;
  return true;
}

// The quilt's views of one (posed) scene. `codes`: kept as 8-bit codes (a PNG to write).
bool renderQuiltFrame(const FrameTarget& t, const Scene& scene, const Accelerator& accelerator,
                      bool codes, Reporter& reporter, FramePictures& out) {
  const RenderRequest& r = *t.request;
  const RenderPlan& plan = *t.plan;
  const DisplayModel& display = **t.display;
  const QuiltLayout& layout = plan.layout;
  const int width = plan.tileWidth, height = plan.tileHeight;
  // One quilt alone is split across mpirun's ranks by bands of every view's rows; a sequence's
  // quilts are whole frames of one rank (docs/distributed.md).
  const RenderSettings share = t.sequence ? plan.settings : frameShare(plan.settings);
  const int quiltWidth = layout.columns * width, quiltHeight = layout.rows * height;
  {
    const auto progress = reporter.progress("render");
    if (!codes) {
      out.quilt = renderQuilt(scene, accelerator, display, share, layout, width, height, &out.stats,
                              progress->callback());
    } else {
      out.codes.resize(size_t(quiltWidth) * size_t(quiltHeight) * 3);
      const auto keepCodes = [&](int, int left, int top, const Image& view) {
        parallelFor(view.height(), 0, 16, [&](int64_t begin, int64_t end) {
          for (int64_t y = begin; y < end; ++y) {
            uint8_t* row =
                out.codes.data() + (size_t(top + y) * size_t(quiltWidth) + size_t(left)) * 3;
            linearToSrgb8(&view.at(0, int(y)).x, 3 * size_t(view.width()), row);
          }
        });
      };
      renderQuiltTiles(scene, accelerator, display, share, layout, width, height, keepCodes,
                       &out.stats, progress->callback());
    }
  }
  if (!t.sequence) {
    const bool writer = codes ? mergeFrameShares(out.codes, out.stats, reporter)
                              : mergeFrameShares({&out.quilt}, out.stats, reporter);
    if (!writer) return false;
  }
  JsonWriter& record = out.record;
  startRecord(record, t, "quilt", scene);
  record.set("/display_kind", displayKindName(display.kind()));
  recordScene(record, r.scene, scene);
  recordSampling(record, r, plan.settings);
  recordSpeed(record, out.stats);
  record.set("/quilt/columns", layout.columns);
  record.set("/quilt/rows", layout.rows);
  record.set("/quilt/view_size", std::to_string(width) + "x" + std::to_string(height));
  record.set("/quilt/aspect", layout.aspect);  // the display's, as the name's `a` (docs/quilts.md)
  record.set("/quilt/order", "view 0 = leftmost camera = bottom-left tile, rightward then upward");
  for (int k = 0; k < layout.views(); ++k) {
    const Vec3d eye = quiltEyePosition(display, k, layout.views());
    record.set("/quilt/eyes_mm/" + std::to_string(k),
               Vec3f(float(eye.x), float(eye.y), float(eye.z)));
  }
  record.set("/quilt/file_name", quiltFileName("quilt", layout, ".png"));
  record.set("/outputs/quilt", quiltFileName("quilt", layout, ".png"));
  if (t.display->framing) recordFraming(record, *t.display->framing);
  t.display->recordDesign(record, "/design");
  if (r.linear) record.set("/outputs/quilt_linear", quiltFileName("quilt", layout, ".pfm"));
  if (t.sequence) recordSequence(record, *t.sequence, t.frame);
  if (t.madeFrom) recordMadeFrom(record, *t.madeFrom);
  out.spp = r.sampling.spp;
  return true;
}

void writeQuilt(const FrameTarget& t, FramePictures& pictures, Reporter& reporter) {
  const RenderRequest& r = *t.request;
  const QuiltLayout& layout = t.plan->layout;
  const std::string name = quiltFileName("quilt", layout, ".png");
  OutputSet set(t.output);
  if (r.linear) {
    writeImage(set.path(name), pictures.quilt);
    writeImage(set.path(quiltFileName("quilt", layout, ".pfm")), pictures.quilt);
  } else {
    writeFileAtomically(set.path(name),
                        pngBytesFromSrgb8(pictures.codes, layout.columns * t.plan->tileWidth,
                                          layout.rows * t.plan->tileHeight));
  }
  if (t.display->file.written())
    writeFileAtomically(set.path(t.display->file.name), t.display->file.text);
  writeFileAtomically(set.path("render.json"), pictures.record.dump() + "\n");
  set.commit();
  const std::string dir = set.dir();
  reporter.result(printed("wrote %s/%s (%d views of %dx%d), %s/render.json", dir.c_str(),
                          name.c_str(), layout.views(), t.plan->tileWidth, t.plan->tileHeight,
                          dir.c_str()));
}

}  // namespace

void renderFrameToFiles(const FrameTarget& t, const Scene& scene, const Accelerator& accelerator,
                        Reporter& reporter) {
  const RenderRequest& r = *t.request;
  FramePictures pictures;
  if (r.quilt.wanted) {
    if (!renderQuiltFrame(t, scene, accelerator, !r.linear, reporter, pictures)) return;
    writeQuilt(t, pictures, reporter);
    reporter.result(speedLine(pictures.spp, pictures.stats));
    return;
  }
  if (!renderLayers(t, scene, accelerator, reporter, pictures)) return;
  reporter.result(
      writePictureSet(t.output, pictures.frames, r.linear, t.display->file, pictures.record));
  std::string speed = speedLine(pictures.spp, pictures.stats);
  // The solve is most of such a render's time: the summary says so, not only the rays'.
  if (pictures.solveSeconds > 0)
    speed +=
        printed("; layers %s solved in %.1f s", r.layers.method.c_str(), pictures.solveSeconds);
  speed = (*t.display)->summaryClause() + speed;
  reporter.result(speed);
}

RenderResult renderFrameInMemory(const FrameTarget& t, const Scene& scene,
                                 const Accelerator& accelerator, Reporter& reporter) {
  FramePictures pictures;
  RenderResult result;
  if (t.request->quilt.wanted) {
    renderQuiltFrame(t, scene, accelerator, false, reporter, pictures);
    result.quilt = std::move(pictures.quilt);
  } else {
    renderLayers(t, scene, accelerator, reporter, pictures);
    result.frames = std::move(pictures.frames);
  }
  result.record = pictures.record.dump();
  return result;
}

}  // namespace parallax::jobs
