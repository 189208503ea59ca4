// Shared pieces of the command-line front end: argument parsing helpers, the progress bar, and
// the conversion of library errors into one-line messages and exit codes.
#pragma once

#include <chrono>
#include <cstdint>
#include <limits>
#include <mutex>
#include <string>

#include "parallax/camera/framing.h"
#include "parallax/core/math.h"
#include "parallax/display/display.h"
#include "parallax/display/view_filter.h"
#include "parallax/io/display_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/io/mesh_file.h"
#include "parallax/io/scene_file.h"
#include "parallax/render/render.h"
#include "parallax/scene/scene.h"

namespace CLI {
class App;
class Validator;
}  // namespace CLI

namespace parallax::app {

inline constexpr int kExitInputError = 2;

// "parallax 0.1.0 (Embree 4.3.3)": this build's version and the Embree it runs on (3 on
// Debian 12, 4 on Debian 13), for `parallax --version` and Python's parallax.version().
std::string versionText();

// ---- Ranges of numeric options (docs/inputs.md) -----------------------------------------
// Validators that read the option's text themselves, so that garbage, NaN and infinity get the
// same one-line message naming the option ("--fov: must be a number above 0 and below 180, got
// 'nan'") as a value out of range. Upper bounds that depend on the work (sizes, samples,
// sweeps) are checked later against the memory and time estimates below.
enum class Bound { Closed, Open };
// A finite real number in [lo, hi] (Open: the end itself is excluded); either may be infinite.
CLI::Validator realIn(double lo, double hi, Bound lower = Bound::Closed,
                      Bound upper = Bound::Closed);
// A whole number in [lo, hi] written in decimal digits (an optional leading minus).
CLI::Validator integerIn(int64_t lo, int64_t hi);
// A whole number n*n in [1, INT_MAX] (samples per pixel of an n x n grid), or 0 as well.
CLI::Validator squareCount(bool zeroAllowed = false);
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
// 0 (all cores) up to the machine's hardware threads.
CLI::Validator threadCount();
// --seed: any unsigned 64-bit number.
CLI::Validator seedValue();

// ---- Memory and time limits -------------------------------------------------------------
// The memory limit in bytes: --max-memory GiB when given (globally or on the command), else
// 3/4 of physical memory.
double memoryLimitBytes();
// Adds --max-memory GiB to `cmd`; the last one given wins.
void addMemoryLimitOption(CLI::App& cmd);
// Refuses pictures of more than 2^31 pixels (the renderer's pixel index is an int); call it
// after the memory estimate, which refuses them first where memory is smaller.
void checkPixelCount(double pixels, const std::string& subject);
// Refuses (InputError naming `subject`) when `bytes` exceed memoryLimitBytes().
void checkMemoryEstimate(double bytes, const std::string& subject, const std::string& what,
                         const std::string& advice);
// The time estimate: `samples` camera samples (pixel x sample, each at least one ray) on
// `threads` threads (0: all) at kSamplesPerSecondPerThread, an optimistic rate (the fastest
// bench figure on a simple scene, rounded up), so that only work certain to take longer than
// the time limit (--max-time, default kDefaultMaxSeconds) is refused.
inline constexpr double kSamplesPerSecondPerThread = 1e8;
inline constexpr double kDefaultMaxSeconds = 24 * 3600.0;
void addTimeLimitOption(CLI::App& cmd);
void checkTimeEstimate(double samples, int threads, const std::string& subject,
                       const std::string& advice);
// Both limit options at once.
void addLimitOptions(CLI::App& cmd);

// "X,Y,Z" -> Vec3f; throws InputError naming the option.
Vec3f parseVec3(const std::string& option, const std::string& text);
// "WxH" -> (W, H) with both positive; throws InputError naming the option. Memory (and the
// pixel count) are checked separately, with the estimate.
void parseSize(const std::string& option, const std::string& text, int& width, int& height);

// --spp, --threads, --seed and --jitter: how every rendering command samples.
struct SamplingOptions {
  int spp = 16;
  int threads = 0;
  uint64_t seed = 0;
  std::string jitter = "auto";
  bool adaptive = false;
  int bounces = 0;  // --bounces: diffuse path-tracing bounces (RenderSettings::bounces)
  double adaptiveThreshold = RenderSettings{}.adaptiveThreshold * 255.0;  // in 8-bit steps
  // The render settings; throws InputError naming --spp (below 1) or --jitter (not auto,
  // pixel or packet).
  RenderSettings settings() const;
  // Refuses --spp when width x height x spp x `passes` samples exceed the time limit.
  void checkWork(double width, double height, double passes = 1.0) const;
};
// Adds the four options to `cmd`; what one sample is differs between commands: `sppHelp`.
void addSamplingOptions(CLI::App& cmd, SamplingOptions& options, const std::string& sppHelp);

// The framing's figures (camera/framing.h) under `at` ("/framing"): fit, focus, gaps, depth
// of field and budget, and the content's near and far as given and as shown. render, design
// and info write the same keys.
void setFramingFigures(JsonWriter& json, const std::string& at, const Framing& framing);

// The framing in render.json, under "/framing": what was asked (fit, focus, depth_budget:
// simulate --reference frames the scene again from these) and what followed. The CLI's render
// and the Python module's write the same.
void recordFraming(JsonWriter& record, const Framing& framing);

// --fit, --focus and --depth-budget (render, and design --scene, view --display-eye): how the
// content is framed for the display (camera/framing.h). Empty: the scene's own choice.
struct FramingOptions {
  std::string fit, focus, depthBudget;
  bool given() const { return !fit.empty() || !focus.empty() || !depthBudget.empty(); }
  // Sets them on the scene's placement; throws InputError naming the option.
  void apply(DisplayPlacement& placement) const {
    applyFramingOptions(placement, fit, focus, depthBudget);
  }
};
// Adds the three options to `cmd`; `scope` begins their help ("" or "With --scene: ").
void addFramingOptions(CLI::App& cmd, FramingOptions& options, const std::string& scope);

// --filter and --filter-width (render, bench, lenticular render): how a display pixel's rays
// spread in angle (display/view_filter.h).
struct FilterOptions {
  std::string kind = viewFilterName(ViewFilter{}.kind);
  double widthViews = ViewFilter{}.widthViews;
  // The ViewFilter; throws InputError naming the option for an unknown kind or a width
  // outside [0.05, 20] views.
  ViewFilter filter() const;
};
// Adds the two options to `cmd`; `scope` begins their help ("" or "With --camera display: "),
// `viewUnit` says what one view is for this display.
void addFilterOptions(CLI::App& cmd, FilterOptions& options, const std::string& scope,
                      const std::string& viewUnit);

// --up auto|y|z (also --mesh-up; only that on view, whose --up is the camera's) and --crease
// DEGREES (docs/import.md): how the scene's mesh files are imported (a scene file's mesh
// objects may say otherwise). addSamplingOptions and addFramingOptions add them, so every
// command that loads a scene has them (render, view, bench, lenticular render, design; info
// adds them itself); a second call on the same command does nothing.
void addImportOptions(CLI::App& cmd);
// What the command line chose (the defaults if the command has no such options).
ImportOptions importOptions();
// What loading this command's scenes imported (every loadSceneOrDefault so far), for the
// /import array of render.json (startRenderRecord).
const std::vector<Scene::ImportRecord>& importRecords();

// The built-in scene when `path` is empty, otherwise the scene or mesh file.
Scene loadSceneOrDefault(const std::string& path, const SceneLoadOptions& options = {});
// The same, with the scene's notes and warnings printed to stderr (for the commands that
// render it).
Scene loadSceneReportingWarnings(const std::string& path, const SceneLoadOptions& options = {});
// --camera NAME|INDEX (render, view): which camera of the scene's glTF files to use
// (io/scene_file.h, SceneLoadOptions::camera).
void addSceneLoadOptions(CLI::App& cmd, SceneLoadOptions& options);

// The built-in display when `path` is empty, otherwise the display file; checked (G1-G4).
// A lenticular calibration is refused here, naming the command's barrier-only `what`.
DisplayDesign loadDesignOrDefault(const std::string& path);

// A display of any kind (io/display_file.h: "", a file of either kind, or lkg:NAME), with the
// reader's warnings (defaulted or unknown calibration keys) printed to stderr, one line each.
DisplayDescription loadDisplayOrDefault(const std::string& pathOrPreset);

// A progress bar on stderr, drawn only when stderr is a terminal; thread-safe and throttled.
class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();
  void update(int done, int total);

 private:
  std::string label_;
  bool enabled_;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, lastDraw_;
  bool drawn_ = false;
};

std::string formatRate(double raysPerSecond);
// "45 s", "12 min", "5 h", "58 days".
std::string formatDuration(double seconds);

}  // namespace parallax::app
