// `parallax bench`: our rays per second against raw Embree on the same rays, in one run
// (jobs/bench_job.h); the options, and the report as text.
#include <climits>
#include <cstdio>
#include <memory>
#include <string>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/jobs/bench_job.h"
#include "parallax/render/bench.h"

namespace parallax::app {

namespace {

void printSimulatorBench(const jobs::SimulatorBench& b) {
  std::printf("simulator    %d views of %dx%d in %.3f s (%.1f M samples/s), peak memory %.0f MiB\n",
              b.views, b.width, b.height, b.seconds, b.samplesPerSecond / 1e6, b.peakMiB);
}

void printLayerBench(const jobs::LayerBench& b) {
  const jobs::LayerSolveFigures& f = b.figures;
  std::printf(
      "layers       %s%s on %dx%d, %d training eyes: ideal views %.2f s, solve %.2f s "
      "(%d iterations, %d passes over the targets, %.3f s each)\n"
      "limit        one pass over the targets (%.0f MiB) per iteration at memory bandwidth: "
      "%.4f s a pass, %.3f s in all\n"
      "ratio        %.4f (limit / solve); a pass costs %.0fx a streaming read of the targets\n"
      "peak memory  %.0f MiB\n",
      b.method.c_str(), b.nmf ? (" rank " + std::to_string(b.rank)).c_str() : "", b.width, b.height,
      f.eyes, f.trainingSeconds, f.solveSeconds, f.iterations, f.passes, b.perPass,
      f.targetBytes / (1 << 20), b.passSeconds, b.limitSeconds, b.ratio,
      b.passSeconds > 0 ? b.perPass / b.passSeconds : 0.0, b.peakMiB);
}

void printRayBench(const jobs::RayBench& b) {
  const BenchResult& r = b.result;
  std::printf("scene        %s (%llu triangles), %s camera, %dx%d, %d spp, %d workers\n",
              b.scene.c_str(), (unsigned long long)b.triangles, b.camera.c_str(), b.width, b.height,
              b.spp, r.workers);
  std::printf("embree       %s, %d-ray packets (the ISA's native width: %d), %s-quality BVH\n",
              b.embree.c_str(), r.packetWidth, r.nativePacketWidth, b.bvhQuality.c_str());
  std::printf("our kernels  %s (core/lane_kernel.h)\n", b.laneKernels);
  const auto line = [](const char* name, const RayRate& rays, const char* what) {
    std::printf("%-12s %12llu rays in %.3f s  %s, %2.0f %% of primaries miss (%s)\n", name,
                (unsigned long long)rays.rays, rays.seconds, formatRate(rays.perSecond()).c_str(),
                100.0 * rays.missFraction(), what);
  };
  line("parallax", r.ours, "generated, traced, shaded");
  line("raw Embree", r.limit, "coherent pinhole rays, one shadow ray per hit");
  if (b.views > 0)
    line("  views", r.viewsLimit, "the same from each view's eye, at its share of the columns");
  line("  same rays", r.sameRays, "this camera's rays, generated and traced, no shading");
  line("  Embree", r.embreeAlone, "the same rays, Embree's traversal alone");
  line("  our rays", r.embreeOnOurs, "every ray parallax traced, Embree's traversal alone");
  std::printf(
      "ratio        %.2f  (ray order %.2f x shading %.2f); Embree alone: ray order %.2f, "
      "ray generation %.0f %% of the same-rays loop\n",
      r.ratio(), r.rayOrderRatio(), r.sameRaysRatio(), r.embreeRayOrderRatio(),
      100.0 * r.rayGenerationShare());
  if (b.views > 0)
    std::printf("views ratio  %.2f  (ours / the views' limit: %d views of %dx%d)\n", r.viewsRatio(),
                b.views, b.viewWidth, b.viewHeight);
  std::printf(
      "shading      %.2f of Embree's time on our rays (shading, light sampling, packet copies); "
      "ours / (camera ray generation + Embree on our rays) %.2f\n",
      r.shadingOverEmbree(), r.tracedRaysRatio());
  if (b.quiltRoute) {
    const QuiltRouteTimes& q = *b.quiltRoute;
    std::printf(
        "quilt route  direct %.3f s (%llu rays); the device quilt (%d views of %dx%d) %.3f s "
        "(%llu rays), interlaced in %.3f s\n             direct / quilt %.2f, direct / (quilt + "
        "interlace) %.2f\n",
        q.direct, (unsigned long long)q.directRays, q.views, q.tileWidth, q.tileHeight, q.quilt,
        (unsigned long long)q.quiltRays, q.interlace, q.directOverQuilt(), q.directOverRoute());
  }
  std::printf("end to end  ");
  for (const jobs::BenchPhase& phase : b.phases)
    std::printf(" %s %.3f s (%.0f MiB)", phase.name, phase.seconds, phase.peakMiB);
  std::printf("\n             %.3f s in all, %.2fx the render loop\npeak memory  %.0f MiB\n",
              b.totalSeconds, b.wallRatio, b.peakMiB);
}

void printBench(const jobs::BenchReport& report) {
  if (report.simulator) printSimulatorBench(*report.simulator);
  if (report.layers) printLayerBench(*report.layers);
  if (report.rays) printRayBench(*report.rays);
}

}  // namespace

void registerBenchCommand(Command& cli) {
  auto options = std::make_shared<jobs::BenchRequest>();
  Command* cmd =
      cli.addSubcommand("bench", "Measure rays per second against raw Embree on the same rays");
  cmd->addOption("--camera", options->camera,
                 "Camera to measure: pinhole, or display (the image layer through the barrier)")
      ->captureDefault();
  addDisplayOption(*cmd, options->display,
                   "Display for --camera display: a file of any kind, or lkg:NAME (a lenticular "
                   "panel's direct render is also timed against its own device quilt and "
                   "interlace, in the same run)");
  addFilterOptions(*cmd, options->filter, "With --camera display: ", "as render --filter-width");
  cmd->addOption("--scene", options->scene.path, "Scene or mesh file (built-in scene if omitted)");
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
  auto json = std::make_shared<bool>(false);
  cmd->addFlag("--json", *json, "Print one JSON object");
  cmd->callback([options, json] {
    options->scene.load.import = importOptions();
    const jobs::BenchReport report = jobs::runBench(*options, cliReporter());
    if (*json)
      std::printf("%s\n", report.json().c_str());
    else
      printBench(report);
  });
}

}  // namespace parallax::app
