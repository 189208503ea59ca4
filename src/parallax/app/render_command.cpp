// `parallax render`: the two layer images of the display, and a record of how they were made.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/app/layer_output.h"
#include "parallax/camera/display_camera.h"
#include "parallax/camera/framing.h"
#include "parallax/core/error.h"
#include "parallax/io/display_file.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/render/display_render.h"
#include "parallax/render/quilt.h"

namespace parallax::app {

namespace {

struct RenderOptions {
  std::string scene, display;
  SamplingOptions sampling;
  std::string output = "out";
  bool linear = false;
  bool subpixels = false;
  bool directMapping = false;
  std::string quilt, size;  // --quilt CxR, --size WxH of one quilt view
  FilterOptions filter;
  FramingOptions framing;  // empty: the scene's (docs/display-geometry.md)
};

// The framing in the record: what was asked (fit, focus, depth_budget: simulate --reference
// frames the scene again from these) and what followed.
void recordFraming(JsonWriter& record, const Framing& f) {
  record.set("/framing/fit", displayFitName(f.fit));
  if (f.focusAuto)
    record.set("/framing/focus", "auto");
  else
    record.set("/framing/focus", f.focusMm);
  if (f.budgetAuto)
    record.set("/framing/depth_budget", "auto");
  else
    record.set("/framing/depth_budget", f.budgetMm);
  setFramingFigures(record, "/framing", f);
  record.set("/framing/virtual_gap_from_display_file", f.virtualGapFixed);
  record.set("/framing/scale_mm_per_unit", f.scaleMmPerUnit);
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
  std::printf("%s\n", depthSummary(framing).c_str());
  const std::string warning = depthWarning(framing);
  if (!warning.empty()) std::fprintf(stderr, "warning: %s\n", warning.c_str());
}

}  // namespace

namespace {

// `render --quilt CxR`: the C*R off-axis views of the display's window from eyes spread evenly
// across the view zone, tiled from the bottom-left into DIR/quilt_qs{C}x{R}a{aspect}.png
// (docs/quilts.md).
void runQuiltRender(const RenderOptions& o, QuiltLayout layout, const DisplayDesign& design,
                    const Scene& scene, const RenderSettings& settings, const Framing& framing) {
  int width = design.spec.imagePanel.width, height = design.spec.imagePanel.height;
  if (!o.size.empty()) parseSize("--size", o.size, width, height);
  checkQuiltWork(layout.columns, layout.rows, width, height, settings.samplesPerPixel,
                 settings.threads, o.size);
  layout.aspect = double(width) / height;
  const double windowAspect = design.frontWidthMm() / design.frontHeightMm();
  if (std::abs(layout.aspect / windowAspect - 1.0) > 0.01)
    std::fprintf(stderr,
                 "warning: --size %dx%d has aspect %.4f, the display's window %.4f: the views are "
                 "stretched\n",
                 width, height, layout.aspect, windowAspect);

  reportFraming(framing);
  const Accelerator accelerator(scene);
  RenderStats stats;
  std::vector<Image> views;
  {
    ProgressBar bar("render");
    views = renderQuiltViews(scene, accelerator, design, settings, layout.views(), width, height,
                             &stats, [&bar](int done, int total) { bar.update(done, total); });
  }
  const Image quilt = assembleQuilt(views, layout.columns, layout.rows);
  const double raysPerSecond = double(stats.totalRays()) / stats.seconds;

  const std::string name = quiltFileName("quilt", layout, ".png");
  JsonWriter record;
  startRenderRecord(record, "quilt", o.display);
  record.set("/scene", scene.source);
  record.set("/spp", o.sampling.spp);
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
    const Vec3d eye = quiltEyePosition(design, k, layout.views());
    record.set("/quilt/eyes_mm/" + std::to_string(k),
               Vec3f(float(eye.x), float(eye.y), float(eye.z)));
  }
  record.set("/outputs/quilt", name);
  recordFraming(record, framing);
  writeDesignJson(record, "/design", design);
  const std::string linearName = quiltFileName("quilt", layout, ".pfm");
  if (o.linear) record.set("/outputs/quilt_linear", linearName);

  OutputSet set(o.output);
  const std::string dir = set.dir();
  writeImage(set.path(name), quilt);
  if (o.linear) writeImage(set.path(linearName), quilt);
  writeFileAtomically(set.path("display.json"), displayFileText(design.spec));
  writeFileAtomically(set.path("render.json"), record.dump() + "\n");
  set.commit();
  std::printf("wrote %s/%s (%d views of %dx%d), %s/render.json\n", dir.c_str(), name.c_str(),
              layout.views(), width, height, dir.c_str());
  std::printf("%d spp in %.2f s, %s\n", o.sampling.spp, stats.seconds,
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
  if (!o.quilt.empty() && !parseColumnsByRows(o.quilt, layout.columns, layout.rows))
    throw InputError("command line", "--quilt", "expected COLUMNSxROWS, got '" + o.quilt + "'");
  DisplayDesign design = loadDesignOrDefault(o.display);
  if (o.subpixels) {
    DisplaySpec spec = design.spec;
    spec.subpixelRays = true;
    design = designDisplay(spec);
  }
  if (o.quilt.empty())
    checkLayerWork(design, o.directMapping, settings.samplesPerPixel, settings.threads, o.display);
  Scene scene = loadSceneReportingWarnings(o.scene);
  const Framing framing = frameForRender(o, scene, design);
  if (!o.quilt.empty()) return runQuiltRender(o, layout, design, scene, settings, framing);
  reportFraming(framing);
  const Accelerator accelerator(scene);
  DisplayLayers layers;
  {
    ProgressBar bar("render");
    const auto onProgress = [&bar](int done, int total) { bar.update(done, total); };
    layers = o.directMapping
                 ? renderDirectMapping(scene, accelerator, design, settings, onProgress)
                 : renderDisplay(scene, accelerator, design, settings, onProgress, filter);
  }
  const double raysPerSecond = double(layers.stats.totalRays()) / layers.stats.seconds;

  JsonWriter record;
  startRenderRecord(record, o.directMapping ? "direct-mapping" : "barrier-camera", o.display);
  record.set("/scene", scene.source);
  record.set("/spp", settings.samplesPerPixel);
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
  writeDisplayLayers(o.output, layers.image, layers.mask, design, o.linear, record);
  std::printf("%d spp in %.2f s, %s\n", settings.samplesPerPixel, layers.stats.seconds,
              formatRate(raysPerSecond).c_str());
}

}  // namespace

void registerRenderCommand(CLI::App& cli) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* cmd =
      cli.add_subcommand("render", "Render the image and mask layers of a parallax display");
  cmd->add_option("scene", options->scene, "Scene or mesh file (built-in scene if omitted)");
  cmd->add_option("--display", options->display, "Display file (built-in display if omitted)");
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
                  "camera first, as DIR/quilt_qs{C}x{R}a{aspect}.png (docs/quilts.md)")
      ->type_name("CxR")
      ->excludes(direct)
      ->excludes(subpixels);
  cmd->add_option("--size", options->size,
                  "With --quilt: the size of one view (default: the image layer's resolution)")
      ->type_name("WxH");
  cmd->callback([options] { runRender(*options); });
}

}  // namespace parallax::app
