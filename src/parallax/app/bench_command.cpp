// `parallax bench`: our rays per second against raw Embree on the same rays, in one run.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>

#include "parallax/accel/accelerator.h"
#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/camera/display_camera.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/io/json_writer.h"
#include "parallax/render/bench.h"
#include "parallax/render/display_render.h"
#include "parallax/sim/simulator.h"

#include <chrono>

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
  int spp = 16;
  int repeats = 2;
  int threads = 0;
  bool json = false;
  int simulateViews = 0;
};

void runBench(const BenchOptions& o) {
  if (o.simulateViews > 0) return benchSimulator(o.display, o.scene, o.simulateViews, o.json);
  int width = 0, height = 0;
  parseSize("--size", o.size, width, height);
  if (o.spp < 1) throw InputError("command line", "--spp", "must be at least 1");
  if (o.camera != "pinhole" && o.camera != "display")
    throw InputError("command line", "--camera",
                     "unknown camera '" + o.camera + "' (pinhole or display)");
  const Scene scene = loadSceneOrDefault(o.scene);
  std::unique_ptr<Camera> camera;
  if (o.camera == "display") {
    // The display camera renders the image layer at its own resolution.
    const DisplayDesign design = loadDesignOrDefault(o.display);
    camera = std::make_unique<DisplayCamera>(design, scene.display);
    width = camera->width(), height = camera->height();
  }
  const CameraSpec spec = scene.camera ? *scene.camera : frameScene(scene);
  const PinholeCamera pinhole(spec.eye, spec.lookAt, spec.up, spec.fovDegrees, width, height);
  const Accelerator accelerator(scene);
  const Camera& measured = camera ? static_cast<const Camera&>(*camera) : pinhole;
  const BenchResult r =
      benchmark(scene, accelerator, measured, pinhole, o.spp, o.repeats, o.threads);
  const double peak = peakResidentMiB();
  if (o.json) {
    JsonWriter json;
    json.set("/camera", o.camera);
    json.set("/scene", scene.source);
    json.set("/triangles", uint64_t(scene.triangleCount()));
    json.set("/width", width);
    json.set("/height", height);
    json.set("/spp", o.spp);
    json.set("/rays", r.rays);
    json.set("/seconds", r.seconds);
    json.set("/rays_per_second", r.raysPerSecond());
    json.set("/limit_rays", r.limitRays);
    json.set("/limit_seconds", r.limitSeconds);
    json.set("/limit_rays_per_second", r.limitRaysPerSecond());
    json.set("/ratio", r.ratio());
    json.set("/peak_rss_mb", peak);
    std::printf("%s\n", json.dump().c_str());
    return;
  }
  std::printf("scene        %s (%zu triangles), %s camera, %dx%d, %d spp\n", scene.source.c_str(),
              scene.triangleCount(), o.camera.c_str(), width, height, o.spp);
  std::printf("parallax     %12llu rays in %.3f s  %s\n", (unsigned long long)r.rays, r.seconds,
              formatRate(r.raysPerSecond()).c_str());
  std::printf("raw Embree   %12llu rays in %.3f s  %s (rtcIntersect16 + rtcOccluded16)\n",
              (unsigned long long)r.limitRays, r.limitSeconds,
              formatRate(r.limitRaysPerSecond()).c_str());
  std::printf("ratio        %.2f\npeak memory  %.0f MiB\n", r.ratio(), peak);
}

}  // namespace

void registerBenchCommand(CLI::App& cli) {
  auto options = std::make_shared<BenchOptions>();
  CLI::App* cmd =
      cli.add_subcommand("bench", "Measure rays per second against raw Embree on the same rays");
  cmd->add_option("--camera", options->camera,
                  "Camera to measure: pinhole, or display (the image layer through the barrier)")
      ->capture_default_str();
  cmd->add_option("--display", options->display, "Display file for --camera display");
  cmd->add_option("--scene", options->scene, "Scene or mesh file (built-in scene if omitted)");
  cmd->add_option("--size", options->size,
                  "Image size WIDTHxHEIGHT (pinhole; the display camera uses the panel's)")
      ->capture_default_str();
  cmd->add_option("--spp", options->spp, "Rays per pixel")->capture_default_str();
  cmd->add_option("--repeats", options->repeats, "Alternating runs; the fastest of each counts")
      ->capture_default_str();
  cmd->add_option("--threads", options->threads, "Worker threads (0: all cores)");
  cmd->add_option("--simulate", options->simulateViews,
                  "Instead: time a sweep of N simulated views of the display (9 is the goal)");
  cmd->add_flag("--json", options->json, "Print one JSON object");
  cmd->callback([options] { runBench(*options); });
}

}  // namespace parallax::app
