// `parallax bench`: our rays per second against raw Embree on the same rays, in one run.
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "parallax/accel/accelerator.h"
#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/camera/display_camera.h"
#include "parallax/core/error.h"
#include "parallax/core/lane_kernel.h"
#include "parallax/core/memory.h"
#include "parallax/core/parallel.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/layer_output.h"
#include "parallax/jobs/render_parts.h"
#include "parallax/jobs/reporter.h"
#include "parallax/layers/training.h"
#include "parallax/render/bench.h"
#include "parallax/render/display_render.h"
#include "parallax/sim/simulator.h"

#include <unistd.h>
#include <chrono>
#include <climits>
#include <filesystem>
#include <type_traits>
#include <vector>

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

// The layer solvers' benchmark (docs/speed.md, "Layer solvers"): what `render --layers METHOD`
// spends on its training views and on its solve, with the solve's passes over the training
// targets, against the physical limit of a solver that reads every target once per iteration
// at this machine's memory bandwidth (streamingPassSeconds of the targets' bytes).
void benchLayers(const std::string& displayPath, const std::string& scenePath,
                 const jobs::LayersRequest& request, const SamplingRequest& sampling, bool json) {
  request.check();
  const DisplayDesign design = loadDesignOrDefault(displayPath);
  const TrainingOptions training =
      jobs::trainingOptions(request, sampling.threads, 0, sampling.seed);
  const Panel& panel = design.spec.imagePanel;
  checkMemoryEstimate(
      trainingHeldBytes(design, training, request.method) +
          double(panel.width) * panel.height * sizeof(Vec3f) * (4.0 * request.rank + 6.0),
      displayPath.empty() ? "the built-in display" : displayPath,
      "the training views of --layers " + request.method, "use a smaller display");
  const Scene scene = loadSceneOrDefault(scenePath);
  const Accelerator accelerator(scene);
  // The slit layers the solve starts from, rendered as `render` renders them.
  DisplayLayers slits = renderDisplay(scene, accelerator, design, sampling.settings());
  jobs::LayerSolveFigures figures;
  JsonWriter record;
  jobs::solveLayers(request, scene, accelerator, design, training,
                    {std::move(slits.image), std::move(slits.mask)}, record, jobs::silentReporter(),
                    &figures);
  const double pass = streamingPassSeconds(figures.targetBytes, sampling.threads);
  const double limit = pass * figures.iterations;
  const double ratio = figures.solveSeconds > 0 ? limit / figures.solveSeconds : 0.0;
  const double perPass = figures.passes > 0 ? figures.solveSeconds / figures.passes : 0.0;
  if (json) {
    JsonWriter out;
    out.set("/layers/method", request.method);
    out.set("/layers/rank", request.rank);
    out.set("/layers/width", panel.width);
    out.set("/layers/height", panel.height);
    out.set("/layers/eyes", figures.eyes);
    out.set("/layers/iterations", figures.iterations);
    out.set("/layers/passes", figures.passes);
    out.set("/layers/target_bytes", figures.targetBytes);
    out.set("/layers/training_seconds", figures.trainingSeconds);
    out.set("/layers/solve_seconds", figures.solveSeconds);
    out.set("/layers/pass_seconds", perPass);
    out.set("/layers/streaming_pass_seconds", pass);
    out.set("/layers/limit_seconds", limit);
    out.set("/layers/ratio", ratio);
    out.set("/peak_rss_mb", peakResidentMiB());
    std::printf("%s\n", out.dump().c_str());
    return;
  }
  std::printf(
      "layers       %s%s on %dx%d, %d training eyes: ideal views %.2f s, solve %.2f s "
      "(%d iterations, %d passes over the targets, %.3f s each)\n"
      "limit        one pass over the targets (%.0f MiB) per iteration at memory bandwidth: "
      "%.4f s a pass, %.3f s in all\n"
      "ratio        %.4f (limit / solve); a pass costs %.0fx a streaming read of the targets\n"
      "peak memory  %.0f MiB\n",
      request.method.c_str(),
      request.method == "nmf" ? (" rank " + std::to_string(request.rank)).c_str() : "", panel.width,
      panel.height, figures.eyes, figures.trainingSeconds, figures.solveSeconds, figures.iterations,
      figures.passes, perPass, figures.targetBytes / (1 << 20), pass, limit, ratio,
      pass > 0 ? perPass / pass : 0.0, peakResidentMiB());
}

struct BenchOptions {
  std::string camera = "pinhole";
  std::string scene, display;
  std::string size = "1920x1080";
  SamplingRequest sampling;
  int repeats = 2;
  bool json = false;
  int simulateViews = 0;
  jobs::LayersRequest layers;  // method "slits": no layer bench
  int packetWidth = 0;
  std::string quality = "auto";
  FilterRequest filter;
};

// One step of what `parallax render` does, timed, with the process's peak memory after it.
struct Phase {
  const char* name;
  double seconds;
  double peakMiB;
};

class PhaseClock {
 public:
  template <class Step>
  auto run(const char* name, const Step& step) {
    const auto start = std::chrono::steady_clock::now();
    if constexpr (std::is_void_v<decltype(step())>) {
      step();
      record(name, start);
    } else {
      auto result = step();
      record(name, start);
      return result;
    }
  }
  const std::vector<Phase>& phases() const { return phases_; }
  double total() const {
    double sum = 0;
    for (const Phase& p : phases_) sum += p.seconds;
    return sum;
  }
  double seconds(const std::string& name) const {
    for (const Phase& p : phases_)
      if (name == p.name) return p.seconds;
    return 0.0;
  }

 private:
  void record(const char* name, std::chrono::steady_clock::time_point start) {
    phases_.push_back(
        {name, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
         peakResidentMiB()});
  }
  std::vector<Phase> phases_;
};

BuildQuality parseQuality(const std::string& text) {
  if (text == "auto") return BuildQuality::Auto;
  if (text == "medium") return BuildQuality::Medium;
  if (text == "high") return BuildQuality::High;
  throw InputError("command line", "--bvh-quality",
                   "unknown quality '" + text + "' (auto, medium or high)");
}

const char* qualityName(BuildQuality quality) {
  return quality == BuildQuality::High     ? "high"
         : quality == BuildQuality::Medium ? "medium"
                                           : "auto";
}

// The rest of `parallax render` after the render loop: the layers' PNGs (at once, as render
// writes them) and their files, written into a temporary folder that is removed afterwards.
void encodeAndWrite(PhaseClock& clock, const Image& image, const Image& mask) {
  std::string imagePng, maskPng;
  clock.run("encode", [&] {
    parallelInvoke(
        0, [&] { imagePng = pngBytes(image); },
        [&] {
          if (!mask.empty()) maskPng = pngBytes(mask);
        });
  });
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("parallax-bench-" + std::to_string(::getpid()));
  clock.run("write", [&] {
    writeFileAtomically((folder / "image.png").string(), imagePng);
    if (!maskPng.empty()) writeFileAtomically((folder / "mask.png").string(), maskPng);
  });
  std::error_code ignored;
  std::filesystem::remove_all(folder, ignored);
}

void runBench(const BenchOptions& o) {
  if (o.layers.solved()) return benchLayers(o.display, o.scene, o.layers, o.sampling, o.json);
  if (o.simulateViews > 0) {
    const DisplayDesign design = loadDesignOrDefault(o.display);
    const Panel& panel = design.spec.imagePanel;
    checkLayerMemory(design, panel.width * (design.camera.subpixelRays ? 3.0 : 1.0), 1,
                     o.display.empty() ? "<built-in display>" : o.display);
    checkTimeEstimate(double(o.simulateViews) * panel.width * panel.height, o.sampling.threads,
                      "simulate", std::to_string(o.simulateViews), "time fewer views");
    return benchSimulator(o.display, o.scene, o.simulateViews, o.json);
  }
  int width = 0, height = 0;
  parseSize("--size", o.size, width, height);
  const RenderSettings settings = o.sampling.settings();
  // Before anything is allocated: the film and the limit's ray buffers (a few per pixel), and
  // the time of `repeats` alternating runs of ours and the three limits, and one more render.
  checkMemoryEstimate(imageBytes(width, height) * 4, "--size " + o.size, "the film and rays",
                      "use a smaller size");
  checkPixelCount(double(width) * height, "--size " + o.size);
  o.sampling.checkWork(width, height, 4.0 * o.repeats + 1.0);
  if (o.camera != "pinhole" && o.camera != "display")
    throw InputError("command line", "--camera",
                     "unknown camera '" + o.camera + "' (pinhole or display)");
  AcceleratorOptions acceleratorOptions;
  acceleratorOptions.packetWidth = o.packetWidth;
  acceleratorOptions.quality = parseQuality(o.quality);

  PhaseClock clock;
  // Load: the scene and, for the display camera, the display.
  std::unique_ptr<DisplayModel> display;
  const Scene scene = clock.run("load", [&] {
    if (o.camera == "display") {
      const DisplayDescription description = loadDisplayOrDefault(o.display);
      jobs::DisplayCameraRequest camera;
      camera.filter = o.filter.filter();
      display = jobs::makeDisplay(description, camera).model;
    }
    return loadSceneOrDefault(o.scene);
  });
  std::unique_ptr<Camera> camera;
  std::optional<PinholeGrid> limitGrid;
  std::vector<PinholeGrid> viewGrids;
  const DisplayModel* model = display.get();
  if (display) {
    // The display camera renders the image layer at its own resolution. Its limit is a
    // pinhole at the view-zone centre whose film is the front layer: the same content, seen
    // by the coherent rays of one eye.
    const Vec3d eye = display->window().eyeMm;
    camera = std::make_unique<DisplayCamera>(std::move(display), scene.display);
    width = camera->width(), height = camera->height();
    limitGrid = WindowCamera(eye, *model, scene.display, width, height).grid(o.sampling.spp);
    // The views' limit: each view eye's pinhole at its share of the film's columns.
    const int views = std::max(1, model->viewCount());
    const int viewWidth = std::max(1, int(std::lround(double(width) / views)));
    for (int v = 0; v < views; ++v)
      viewGrids.push_back(
          WindowCamera(model->viewPosition(v), *model, scene.display, viewWidth, height)
              .grid(o.sampling.spp));
    // The panel's film, and a lenticular panel's quilt route (timed below), before either is
    // allocated.
    checkMemoryEstimate(imageBytes(width, height) * 4 + quiltRouteBytes(*model),
                        "--display " + o.display, "the panel's film and its quilt route",
                        "use a smaller display");
  }
  const CameraSpec spec = scene.camera ? *scene.camera : frameScene(scene);
  const PinholeCamera pinhole(spec.eye, spec.lookAt, spec.up, spec.fovDegrees, width, height);
  if (!limitGrid) limitGrid = pinhole.grid(o.sampling.spp);
  const Camera& measured = camera ? static_cast<const Camera&>(*camera) : pinhole;
  // The render's camera rays and about as many shadow rays: what the BVH quality is chosen by.
  acceleratorOptions.expectedRays = 2.0 * double(width) * height * settings.samplesPerPixel;
  const Accelerator accelerator =
      clock.run("bvh", [&] { return Accelerator(scene, acceleratorOptions); });
  // One render as `parallax render` runs it (cold), then its outputs.
  Image image, mask;
  clock.run("render", [&] {
    if (model) {
      DisplayLayers layers = renderDisplay(scene, accelerator, *model, settings);
      image = std::move(layers.image), mask = std::move(layers.mask);
    } else {
      image = render(scene, accelerator, pinhole, settings);
    }
  });
  encodeAndWrite(clock, image, mask);
  const double wallRatio = clock.total() / std::max(1e-9, clock.seconds("render"));

  const BenchResult r =
      benchmark(scene, accelerator, measured, *limitGrid, settings, o.repeats, viewGrids);
  // A lenticular panel: its direct render against its own device quilt route, in this run.
  std::optional<QuiltRouteTimes> quiltRoute;
  if (model && model->lenticularDesign())
    quiltRoute = benchmarkQuiltRoute(scene, accelerator, *model, settings, o.repeats);
  const double peak = peakResidentMiB();
  const char* quality = qualityName(accelerator.buildQuality());
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
    json.set("/workers", r.workers);
    json.set("/packet_width", r.packetWidth);
    json.set("/native_packet_width", r.nativePacketWidth);
    json.set("/lane_kernels", laneKernelIsa());
    json.set("/embree", embreeLibrary().name());
    json.set("/bvh_quality", quality);
    const auto rate = [&json](const std::string& key, const RayRate& rays) {
      json.set(key + "rays", rays.rays);
      json.set(key + "seconds", rays.seconds);
      json.set(key + "rays_per_second", rays.perSecond());
      json.set(key + "miss_fraction", rays.missFraction());
    };
    rate("/", r.ours);
    rate("/limit_", r.limit);
    rate("/same_rays_limit_", r.sameRays);
    rate("/embree_alone_", r.embreeAlone);
    rate("/embree_on_ours_", r.embreeOnOurs);
    json.set("/ratio", r.ratio());
    if (!viewGrids.empty()) {
      rate("/views_limit_", r.viewsLimit);
      json.set("/views_limit_views", int(viewGrids.size()));
      json.set("/views_limit_width", viewGrids.front().width);
      json.set("/views_ratio", r.viewsRatio());
    }
    json.set("/same_rays_ratio", r.sameRaysRatio());
    json.set("/ray_order_ratio", r.rayOrderRatio());
    json.set("/embree_ray_order_ratio", r.embreeRayOrderRatio());
    json.set("/ray_generation_share", r.rayGenerationShare());
    json.set("/traced_rays_ratio", r.tracedRaysRatio());
    json.set("/shading_over_embree", r.shadingOverEmbree());
    for (const Phase& phase : clock.phases()) {
      json.set(std::string("/phases/") + phase.name + "/seconds", phase.seconds);
      json.set(std::string("/phases/") + phase.name + "/peak_rss_mb", phase.peakMiB);
    }
    if (quiltRoute) {
      const QuiltRouteTimes& q = *quiltRoute;
      json.set("/quilt_route/views", q.views);
      json.set("/quilt_route/tile_width", q.tileWidth);
      json.set("/quilt_route/tile_height", q.tileHeight);
      json.set("/quilt_route/direct_seconds", q.direct);
      json.set("/quilt_route/direct_rays", q.directRays);
      json.set("/quilt_route/quilt_seconds", q.quilt);
      json.set("/quilt_route/quilt_rays", q.quiltRays);
      json.set("/quilt_route/interlace_seconds", q.interlace);
      json.set("/quilt_route/direct_over_quilt", q.directOverQuilt());
      json.set("/quilt_route/direct_over_quilt_and_interlace", q.directOverRoute());
    }
    json.set("/phases/total_seconds", clock.total());
    json.set("/wall_ratio", wallRatio);
    json.set("/peak_rss_mb", peak);
    std::printf("%s\n", json.dump().c_str());
    return;
  }
  std::printf("scene        %s (%zu triangles), %s camera, %dx%d, %d spp, %d workers\n",
              scene.source.c_str(), scene.triangleCount(), o.camera.c_str(), width, height,
              o.sampling.spp, r.workers);
  std::printf("embree       %s, %d-ray packets (the ISA's native width: %d), %s-quality BVH\n",
              embreeLibrary().name().c_str(), r.packetWidth, r.nativePacketWidth, quality);
  std::printf("our kernels  %s (core/lane_kernel.h)\n", laneKernelIsa());
  const auto line = [](const char* name, const RayRate& rays, const char* what) {
    std::printf("%-12s %12llu rays in %.3f s  %s, %2.0f %% of primaries miss (%s)\n", name,
                (unsigned long long)rays.rays, rays.seconds, formatRate(rays.perSecond()).c_str(),
                100.0 * rays.missFraction(), what);
  };
  line("parallax", r.ours, "generated, traced, shaded");
  line("raw Embree", r.limit, "coherent pinhole rays, one shadow ray per hit");
  if (!viewGrids.empty())
    line("  views", r.viewsLimit, "the same from each view's eye, at its share of the columns");
  line("  same rays", r.sameRays, "this camera's rays, generated and traced, no shading");
  line("  Embree", r.embreeAlone, "the same rays, Embree's traversal alone");
  line("  our rays", r.embreeOnOurs, "every ray parallax traced, Embree's traversal alone");
  std::printf(
      "ratio        %.2f  (ray order %.2f x shading %.2f); Embree alone: ray order %.2f, "
      "ray generation %.0f %% of the same-rays loop\n",
      r.ratio(), r.rayOrderRatio(), r.sameRaysRatio(), r.embreeRayOrderRatio(),
      100.0 * r.rayGenerationShare());
  if (!viewGrids.empty())
    std::printf("views ratio  %.2f  (ours / the views' limit: %zu views of %dx%d)\n",
                r.viewsRatio(), viewGrids.size(), viewGrids.front().width,
                viewGrids.front().height);
  std::printf(
      "shading      %.2f of Embree's time on our rays (shading, light sampling, packet copies); "
      "ours / (camera ray generation + Embree on our rays) %.2f\n",
      r.shadingOverEmbree(), r.tracedRaysRatio());
  if (quiltRoute) {
    const QuiltRouteTimes& q = *quiltRoute;
    std::printf(
        "quilt route  direct %.3f s (%llu rays); the device quilt (%d views of %dx%d) %.3f s "
        "(%llu rays), interlaced in %.3f s\n             direct / quilt %.2f, direct / (quilt + "
        "interlace) %.2f\n",
        q.direct, (unsigned long long)q.directRays, q.views, q.tileWidth, q.tileHeight, q.quilt,
        (unsigned long long)q.quiltRays, q.interlace, q.directOverQuilt(), q.directOverRoute());
  }
  std::printf("end to end  ");
  for (const Phase& phase : clock.phases())
    std::printf(" %s %.3f s (%.0f MiB)", phase.name, phase.seconds, phase.peakMiB);
  std::printf("\n             %.3f s in all, %.2fx the render loop\npeak memory  %.0f MiB\n",
              clock.total(), wallRatio, peak);
}

}  // namespace

void registerBenchCommand(Command& cli) {
  auto options = std::make_shared<BenchOptions>();
  Command* cmd =
      cli.addSubcommand("bench", "Measure rays per second against raw Embree on the same rays");
  cmd->addOption("--camera", options->camera,
                 "Camera to measure: pinhole, or display (the image layer through the barrier)")
      ->captureDefault();
  cmd->addOption("--display", options->display,
                 "Display for --camera display: a file of any kind, or lkg:NAME (a lenticular "
                 "panel's direct render is also timed against its own device quilt and "
                 "interlace, in the same run)");
  addFilterOptions(*cmd, options->filter, "With --camera display: ", "as render --filter-width");
  cmd->addOption("--scene", options->scene, "Scene or mesh file (built-in scene if omitted)");
  cmd->addOption("--size", options->size,
                 "Image size WIDTHxHEIGHT (pinhole; the display camera uses the panel's)")
      ->captureDefault();
  addSamplingOptions(*cmd, options->sampling, "Rays per pixel");
  cmd->addOption("--repeats", options->repeats, "Alternating runs; the fastest of each counts")
      ->captureDefault()
      ->check(integerIn(1, INT_MAX));
  cmd->addOption("--simulate", options->simulateViews,
                 "Instead: time a sweep of N simulated views of the display (9 is the goal)")
      ->check(integerIn(0, INT_MAX));
  cmd->addOption("--packet-width", options->packetWidth,
                 "Rays per Embree packet query: 4, 8 or 16 (0: 16, the fastest measured with "
                 "AVX-512, AVX2 and SSE4.2 kernels alike)")
      ->captureDefault()
      ->oneOf({"0", "4", "8", "16"});
  cmd->addOption("--bvh-quality", options->quality,
                 "BVH build: auto (high when the render traces at least 5000 rays per "
                 "triangle, else medium), medium or high")
      ->captureDefault();
  cmd->addOption("--layers", options->layers.method,
                 "Instead: time render --layers METHOD (optimized-image or nmf) on the barrier "
                 "display: its ideal views, its solve and the solve's passes over the training "
                 "targets, against one pass per iteration at memory bandwidth")
      ->oneOf({"optimized-image", "nmf"});
  cmd->addOption("--rank", options->layers.rank, "With --layers nmf: frame pairs")
      ->captureDefault()
      ->check(integerIn(1, 16));
  cmd->addOption("--iterations", options->layers.iterations,
                 "With --layers: solver iterations (default: as render's)")
      ->check(integerIn(1, 1000));
  cmd->addOption("--train-eyes", options->layers.trainEyes,
                 "With --layers: training eyes per view (as render's)")
      ->captureDefault();
  cmd->addOption("--train-distances", options->layers.trainDistances,
                 "With --layers: the training eyes' distances in units of D (as render's)")
      ->captureDefault();
  cmd->addOption("--train-spp", options->layers.trainSpp,
                 "With --layers: samples per pixel of the training eyes' ideal views (as "
                 "render's: default 2)")
      ->typeName("N");
  cmd->addFlag("--json", options->json, "Print one JSON object");
  cmd->callback([options] { runBench(*options); });
}

}  // namespace parallax::app
