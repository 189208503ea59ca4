// `parallax bench`: our rays per second against raw Embree on the same rays, in one run.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>
#include <optional>

#include "parallax/accel/accelerator.h"
#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/app/layer_output.h"
#include "parallax/camera/display_camera.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/io/json_writer.h"
#include "parallax/render/bench.h"
#include "parallax/render/display_render.h"
#include "parallax/sim/simulator.h"

#include <chrono>
#include <climits>

namespace parallax::app {

namespace {

// The simulator's benchmark: a sweep of `views` eyes across the view zone of the display, on
// layers rendered beforehand (not timed).
void benchSimulator(const std::string& displayPath, const std::string& scenePath, int views,
                    bool json) {
  const DisplayDesign design = loadDesignOrDefault(displayPath);
  const Scene scene = loadSceneOrDefault(scenePath);
  const Accelerator accelerator(scene);
  DisplayLayers layers = renderDisplay(scene, accelerator, design, {});
  const DisplaySimulator simulator(design, {std::move(layers.image), std::move(layers.mask)}, {});
  const BarrierRayGenerator rays(design);
  const auto start = std::chrono::steady_clock::now();
  double checksum = 0;
  for (int i = 0; i < views; ++i) {
    const Vec3d eye{
        design.spec.viewZoneCenterXMm + design.viewZoneWidthMm * ((i + 0.5) / views - 0.5),
        design.spec.viewZoneHeightMm, design.viewDistanceMm};
    checksum += double(simulator.view(eye).at(0, 0).x);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double samples = double(views) * simulator.outputWidth() * simulator.outputHeight();
  if (json) {
    JsonWriter out;
    out.set("/views", views);
    out.set("/width", simulator.outputWidth());
    out.set("/height", simulator.outputHeight());
    out.set("/seconds", seconds);
    out.set("/samples_per_second", samples / seconds);
    out.set("/peak_rss_mb", peakResidentMiB());
    std::printf("%s\n", out.dump().c_str());
  } else {
    std::printf(
        "simulator    %d views of %dx%d in %.3f s (%.1f M samples/s), peak memory %.0f MiB\n",
        views, simulator.outputWidth(), simulator.outputHeight(), seconds, samples / seconds / 1e6,
        peakResidentMiB());
  }
  (void)checksum;
}

struct BenchOptions {
  std::string camera = "pinhole";
  std::string scene, display;
  std::string size = "1920x1080";
  SamplingOptions sampling;
  int repeats = 2;
  bool json = false;
  int simulateViews = 0;
  FilterOptions filter;
};

void runBench(const BenchOptions& o) {
  if (o.simulateViews > 0) {
    const DisplayDesign design = loadDesignOrDefault(o.display);
    const Panel& panel = design.spec.imagePanel;
    checkLayerMemory(design, panel.width * (design.spec.subpixelRays ? 3.0 : 1.0), 1,
                     o.display.empty() ? "<built-in display>" : o.display);
    checkTimeEstimate(double(o.simulateViews) * panel.width * panel.height, o.sampling.threads,
                      "--simulate " + std::to_string(o.simulateViews), "time fewer views");
    return benchSimulator(o.display, o.scene, o.simulateViews, o.json);
  }
  int width = 0, height = 0;
  parseSize("--size", o.size, width, height);
  const RenderSettings settings = o.sampling.settings();
  // Before anything is allocated: the film and the limit's ray buffers (a few per pixel), and
  // the time of `repeats` alternating runs of ours and the two limits.
  checkMemoryEstimate(imageBytes(width, height) * 4, "--size " + o.size, "the film and rays",
                      "use a smaller size");
  checkPixelCount(double(width) * height, "--size " + o.size);
  o.sampling.checkWork(width, height, 3.0 * o.repeats);
  if (o.camera != "pinhole" && o.camera != "display")
    throw InputError("command line", "--camera",
                     "unknown camera '" + o.camera + "' (pinhole or display)");
  const Scene scene = loadSceneOrDefault(o.scene);
  std::unique_ptr<Camera> camera;
  std::optional<PinholeGrid> limitGrid;
  if (o.camera == "display") {
    // The display camera renders the image layer at its own resolution. Its limit is a
    // pinhole at the view-zone centre whose film is the front layer: the same content, seen
    // by the coherent rays of one eye.
    // Any display kind: a barrier's image layer, a lenticular panel's subpixels.
    const DisplayDescription description = loadDisplayOrDefault(o.display);
    std::unique_ptr<DisplayModel> display =
        description.kind == DisplayKind::Lenticular
            ? makeLenticularDisplay(designLenticular(description.lenticular), o.filter.filter())
            : makeBarrierDisplay(designDisplay(description.barrier), o.filter.filter());
    const Vec3d eye = display->window().eyeMm;
    camera = std::make_unique<DisplayCamera>(std::move(display), scene.display);
    width = camera->width(), height = camera->height();
    const DisplayCamera& displayCamera = static_cast<const DisplayCamera&>(*camera);
    limitGrid = WindowCamera(eye, displayCamera.display(), scene.display, width, height)
                    .grid(o.sampling.spp);
  }
  const CameraSpec spec = scene.camera ? *scene.camera : frameScene(scene);
  const PinholeCamera pinhole(spec.eye, spec.lookAt, spec.up, spec.fovDegrees, width, height);
  if (!limitGrid) limitGrid = pinhole.grid(o.sampling.spp);
  const Accelerator accelerator(scene);
  const Camera& measured = camera ? static_cast<const Camera&>(*camera) : pinhole;
  const BenchResult r = benchmark(scene, accelerator, measured, *limitGrid, settings, o.repeats);
  const double peak = peakResidentMiB();
  const double sameRaysRatio =
      r.sameRays.perSecond() > 0 ? r.ours.perSecond() / r.sameRays.perSecond() : 0.0;
  const double rayOrder =
      r.limit.perSecond() > 0 ? r.sameRays.perSecond() / r.limit.perSecond() : 0.0;
  if (o.json) {
    JsonWriter json;
    json.set("/camera", o.camera);
    if (o.camera == "display") json.set("/filter", o.filter.kind);
    json.set("/scene", scene.source);
    json.set("/triangles", uint64_t(scene.triangleCount()));
    json.set("/width", width);
    json.set("/height", height);
    json.set("/spp", o.sampling.spp);
    json.set("/jitter", o.sampling.jitter);
    json.set("/rays", r.ours.rays);
    json.set("/seconds", r.ours.seconds);
    json.set("/rays_per_second", r.ours.perSecond());
    json.set("/limit_rays", r.limit.rays);
    json.set("/limit_seconds", r.limit.seconds);
    json.set("/limit_rays_per_second", r.limit.perSecond());
    json.set("/ratio", r.ratio());
    json.set("/same_rays_limit_rays", r.sameRays.rays);
    json.set("/same_rays_limit_seconds", r.sameRays.seconds);
    json.set("/same_rays_limit_rays_per_second", r.sameRays.perSecond());
    json.set("/same_rays_ratio", sameRaysRatio);
    json.set("/ray_order_ratio", rayOrder);
    json.set("/peak_rss_mb", peak);
    std::printf("%s\n", json.dump().c_str());
    return;
  }
  std::printf("scene        %s (%zu triangles), %s camera, %dx%d, %d spp\n", scene.source.c_str(),
              scene.triangleCount(), o.camera.c_str(), width, height, o.sampling.spp);
  std::printf("parallax     %12llu rays in %.3f s  %s\n", (unsigned long long)r.ours.rays,
              r.ours.seconds, formatRate(r.ours.perSecond()).c_str());
  std::printf("raw Embree   %12llu rays in %.3f s  %s (coherent pinhole rays)\n",
              (unsigned long long)r.limit.rays, r.limit.seconds,
              formatRate(r.limit.perSecond()).c_str());
  std::printf("  same rays  %12llu rays in %.3f s  %s (this camera's rays, no shading)\n",
              (unsigned long long)r.sameRays.rays, r.sameRays.seconds,
              formatRate(r.sameRays.perSecond()).c_str());
  std::printf("ratio        %.2f  (ray order %.2f x shading %.2f)\npeak memory  %.0f MiB\n",
              r.ratio(), rayOrder, sameRaysRatio, peak);
}

}  // namespace

void registerBenchCommand(CLI::App& cli) {
  auto options = std::make_shared<BenchOptions>();
  CLI::App* cmd =
      cli.add_subcommand("bench", "Measure rays per second against raw Embree on the same rays");
  cmd->add_option("--camera", options->camera,
                  "Camera to measure: pinhole, or display (the image layer through the barrier)")
      ->capture_default_str();
  cmd->add_option("--display", options->display,
                  "Display for --camera display: a file of any kind, or lkg:NAME");
  addFilterOptions(*cmd, options->filter, "With --camera display: ", "as render --filter-width");
  cmd->add_option("--scene", options->scene, "Scene or mesh file (built-in scene if omitted)");
  cmd->add_option("--size", options->size,
                  "Image size WIDTHxHEIGHT (pinhole; the display camera uses the panel's)")
      ->capture_default_str();
  addSamplingOptions(*cmd, options->sampling, "Rays per pixel");
  cmd->add_option("--repeats", options->repeats, "Alternating runs; the fastest of each counts")
      ->capture_default_str()
      ->check(integerIn(1, INT_MAX));
  cmd->add_option("--simulate", options->simulateViews,
                  "Instead: time a sweep of N simulated views of the display (9 is the goal)")
      ->check(integerIn(0, INT_MAX));
  cmd->add_flag("--json", options->json, "Print one JSON object");
  cmd->callback([options] { runBench(*options); });
}

}  // namespace parallax::app
