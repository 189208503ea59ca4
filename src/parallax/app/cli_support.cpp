#include "parallax/app/cli_support.h"

#include <unistd.h>
#include <CLI/CLI.hpp>

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <thread>

#include "parallax/accel/accelerator.h"
#include "parallax/cluster/process_group.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/io/display_file.h"
#include "parallax/io/scene_file.h"

namespace parallax::app {

std::string versionText() {
  return std::string("parallax ") + PARALLAX_VERSION + " (" + embreeLibrary().name() + ")";
}

Vec3f parseVec3(const std::string& option, const std::string& text) {
  Vec3f v;
  char c1 = 0, c2 = 0;
  std::istringstream in(text);
  if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || !in.eof() || !isFinite(v))
    throw InputError("command line", option, "expected X,Y,Z, got '" + text + "'");
  return v;
}

namespace {

// The text as a number, or nothing: decimal digits with an optional leading minus, no spaces.
bool parseInteger(const std::string& text, int64_t& value) {
  if (text.empty() || text.size() > 20) return false;
  for (size_t i = 0; i < text.size(); ++i)
    if (!(std::isdigit(static_cast<unsigned char>(text[i])) || (i == 0 && text[i] == '-')))
      return false;
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (errno != 0 || end != text.c_str() + text.size()) return false;
  value = v;
  return true;
}

bool parseReal(const std::string& text, double& value) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(v)) return false;
  value = v;
  return true;
}

std::string number(double v) {
  if (std::isinf(v)) return v > 0 ? "infinity" : "-infinity";
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

}  // namespace

void parseSize(const std::string& option, const std::string& text, int& width, int& height) {
  const size_t x = text.find_first_of("xX");
  int64_t w = 0, h = 0;
  if (x == std::string::npos || !parseInteger(text.substr(0, x), w) ||
      !parseInteger(text.substr(x + 1), h) || w <= 0 || h <= 0)
    throw InputError(option, "",
                     "expected WIDTHxHEIGHT (positive whole numbers), got '" + text + "'");
  if (w > INT_MAX || h > INT_MAX)
    throw InputError(option + " " + text, "", "is more pixels across than an int holds");
  width = int(w);
  height = int(h);
}

CLI::Validator realIn(double lo, double hi, Bound lower, Bound upper) {
  std::string range;
  if (std::isinf(lo) && std::isinf(hi))
    range = "that is finite";
  else if (std::isinf(hi))
    range = lower == Bound::Open ? "above " + number(lo) : "at least " + number(lo);
  else
    range = std::string(lower == Bound::Open ? "above " : "from ") + number(lo) +
            (lower == Bound::Open ? " and " : " ") +
            (upper == Bound::Open   ? "below "
             : lower == Bound::Open ? "at most "
                                    : "to ") +
            number(hi);
  const std::string description =
      std::isinf(lo) && std::isinf(hi) ? std::string("a finite number") : "a number " + range;
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double v = 0;
        const bool ok = parseReal(text, v) && (lower == Bound::Open ? v > lo : v >= lo) &&
                        (upper == Bound::Open ? v < hi : v <= hi);
        return ok ? std::string() : "must be " + description + ", got '" + text + "'";
      },
      "REAL");
}

CLI::Validator integerIn(int64_t lo, int64_t hi) {
  const std::string description =
      hi == std::numeric_limits<int64_t>::max() || hi == INT_MAX
          ? "a whole number, at least " + std::to_string(lo)
          : "a whole number from " + std::to_string(lo) + " to " + std::to_string(hi);
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        int64_t v = 0;
        const bool ok = parseInteger(text, v) && v >= lo && v <= hi;
        return ok ? std::string() : "must be " + description + ", got '" + text + "'";
      },
      "INT");
}

CLI::Validator squareCount(bool zeroAllowed) {
  return CLI::Validator(
      [zeroAllowed](std::string& text) -> std::string {
        int64_t v = 0;
        if (parseInteger(text, v) && v >= (zeroAllowed ? 0 : 1) && v <= INT_MAX) {
          const int64_t n = std::llround(std::sqrt(double(v)));
          if (n * n == v) return {};
        }
        return std::string("must be a square whole number n*n (") + (zeroAllowed ? "0, " : "") +
               "1, 4, 9, 16, ...), got '" + text + "'";
      },
      "N*N");
}

CLI::Validator threadCount() {
  const int64_t cores = std::max(1u, std::thread::hardware_concurrency());
  return CLI::Validator(
      [cores](std::string& text) -> std::string {
        int64_t v = 0;
        if (parseInteger(text, v) && v >= 0 && v <= cores) return {};
        return "must be 0 (all cores) to " + std::to_string(cores) +
               " (this machine's hardware threads), got '" + text + "'";
      },
      "INT");
}

CLI::Validator seedValue() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const bool digits = !text.empty() && text.size() <= 20 &&
                            text.find_first_not_of("0123456789") == std::string::npos;
        errno = 0;
        if (digits) (void)std::strtoull(text.c_str(), nullptr, 10);
        if (digits && errno == 0) return {};
        return "must be a whole number from 0 to 2^64-1, got '" + text + "'";
      },
      "UINT");
}

namespace {

double gMaxMemoryGiB = 0;  // 0: the default share of physical memory
double gMaxSeconds = 0;    // 0: kDefaultMaxSeconds

}  // namespace

double memoryLimitBytes() {
  return gMaxMemoryGiB > 0 ? gMaxMemoryGiB * kGiB : defaultMemoryLimitBytes(physicalMemoryBytes());
}

void addMemoryLimitOption(CLI::App& cmd) {
  const uint64_t physical = physicalMemoryBytes();
  const double physicalGiB = physical > 0 ? double(physical) / kGiB : 1e6;
  cmd.add_option("--max-memory", gMaxMemoryGiB,
                 "Memory limit in GiB for what the command allocates (default: 3/4 of the "
                 "physical memory); refused before allocating when the estimate exceeds it")
      ->check(realIn(0, physicalGiB, Bound::Open))
      ->type_name("GiB");
}

void checkPixelCount(double pixels, const std::string& subject) {
  if (pixels > double(INT_MAX))
    throw InputError(subject, "",
                     "more than 2^31 pixels, the most the renderer can index; use a smaller size");
}

void checkMemoryEstimate(double bytes, const std::string& subject, const std::string& what,
                         const std::string& advice) {
  checkMemory(bytes, memoryLimitBytes(), subject, what, advice + ", or raise --max-memory");
}

void addTimeLimitOption(CLI::App& cmd) {
  cmd.add_option("--max-time", gMaxSeconds,
                 "Time limit in seconds: work estimated (at an optimistic rate) to take longer is "
                 "refused before it starts (default: one day)")
      ->check(realIn(0, std::numeric_limits<double>::infinity(), Bound::Open))
      ->type_name("SECONDS");
}

void addLimitOptions(CLI::App& cmd) {
  addMemoryLimitOption(cmd);
  addTimeLimitOption(cmd);
}

void checkTimeEstimate(double samples, int threads, const std::string& subject,
                       const std::string& advice) {
  const double cores = std::max(1u, std::thread::hardware_concurrency());
  const double used = threads > 0 ? std::min(double(threads), cores) : cores;
  const double seconds = samples / (kSamplesPerSecondPerThread * used);
  const double limit = gMaxSeconds > 0 ? gMaxSeconds : kDefaultMaxSeconds;
  if (seconds <= limit) return;
  char text[256];
  std::snprintf(text, sizeof text,
                "needs %.3g samples, at least %s at %.0f M samples/s on %.0f threads (limit %s); ",
                samples, formatDuration(seconds).c_str(), kSamplesPerSecondPerThread / 1e6, used,
                formatDuration(limit).c_str());
  throw InputError(subject, "", text + advice + ", or raise --max-time");
}

namespace {

JitterSharing parseJitter(const std::string& text) {
  if (text == "auto") return JitterSharing::Auto;
  if (text == "pixel") return JitterSharing::Pixel;
  if (text == "packet") return JitterSharing::Packet;
  throw InputError("command line", "--jitter",
                   "expected auto, pixel or packet, got '" + text + "'");
}

}  // namespace

void SamplingOptions::checkWork(double width, double height, double passes) const {
  checkTimeEstimate(width * height * double(spp) * passes, threads, "--spp " + std::to_string(spp),
                    "use fewer samples");
}

RenderSettings SamplingOptions::settings() const {
  if (spp < 1) throw InputError("command line", "--spp", "must be at least 1");
  RenderSettings s;
  s.samplesPerPixel = spp;
  s.threads = threads;
  s.seed = seed;
  s.jitter = parseJitter(jitter);
  s.adaptive = adaptive;
  s.adaptiveThreshold = adaptiveThreshold / 255.0;
  if (bounces < 0 || bounces > RenderSettings::kMaxBounces)
    throw InputError("command line", "--bounces",
                     "must be from 0 to " + std::to_string(RenderSettings::kMaxBounces));
  s.bounces = bounces;
  return s;
}

void addSamplingOptions(CLI::App& cmd, SamplingOptions& options, const std::string& sppHelp) {
  cmd.add_option("--spp", options.spp, sppHelp)
      ->capture_default_str()
      ->check(integerIn(1, INT_MAX));
  cmd.add_option("--threads", options.threads, "Worker threads (0: all cores)")
      ->check(threadCount());
  cmd.add_option("--seed", options.seed, "Seed of the sample jitter")->check(seedValue());
  addLimitOptions(cmd);
  addImportOptions(cmd);
  cmd.add_option("--jitter", options.jitter,
                 "Within-stratum jitter: auto (the camera's choice: shared by the 16 rays of a "
                 "packet for the barrier camera, which keeps them parallel), pixel (independent) "
                 "or packet (shared)")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "pixel", "packet"}));
  cmd.add_flag("--adaptive", options.adaptive,
               "Adaptive sampling: --spp becomes a cap; a pixel stops after a stratified group "
               "of samples once its mean is certain (from the spread of its groups' means) and "
               "its neighbours agree (docs/display-geometry.md, \"Adaptive sampling\")");
  cmd.add_option("--adaptive-threshold", options.adaptiveThreshold,
                 "With --adaptive: the standard error (in 8-bit sRGB steps of luminance) below "
                 "which a pixel stops")
      ->capture_default_str()
      ->check(realIn(0.0, 255.0));
  cmd.add_option("--bounces", options.bounces,
                 "Diffuse bounces of path tracing with next-event estimation (0: direct light "
                 "only; docs/path-tracing.md)")
      ->capture_default_str()
      ->check(integerIn(0, RenderSettings::kMaxBounces));
}

void setFramingFigures(JsonWriter& json, const std::string& at, const Framing& f) {
  json.set(at + "/fit", displayFitName(f.fit));
  json.set(at + "/focus_mm", f.focusMm);
  json.set(at + "/depth_budget_mm", f.budgetMm);
  json.set(at + "/depth_of_field_mm", f.depthOfFieldMm);
  json.set(at + "/gap_mm", f.gapMm);
  json.set(at + "/virtual_gap_mm", f.virtualGapMm);
  json.set(at + "/virtual_depth_of_field_mm", f.depthOfFieldMm * f.virtualGapMm / f.gapMm);
  if (!f.hasContent) return;
  json.set(at + "/content_near_mm", f.nearMm);
  json.set(at + "/content_far_mm", f.farMm);
  json.set(at + "/shown_near_mm", f.shownNearMm);
  json.set(at + "/shown_far_mm", f.shownFarMm);
  json.set(at + "/within_budget", f.withinBudget());
}

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

void addFramingOptions(CLI::App& cmd, FramingOptions& options, const std::string& scope) {
  addImportOptions(cmd);
  cmd.add_option("--fit", options.fit,
                 scope +
                     "How the content is framed: window (the width only), depth (the width, the "
                     "zero-parallax plane inside the content and the depth compressed into the "
                     "budget; the default without a display width in the scene), none (the "
                     "scene's display block as it is), auto")
      ->type_name("window|depth|none|auto");
  cmd.add_option("--focus", options.focus,
                 scope +
                     "The zero-parallax plane: its offset in mm toward the viewer from the "
                     "scene's display centre, or auto (with --fit depth: the harmonic mean of "
                     "the content's nearest and farthest distances from the eye)")
      ->type_name("MM|auto");
  cmd.add_option("--depth-budget", options.depthBudget,
                 scope +
                     "With --fit depth: half the displayed depth range in mm, or auto (the "
                     "display's depth of field, G4)")
      ->type_name("MM|auto");
}

ViewFilter FilterOptions::filter() const {
  ViewFilter filter;
  if (!parseViewFilterKind(kind, filter.kind))
    throw InputError("command line", "--filter",
                     "expected none, view, tent, gaussian or period, got '" + kind + "'");
  if (!(widthViews >= 0.05 && widthViews <= 20))
    throw InputError(
        "command line", "--filter-width",
        "expected a width in views between 0.05 and 20, got " + std::to_string(widthViews));
  filter.widthViews = widthViews;
  return filter;
}

void addFilterOptions(CLI::App& cmd, FilterOptions& options, const std::string& scope,
                      const std::string& viewUnit) {
  cmd.add_option("--filter", options.kind,
                 scope +
                     "How a pixel's rays spread in angle (docs/display-geometry.md, "
                     "\"Super-sampling\"): none (the central ray, 1 spp), view (a box one view "
                     "wide), tent (the pixel-times-opening fan), gaussian, or period (a whole "
                     "aperture period: the old cell, for comparison)")
      ->capture_default_str();
  cmd.add_option("--filter-width", options.widthViews,
                 scope + "The filter's width in views (" + viewUnit +
                     "; box width; tent and Gaussian: full width at half maximum)")
      ->capture_default_str();
}

namespace {
std::string gUpAxis = upAxisName(UpAxis::Auto);
double gCreaseDegrees = kDefaultCreaseDegrees;
std::vector<Scene::ImportRecord> gImportRecords;
}  // namespace

void addImportOptions(CLI::App& cmd) {
  if (cmd.get_option_no_throw("--mesh-up")) return;  // added already
  // view has --up already (the camera's up vector); --mesh-up works on every command.
  const bool upFree = cmd.get_option_no_throw("--up") == nullptr;
  cmd.add_option(upFree ? "--up,--mesh-up" : "--mesh-up", gUpAxis,
                 "Which axis of the mesh files points up: auto (Z for STL, 3MF, AMF, Blender and "
                 "FBX files that say so; Y otherwise), y, or z (turned Y-up); docs/import.md")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "y", "z"}));
  cmd.add_option("--crease", gCreaseDegrees,
                 "Meshes without normals get smooth ones, split where faces meet at more than "
                 "this angle in degrees (0: faceted); docs/import.md")
      ->capture_default_str()
      ->type_name("DEGREES")
      ->check(realIn(0.0, 180.0));
}

ImportOptions importOptions() {
  ImportOptions options;
  if (!parseUpAxis(gUpAxis, options.up))  // the option's check lets no other value through
    throw InputError("command line", "--up", "expected auto, y or z, got '" + gUpAxis + "'");
  options.creaseDegrees = float(gCreaseDegrees);
  return options;
}

const std::vector<Scene::ImportRecord>& importRecords() {
  return gImportRecords;
}

Scene loadSceneOrDefault(const std::string& path, const SceneLoadOptions& options) {
  if (path.empty() && !options.camera.empty())
    throw InputError("command line", "--camera", "the built-in scene has no cameras");
  SceneLoadOptions load = options;
  load.import = importOptions();
  Scene scene = path.empty() ? defaultScene() : loadScene(path, load);
  gImportRecords.insert(gImportRecords.end(), scene.imports.begin(), scene.imports.end());
  return scene;
}

Scene loadSceneReportingWarnings(const std::string& path, const SceneLoadOptions& options) {
  cluster::failIfAskedForTest(cluster::world());
  Scene scene = loadSceneOrDefault(path, options);
  // Under mpirun every rank loads the scene: its notes once.
  if (!cluster::world().isRoot()) return scene;
  for (const auto& n : scene.notes) std::fprintf(stderr, "note: %s\n", n.c_str());
  for (const auto& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  return scene;
}

void addSceneLoadOptions(CLI::App& cmd, SceneLoadOptions& options) {
  cmd.add_option("--camera", options.camera,
                 "A camera of the scene's glTF files, by name or index: the view's camera, and "
                 "for render the display seen as that camera saw the scene (docs/gltf.md). "
                 "Default: a bare glTF file's first camera")
      ->type_name("NAME|INDEX");
}

DisplayDesign loadDesignOrDefault(const std::string& path) {
  const DisplayDescription description = loadDisplayOrDefault(path);
  if (description.kind != DisplayKind::Barrier)
    throw InputError(description.source(), "",
                     "is a lenticular calibration; this command takes a barrier display");
  return designDisplay(description.barrier);
}

DisplayDescription loadDisplayOrDefault(const std::string& pathOrPreset) {
  DisplayDescription description = loadDisplayDescription(pathOrPreset);
  for (const std::string& warning : description.lenticular.warnings)
    std::fprintf(stderr, "warning: %s\n", warning.c_str());
  return description;
}

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)),
      enabled_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      lastDraw_(start_) {}

ProgressBar::~ProgressBar() {
  if (drawn_) std::fputs("\r\033[K", stderr);
}

void ProgressBar::update(int done, int total) {
  if (!enabled_ || total <= 0) return;
  const std::lock_guard lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  if (done < total && now - lastDraw_ < std::chrono::milliseconds(100)) return;
  lastDraw_ = now;
  drawn_ = true;
  const double fraction = double(done) / double(total);
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double remaining = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
  constexpr int kWidth = 30;
  const int filled = int(fraction * kWidth);
  std::string bar(size_t(filled), '#');
  bar.append(size_t(kWidth - filled), '-');
  std::fprintf(stderr, "\r%s [%s] %3d%%  %.1fs left\033[K", label_.c_str(), bar.c_str(),
               int(fraction * 100), remaining);
  std::fflush(stderr);
}

std::string formatDuration(double seconds) {
  char text[64];
  if (seconds < 120)
    std::snprintf(text, sizeof text, "%.0f s", seconds);
  else if (seconds < 7200)
    std::snprintf(text, sizeof text, "%.0f min", seconds / 60);
  else if (seconds < 3 * 86400)
    std::snprintf(text, sizeof text, "%.0f h", seconds / 3600);
  else
    std::snprintf(text, sizeof text, "%.3g days", seconds / 86400);
  return text;
}

std::string formatRate(double raysPerSecond) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f M rays/s", raysPerSecond / 1e6);
  return text;
}

}  // namespace parallax::app
