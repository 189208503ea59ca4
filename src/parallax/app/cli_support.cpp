#include "parallax/app/cli_support.h"

#include <unistd.h>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <thread>

#include "parallax/accel/accelerator.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/display/lenticular.h"
#include "parallax/importer/scene_file.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/layer_output.h"

namespace parallax::app {

Vec3f parseVec3(const std::string& option, const std::string& text) {
  Vec3f v;
  char c1 = 0, c2 = 0;
  std::istringstream in(text);
  if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || !in.eof() || !isFinite(v))
    throw InputError("command line", option, "expected X,Y,Z, got '" + text + "'");
  return v;
}

namespace {

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

TextCheck realIn(double lo, double hi, Bound lower, Bound upper) {
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
  return TextCheck{[=](const std::string& text) -> std::string {
                     double v = 0;
                     const bool ok = parseReal(text, v) &&
                                     (lower == Bound::Open ? v > lo : v >= lo) &&
                                     (upper == Bound::Open ? v < hi : v <= hi);
                     return ok ? std::string() : "must be " + description + ", got '" + text + "'";
                   },
                   "REAL"};
}

TextCheck integerIn(int64_t lo, int64_t hi) {
  const std::string description =
      hi == std::numeric_limits<int64_t>::max() || hi == INT_MAX
          ? "a whole number, at least " + std::to_string(lo)
          : "a whole number from " + std::to_string(lo) + " to " + std::to_string(hi);
  return TextCheck{[=](const std::string& text) -> std::string {
                     int64_t v = 0;
                     const bool ok = parseInteger(text, v) && v >= lo && v <= hi;
                     return ok ? std::string() : "must be " + description + ", got '" + text + "'";
                   },
                   "INT"};
}

TextCheck squareCount(bool zeroAllowed) {
  return TextCheck{[zeroAllowed](const std::string& text) -> std::string {
                     int64_t v = 0;
                     if (parseInteger(text, v) && v >= (zeroAllowed ? 0 : 1) && v <= INT_MAX) {
                       const int64_t n = std::llround(std::sqrt(double(v)));
                       if (n * n == v) return {};
                     }
                     return std::string("must be a square whole number n*n (") +
                            (zeroAllowed ? "0, " : "") + "1, 4, 9, 16, ...), got '" + text + "'";
                   },
                   "N*N"};
}

TextCheck threadCount() {
  const int64_t cores = std::max(1u, std::thread::hardware_concurrency());
  return TextCheck{[cores](const std::string& text) -> std::string {
                     int64_t v = 0;
                     if (parseInteger(text, v) && v >= 0 && v <= cores) return {};
                     return "must be 0 (all cores) to " + std::to_string(cores) +
                            " (this machine's hardware threads), got '" + text + "'";
                   },
                   "INT"};
}

TextCheck seedValue() {
  return TextCheck{[](const std::string& text) -> std::string {
                     const bool digits = !text.empty() && text.size() <= 20 &&
                                         text.find_first_not_of("0123456789") == std::string::npos;
                     errno = 0;
                     if (digits) (void)std::strtoull(text.c_str(), nullptr, 10);
                     if (digits && errno == 0) return {};
                     return "must be a whole number from 0 to 2^64-1, got '" + text + "'";
                   },
                   "UINT"};
}

void addMemoryLimitOption(Command& cmd) {
  const uint64_t physical = physicalMemoryBytes();
  const double physicalGiB = physical > 0 ? double(physical) / kGiB : 1e6;
  cmd.addOption("--max-memory", jobs::limits().maxMemoryGiB,
                "Memory limit in GiB for what the command allocates (default: 3/4 of the "
                "physical memory); refused before allocating when the estimate exceeds it")
      ->check(realIn(0, physicalGiB, Bound::Open))
      ->typeName("GiB");
}

void addTimeLimitOption(Command& cmd) {
  cmd.addOption("--max-time", jobs::limits().maxSeconds,
                "Time limit in seconds: work estimated (at an optimistic rate) to take longer is "
                "refused before it starts (default: one day)")
      ->check(realIn(0, std::numeric_limits<double>::infinity(), Bound::Open))
      ->typeName("SECONDS");
}

void addLimitOptions(Command& cmd) {
  addMemoryLimitOption(cmd);
  addTimeLimitOption(cmd);
}

void addSamplingOptions(Command& cmd, SamplingRequest& options, const std::string& sppHelp) {
  cmd.addOption("--spp", options.spp, sppHelp)->captureDefault()->check(integerIn(1, INT_MAX));
  cmd.addOption("--threads", options.threads, "Worker threads (0: all cores)")
      ->check(threadCount());
  cmd.addOption("--seed", options.seed, "Seed of the sample jitter")->check(seedValue());
  addLimitOptions(cmd);
  addImportOptions(cmd);
  cmd.addOption("--jitter", options.jitter,
                "Within-stratum jitter: auto (the camera's choice: shared by the 16 rays of a "
                "packet for the barrier camera, which keeps them parallel), pixel (independent) "
                "or packet (shared)")
      ->captureDefault()
      ->oneOf({"auto", "pixel", "packet"});
  Option* adaptive =
      cmd.addFlag("--adaptive", options.adaptive,
                  "Adaptive sampling: --spp becomes a cap; a pixel stops after a stratified group "
                  "of samples once its mean is certain (from the spread of its groups' means) and "
                  "its neighbours agree (docs/display-geometry.md, \"Adaptive sampling\")");
  cmd.addOption("--adaptive-threshold", options.adaptiveThreshold,
                "With --adaptive: the standard error (in 8-bit sRGB steps of luminance) below "
                "which a pixel stops")
      ->captureDefault()
      ->check(realIn(0.0, 255.0))
      ->needs(adaptive);  // refused, not ignored, without it
  cmd.addOption("--bounces", options.bounces,
                "Diffuse bounces of path tracing with next-event estimation (0: direct light "
                "only; docs/path-tracing.md)")
      ->captureDefault()
      ->check(integerIn(0, RenderSettings::kMaxBounces));
}

void addFramingOptions(Command& cmd, FramingRequest& options, const std::string& scope) {
  addImportOptions(cmd);
  cmd.addOption("--fit", options.fit,
                scope +
                    "How the content is framed: window (the width only), depth (the width, the "
                    "zero-parallax plane inside the content and the depth compressed into the "
                    "budget; the default without a display width in the scene), camera (the "
                    "window is what the scene's glTF camera sees at its focus distance, depth "
                    "compressed as for depth; the default for a scene with a camera), none "
                    "(the scene's display block as it is), auto")
      ->typeName("window|depth|camera|none|auto");
  cmd.addOption("--focus", options.focus,
                scope +
                    "The zero-parallax plane: its offset in mm toward the viewer from the "
                    "scene's display centre, or auto (with --fit depth: the harmonic mean of "
                    "the content's nearest and farthest distances from the eye)")
      ->typeName("MM|auto");
  cmd.addOption("--depth-budget", options.depthBudget,
                scope +
                    "With --fit depth: half the displayed depth range in mm, or auto (the "
                    "display's depth of field, G4)")
      ->typeName("MM|auto");
}

void addFilterOptions(Command& cmd, FilterRequest& options, const std::string& scope,
                      const std::string& viewUnit) {
  cmd.addOption("--filter", options.kind,
                scope +
                    "How a pixel's rays spread in angle (docs/display-geometry.md, "
                    "\"Super-sampling\"): none (the central ray, 1 spp), view (a box one view "
                    "wide), tent (the pixel-times-opening fan), gaussian, or period (a whole "
                    "aperture period: the old cell, for comparison)")
      ->captureDefault();
  cmd.addOption("--filter-width", options.widthViews,
                scope + "The filter's width in views (" + viewUnit +
                    "; box width; tent and Gaussian: full width at half maximum)")
      ->captureDefault();
}

Option* addDisplayOption(Command& cmd, DisplayRequest& display, const std::string& help,
                         const std::string& name) {
  Option* option = cmd.addOption(name, display.path, help);
  return name.rfind("--", 0) == 0 ? option->typeName("FILE|lkg:NAME") : option;
}

void addLensReadingOptions(Command& cmd, LensReadingRequest& lens, bool forRender) {
  const std::string verb = forRender ? "render the panel for" : "read the panel through";
  cmd.addOptionFunction<double>(
         "--lens-spot", [&lens](const double& w) { lens.spot = w; },
         "Lenticular: " + verb +
             " lenses whose focal spot is W subpixels wide (0: an ideal lens, one subpixel seen "
             "per lens; 3: a pixel-wide spot); default: the display's optics "
             "(docs/lenticular.md, \"The optics\")")
      ->typeName("W")
      ->check(realIn(0, kMaxLensSpotSubpixels));
  cmd.addOption("--bundles", lens.bundles,
                std::string("Lenticular: ") +
                    (forRender ? "render the panel for" : "read the panel with") +
                    " the light of one view leaving parallel, or converging at the design "
                    "distance; default: the display's optics")
      ->typeName("parallel|converging")
      ->oneOf({"parallel", "converging"});
}

namespace {
std::string gUpAxis = upAxisName(UpAxis::Auto);
double gCreaseDegrees = kDefaultCreaseDegrees;
}  // namespace

void addImportOptions(Command& cmd) {
  if (cmd.hasOption("--mesh-up")) return;  // added already
  // view has --up already (the camera's up vector); --mesh-up works on every command.
  const bool upFree = !cmd.hasOption("--up");
  cmd.addOption(upFree ? "--up,--mesh-up" : "--mesh-up", gUpAxis,
                "Which axis of the mesh files points up: auto (Z for STL, 3MF, AMF, Blender and "
                "FBX files that say so; -Y for Gaussian splat files; Y otherwise), y, z or -y "
                "(turned Y-up); docs/import.md")
      ->captureDefault()
      ->oneOf({"auto", "y", "z", "-y"});
  cmd.addOption("--crease", gCreaseDegrees,
                "Meshes without normals get smooth ones, split where faces meet at more than "
                "this angle in degrees (0: faceted); docs/import.md")
      ->captureDefault()
      ->typeName("DEGREES")
      ->check(realIn(0.0, 180.0));
}

ImportOptions importOptions() {
  ImportOptions options;
  if (!parseUpAxis(gUpAxis, options.up))  // the option's check lets no other value through
    throw InputError("command line", "--up", "expected auto, y, z or -y, got '" + gUpAxis + "'");
  options.creaseDegrees = float(gCreaseDegrees);
  return options;
}

Scene loadSceneOrDefault(const std::string& path, const SceneLoadOptions& options) {
  jobs::SceneRequest request;
  request.path = path;
  request.load = options;
  request.load.import = importOptions();
  return jobs::loadSceneQuietly(request);
}

void addSceneLoadOptions(Command& cmd, SceneLoadOptions& options) {
  cmd.addOption("--camera", options.camera,
                "A camera of the scene's glTF files, by its name, its node's name (Blender's "
                "object name) or index: the view's camera, and "
                "for render the display seen as that camera saw the scene (docs/gltf.md). "
                "Default: a bare glTF file's first camera")
      ->typeName("NAME|INDEX");
  cmd.addOption("--focus-on", options.focusOn,
                "An object whose centre the zero-parallax plane goes through: a glTF node's "
                "name (Blender's object name), else a scene object's or mesh's name; with a "
                "camera, the distance its shot is framed at (docs/gltf.md)")
      ->typeName("NAME");
  cmd.addOption("--exposure", options.exposureStops,
                "Exposure in stops: the scene's light times 2^EV in every picture (default: the "
                "scene file's \"look\", else 0; docs/look.md)")
      ->typeName("EV");
  cmd.addOption("--view-transform", options.viewTransform,
                "How light becomes display values: standard (clips at white, the default) or "
                "filmic (a log encoding with a soft shoulder, as Blender's Filmic; docs/look.md)")
      ->typeName("NAME");
}

DisplayDesign loadDesignOrDefault(const std::string& path) {
  return jobs::loadBarrierDesign(path, cliReporter());
}

void addSequenceOptions(Command& cmd, SequenceRequest& options, const std::string& frames) {
  cmd.addOption("--frames", options.frames,
                "Render frames FIRST:LAST of the animation (1-based) into DIR/frame-NNNN; "
                "finished frames are skipped, so a killed sequence resumes (docs/animation.md)")
      ->typeName("FIRST:LAST");
  cmd.addOption("--chunk", options.chunk,
                "Only the K-th of N contiguous parts of the frames (of --frames, else all): one "
                "task of a render farm (docs/distributed.md)")
      ->typeName("K/N");
  cmd.addOption("--turntable", options.turntable,
                "Turn the content DEGREES about the display's up axis over the animation "
                "(360: a loop)")
      ->typeName("DEGREES")
      ->check(realIn(-36000, 36000));
  cmd.addOption("--duration", options.duration,
                "The animation's length in seconds (default: the scene's last key, else 4 s "
                "for a turntable)")
      ->typeName("SECONDS")
      ->check(realIn(0, 1e5, Bound::Open));
  cmd.addOption("--fps", options.fps, "Frames per second of the animation (and of --video)")
      ->captureDefault()
      ->check(realIn(0, 240, Bound::Open));
  addVideoOptions(cmd, options.video, frames, false);
}

void addVideoOptions(Command& cmd, VideoRequest& o, const std::string& frames, bool withFps) {
  Option* video =
      cmd.addOption("--video", o.file,
                    "Also write " + frames +
                        " as a video: .mp4 (H.264; H.265 above 4096 a side), .webm (VP9) or .mkv "
                        "(docs/video.md)")
          ->typeName("FILE");
  // The video's own settings are refused, not ignored, without it.
  cmd.addOption("--video-codec", o.codec, "Codec of --video: auto, h264, h265 or vp9")
      ->captureDefault()
      ->needs(video);
  cmd.addOption("--video-quality", o.quality,
                "Constant quality (CRF) of --video, lower is better: 0 to 51 for h264 and h265 "
                "(18: visually lossless), 0 to 63 for vp9")
      ->captureDefault()
      ->check(integerIn(0, 63))
      ->needs(video);
  if (!withFps) return;
  cmd.addOption("--fps", o.fps, "Frames per second of --video, above 0 and at most 240")
      ->captureDefault()
      ->check(realIn(0, 240, Bound::Open))
      ->needs(video);
}

Option* addRgbdOptions(Command& cmd, RgbdRequest& options) {
  Option* rgbd =
      cmd.addOption("--rgbd", options.files,
                    "An RGB-D photo instead of a scene: a colour image and its greyscale depth "
                    "map (8- or 16-bit PNG) of the same size (docs/rgbd.md)")
          ->expected(2)
          ->typeName("COLOUR DEPTH");
  // Its settings are refused, not ignored, without it.
  cmd.addOption("--depth-convention", options.convention,
                "With --rgbd: how the depth map's values give distance: disparity (bright = "
                "near, linear in 1/distance: MiDaS, Depth-Anything), depth (bright = far, "
                "linear), inverse (bright = near, linear)")
      ->typeName("disparity|depth|inverse")
      ->captureDefault()
      ->needs(rgbd);
  cmd.addOption("--depth-range", options.range,
                "With --rgbd: the distances of the nearest and farthest values, in scene units; "
                "only their ratio shapes the picture (the framing scales it to the display)")
      ->typeName("NEAR:FAR")
      ->captureDefault()
      ->needs(rgbd);
  cmd.addOption("--rgbd-edges", options.edges,
                "With --rgbd: at depth jumps, stretch (one sheet, rubber sheets across the "
                "jumps) or layered (cut at jumps, a background sheet extended from the far side "
                "fills them)")
      ->typeName("stretch|layered")
      ->captureDefault()
      ->needs(rgbd);
  cmd.addOption("--rgbd-fov", options.fovDegrees,
                "With --rgbd: the photo's horizontal field of view in degrees")
      ->check(realIn(1.0, 170.0))
      ->typeName("DEGREES")
      ->captureDefault()
      ->needs(rgbd);
  return rgbd;
}

std::string optionName(const std::string& field) {
  // Fields the command line spells otherwise than --field-name.
  static const std::pair<const char*, const char*> kOwnSpelling[] = {
      {"train_eyes_per_view", "--train-eyes"},
      {"framing", "--fit/--focus/--depth-budget"},
      {"sequence", "--frames/--turntable"},
      {"max_memory", "--max-memory"},
      // calibrate's settings keep the library's names (jobs/calibrate_job.h).
      {"screen_period_px", "--screen-period"},
      {"slit_period_px", "--slit-period"},
      {"phase_px", "--phase"},
      {"from_px", "--from"},
      {"to_px", "--to"},
      {"period_steps", "--steps"},
      {"phase_step_px", "--phase-step"},
  };
  for (const auto& [name, option] : kOwnSpelling)
    if (field == name) return option;
  std::string option = "--" + field;
  for (char& c : option)
    if (c == '_') c = '-';
  return option;
}

std::string errorLine(const InputError& error) {
  return errorText(error, optionName, [](const std::string& field, const std::string& value) {
    return optionName(field) + " " + value;
  });
}

jobs::Reporter& cliReporter() {
  static jobs::TerminalReporter reporter(optionName, true, true);
  return reporter;
}

}  // namespace parallax::app
