// The bench runner (docs/speed.md): our rays per second against raw Embree on the same rays,
// in one run; or, instead, the simulator's sweep of views, or a layer solver's time against its
// memory-bandwidth limit. `parallax bench` spells a BenchRequest and prints the report (text, or
// its JSON object).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "parallax/jobs/render_parts.h"
#include "parallax/jobs/render_request.h"
#include "parallax/jobs/reporter.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/scene_request.h"
#include "parallax/render/bench.h"

namespace parallax::jobs {

struct BenchRequest {
  std::string camera = "pinhole";  // pinhole, or display (the display's own rays)
  SceneRequest scene;              // path "": the built-in scene
  DisplayRequest display;          // "": the built-in barrier
  std::string size = "1920x1080";  // the pinhole's film (the display camera uses the panel's)
  SamplingRequest sampling;
  int repeats = 2;               // alternating runs; the fastest of each counts
  int simulateViews = 0;         // > 0: time a sweep of this many simulated views instead
  LayersRequest layers;          // a solver: time render --layers METHOD instead
  int packetWidth = 0;           // rays per Embree packet query (0: 16)
  std::string quality = "auto";  // the BVH build: auto, medium or high
  FilterRequest filter;          // the display camera's view filter
};

// One step of what `parallax render` does, timed, with the process's peak memory after it.
struct BenchPhase {
  const char* name;
  double seconds;
  double peakMiB;
};

struct SimulatorBench {
  int views = 0, width = 0, height = 0;
  double seconds = 0, samplesPerSecond = 0, peakMiB = 0;
};

struct LayerBench {
  std::string method;
  bool nmf = false;
  int rank = 1, width = 0, height = 0;
  LayerSolveFigures figures;
  // One streaming read of the targets at memory bandwidth, that per iteration, their ratio to
  // the solve, and the solve's time per pass.
  double passSeconds = 0, limitSeconds = 0, ratio = 0, perPass = 0;
  double peakMiB = 0;
};

struct RayBench {
  std::string camera, filterKind, scene, jitter, embree, bvhQuality;
  const char* laneKernels = "";
  uint64_t triangles = 0;
  int width = 0, height = 0, spp = 0;
  BenchResult result;
  // The views' limit (the display camera): its views and one view's film.
  int views = 0, viewWidth = 0, viewHeight = 0;
  std::optional<QuiltRouteTimes> quiltRoute;  // a lenticular panel's direct render vs its quilt
  std::vector<BenchPhase> phases;
  double totalSeconds = 0, wallRatio = 0, peakMiB = 0;
};

// What one bench run measured: one of the three.
struct BenchReport {
  std::optional<SimulatorBench> simulator;
  std::optional<LayerBench> layers;
  std::optional<RayBench> rays;
  // The report as one JSON object (`bench --json`).
  std::string json() const;
};

// Every check and estimate before the scene is loaded; the display reader's warnings to
// `reporter`.
BenchReport runBench(const BenchRequest& request, Reporter& reporter);

}  // namespace parallax::jobs
