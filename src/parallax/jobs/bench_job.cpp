// The bench runner (bench_job.h).
#include "parallax/jobs/bench_job.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <type_traits>
#include <utility>

#include "parallax/accel/accelerator.h"
#include "parallax/camera/display_camera.h"
#include "parallax/core/error.h"
#include "parallax/core/lane_kernel.h"
#include "parallax/core/memory.h"
#include "parallax/core/parallel.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/layer_output.h"
#include "parallax/jobs/limits.h"
#include "parallax/layers/training.h"
#include "parallax/render/display_render.h"
#include "parallax/sim/simulator.h"

namespace parallax::jobs {

namespace {

const std::string kBuiltInDisplay = "the built-in display";

// The simulator's benchmark: a sweep of `views` eyes across the view zone of the display, on
// layers rendered beforehand (not timed).
SimulatorBench benchSimulator(const DisplayDesign& design, const Scene& scene, int views) {
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
  SimulatorBench bench;
  bench.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  bench.views = views;
  bench.width = simulator.outputWidth();
  bench.height = simulator.outputHeight();
  const double samples = double(views) * bench.width * bench.height;
  bench.samplesPerSecond = samples / bench.seconds;
  bench.peakMiB = peakResidentMiB();
  (void)checksum;
  return bench;
}

// The layer solvers' benchmark (docs/speed.md, "Layer solvers"): what `render --layers METHOD`
// spends on its training views and on its solve, with the solve's passes over the training
// targets, against the physical limit of a solver that reads every target once per iteration
// at this machine's memory bandwidth (streamingPassSeconds of the targets' bytes).
LayerBench benchLayers(const BenchRequest& r, Reporter& reporter) {
  const LayersRequest& request = r.layers;
  request.check();
  const DisplayDesign design = loadBarrierDesign(r.display.path, reporter);
  const TrainingOptions training = trainingOptions(request, r.sampling.threads, 0, r.sampling.seed);
  checkMemoryEstimate(layerSolveBytes(design, request, training), r.display.named(kBuiltInDisplay),
                      "the training views of --layers " + request.method, "use a smaller display");
  const Scene scene = loadSceneQuietly(r.scene);
  const Accelerator accelerator(scene);
  // The slit layers the solve starts from, rendered as `render` renders them.
  DisplayLayers slits = renderDisplay(scene, accelerator, design, r.sampling.settings());
  LayerBench bench;
  JsonWriter record;
  solveLayers(request, scene, accelerator, design, training,
              {std::move(slits.image), std::move(slits.mask)}, record, silentReporter(),
              &bench.figures);
  const LayerSolveFigures& figures = bench.figures;
  bench.method = request.method;
  bench.nmf = request.methodKind() == LayerMethod::Nmf;
  bench.rank = request.rank;
  bench.width = design.spec.imagePanel.width;
  bench.height = design.spec.imagePanel.height;
  bench.passSeconds = streamingPassSeconds(figures.targetBytes, r.sampling.threads);
  bench.limitSeconds = bench.passSeconds * figures.iterations;
  bench.ratio = figures.solveSeconds > 0 ? bench.limitSeconds / figures.solveSeconds : 0.0;
  bench.perPass = figures.passes > 0 ? figures.solveSeconds / figures.passes : 0.0;
  bench.peakMiB = peakResidentMiB();
  return bench;
}

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
  const std::vector<BenchPhase>& phases() const { return phases_; }
  double total() const {
    double sum = 0;
    for (const BenchPhase& p : phases_) sum += p.seconds;
    return sum;
  }
  double seconds(const std::string& name) const {
    for (const BenchPhase& p : phases_)
      if (name == p.name) return p.seconds;
    return 0.0;
  }

 private:
  void record(const char* name, std::chrono::steady_clock::time_point start) {
    phases_.push_back(
        {name, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
         peakResidentMiB()});
  }
  std::vector<BenchPhase> phases_;
};

BuildQuality parseQuality(const std::string& text) {
  if (text == "auto") return BuildQuality::Auto;
  if (text == "medium") return BuildQuality::Medium;
  if (text == "high") return BuildQuality::High;
  throw RequestError("bvh_quality", "unknown quality '" + text + "' (auto, medium or high)");
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

// The cameras a ray bench measures and the grids of its limits, made once the scene is loaded.
struct BenchCameras {
  std::unique_ptr<Camera> display;  // the display camera (null: the pinhole's)
  std::optional<PinholeGrid> limit;
  std::vector<PinholeGrid> views;
};

// The display camera renders the image layer at its own resolution. Its limit is a pinhole at
// the view-zone centre whose film is the front layer: the same content, seen by the coherent
// rays of one eye; the views' limit is each view eye's pinhole at its share of the film's
// columns.
BenchCameras displayCameras(std::unique_ptr<DisplayModel> display, const Scene& scene,
                            const BenchRequest& r, int& width, int& height) {
  BenchCameras cameras;
  const DisplayModel& model = *display;
  const Vec3d eye = display->window().eyeMm;
  cameras.display = std::make_unique<DisplayCamera>(std::move(display), scene.display);
  width = cameras.display->width(), height = cameras.display->height();
  cameras.limit = WindowCamera(eye, model, scene.display, width, height).grid(r.sampling.spp);
  const int views = std::max(1, model.viewCount());
  const int viewWidth = std::max(1, int(std::lround(double(width) / views)));
  for (int v = 0; v < views; ++v)
    cameras.views.push_back(
        WindowCamera(model.viewPosition(v), model, scene.display, viewWidth, height)
            .grid(r.sampling.spp));
  // The panel's film, and a lenticular panel's quilt route (timed below), before either is
  // allocated.
  checkMemoryEstimate(imageBytes(width, height) * 4 + quiltRouteBytes(model),
                      "--display " + r.display.path, "the panel's film and its quilt route",
                      "use a smaller display");
  return cameras;
}

RayBench benchRays(const BenchRequest& r, Reporter& reporter) {
  int width = 0, height = 0;
  parseSize("--size", r.size, width, height);
  const RenderSettings settings = r.sampling.settings();
  // Before anything is allocated: the film and the limit's ray buffers (a few per pixel), and
  // the time of `repeats` alternating runs of ours and the three limits, and one more render.
  checkMemoryEstimate(imageBytes(width, height) * 4, "--size " + r.size, "the film and rays",
                      "use a smaller size");
  checkPixelCount(double(width) * height, "--size " + r.size);
  r.sampling.checkWork(width, height, 4.0 * r.repeats + 1.0);
  if (r.camera != "pinhole" && r.camera != "display")
    throw RequestError("camera", "unknown camera '" + r.camera + "' (pinhole or display)");
  AcceleratorOptions acceleratorOptions;
  acceleratorOptions.packetWidth = r.packetWidth;
  acceleratorOptions.quality = parseQuality(r.quality);

  PhaseClock clock;
  // Load: the scene and, for the display camera, the display.
  std::unique_ptr<DisplayModel> display;
  const Scene scene = clock.run("load", [&] {
    if (r.camera == "display") {
      display =
          makeDisplay(r.display.describe(reporter), r.display.camera(r.filter.filter())).model;
    }
    return loadSceneQuietly(r.scene);
  });
  const DisplayModel* model = display.get();
  BenchCameras cameras;
  if (display) cameras = displayCameras(std::move(display), scene, r, width, height);
  const CameraSpec spec = scene.camera ? *scene.camera : frameScene(scene);
  const PinholeCamera pinhole(spec.eye, spec.lookAt, spec.up, spec.fovDegrees, width, height);
  if (!cameras.limit) cameras.limit = pinhole.grid(r.sampling.spp);
  const Camera& measured = cameras.display ? static_cast<const Camera&>(*cameras.display) : pinhole;
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

  RayBench bench;
  bench.wallRatio = clock.total() / std::max(1e-9, clock.seconds("render"));
  bench.result =
      benchmark(scene, accelerator, measured, *cameras.limit, settings, r.repeats, cameras.views);
  // A lenticular panel: its direct render against its own device quilt route, in this run.
  if (model && hasQuiltRoute(*model))
    bench.quiltRoute = benchmarkQuiltRoute(scene, accelerator, *model, settings, r.repeats);
  bench.peakMiB = peakResidentMiB();
  bench.bvhQuality = qualityName(accelerator.buildQuality());
  bench.camera = r.camera;
  bench.filterKind = r.filter.kind;
  bench.scene = scene.source;
  bench.triangles = uint64_t(scene.triangleCount());
  bench.width = width, bench.height = height;
  bench.spp = r.sampling.spp;
  bench.jitter = r.sampling.jitter;
  bench.embree = embreeLibrary().name();
  bench.laneKernels = laneKernelIsa();
  if (!cameras.views.empty()) {
    bench.views = int(cameras.views.size());
    bench.viewWidth = cameras.views.front().width;
    bench.viewHeight = cameras.views.front().height;
  }
  bench.phases = clock.phases();
  bench.totalSeconds = clock.total();
  return bench;
}

void setRayBenchJson(JsonWriter& json, const RayBench& b) {
  const BenchResult& r = b.result;
  json.set("/camera", b.camera);
  if (b.camera == "display") json.set("/filter", b.filterKind);
  json.set("/scene", b.scene);
  json.set("/triangles", b.triangles);
  json.set("/width", b.width);
  json.set("/height", b.height);
  json.set("/spp", b.spp);
  json.set("/jitter", b.jitter);
  json.set("/workers", r.workers);
  json.set("/packet_width", r.packetWidth);
  json.set("/native_packet_width", r.nativePacketWidth);
  json.set("/lane_kernels", b.laneKernels);
  json.set("/embree", b.embree);
  json.set("/bvh_quality", b.bvhQuality);
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
  if (b.views > 0) {
    rate("/views_limit_", r.viewsLimit);
    json.set("/views_limit_views", b.views);
    json.set("/views_limit_width", b.viewWidth);
    json.set("/views_ratio", r.viewsRatio());
  }
  json.set("/same_rays_ratio", r.sameRaysRatio());
  json.set("/ray_order_ratio", r.rayOrderRatio());
  json.set("/embree_ray_order_ratio", r.embreeRayOrderRatio());
  json.set("/ray_generation_share", r.rayGenerationShare());
  json.set("/traced_rays_ratio", r.tracedRaysRatio());
  json.set("/shading_over_embree", r.shadingOverEmbree());
  for (const BenchPhase& phase : b.phases) {
    json.set(std::string("/phases/") + phase.name + "/seconds", phase.seconds);
    json.set(std::string("/phases/") + phase.name + "/peak_rss_mb", phase.peakMiB);
  }
  if (b.quiltRoute) {
    const QuiltRouteTimes& q = *b.quiltRoute;
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
  json.set("/phases/total_seconds", b.totalSeconds);
  json.set("/wall_ratio", b.wallRatio);
  json.set("/peak_rss_mb", b.peakMiB);
}

}  // namespace

std::string BenchReport::json() const {
  JsonWriter out;
  if (simulator) {
    out.set("/views", simulator->views);
    out.set("/width", simulator->width);
    out.set("/height", simulator->height);
    out.set("/seconds", simulator->seconds);
    out.set("/samples_per_second", simulator->samplesPerSecond);
    out.set("/peak_rss_mb", simulator->peakMiB);
  } else if (layers) {
    const LayerBench& b = *layers;
    out.set("/layers/method", b.method);
    out.set("/layers/rank", b.rank);
    out.set("/layers/width", b.width);
    out.set("/layers/height", b.height);
    out.set("/layers/eyes", b.figures.eyes);
    out.set("/layers/iterations", b.figures.iterations);
    out.set("/layers/passes", b.figures.passes);
    out.set("/layers/target_bytes", b.figures.targetBytes);
    out.set("/layers/training_seconds", b.figures.trainingSeconds);
    out.set("/layers/solve_seconds", b.figures.solveSeconds);
    out.set("/layers/pass_seconds", b.perPass);
    out.set("/layers/streaming_pass_seconds", b.passSeconds);
    out.set("/layers/limit_seconds", b.limitSeconds);
    out.set("/layers/ratio", b.ratio);
    out.set("/peak_rss_mb", b.peakMiB);
  } else if (rays) {
    setRayBenchJson(out, *rays);
  }
  return out.dump();
}

BenchReport runBench(const BenchRequest& r, Reporter& reporter) {
  BenchReport report;
  if (r.layers.solved()) {
    report.layers = benchLayers(r, reporter);
  } else if (r.simulateViews > 0) {
    const DisplayDesign design = loadBarrierDesign(r.display.path, reporter);
    const Panel& panel = design.spec.imagePanel;
    checkLayerMemory(design, panel.width * (design.camera.subpixelRays ? 3.0 : 1.0), 1,
                     r.display.named());
    checkTimeEstimate(double(r.simulateViews) * panel.width * panel.height, r.sampling.threads,
                      "simulate", std::to_string(r.simulateViews), "time fewer views");
    report.simulator = benchSimulator(design, loadSceneQuietly(r.scene), r.simulateViews);
  } else {
    report.rays = benchRays(r, reporter);
  }
  return report;
}

}  // namespace parallax::jobs
