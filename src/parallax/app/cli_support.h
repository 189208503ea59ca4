// Shared pieces of the command-line front end: argument parsing helpers, the progress bar, and
// the conversion of library errors into one-line messages and exit codes.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "parallax/app/cli_parser.h"
#include "parallax/core/error.h"
#include "parallax/core/math.h"
#include "parallax/display/display.h"
#include "parallax/importer/mesh_file.h"
#include "parallax/importer/scene_file.h"
#include "parallax/jobs/display_request.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/reporter.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/scene_request.h"
#include "parallax/jobs/sequence.h"
#include "parallax/jobs/terminal_reporter.h"
#include "parallax/jobs/video_output.h"
#include "parallax/scene/scene.h"

namespace parallax::app {

// The commands call the request layer directly.
using namespace parallax::jobs;

inline constexpr int kExitInputError = 2;
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// ---- Ranges of numeric options (docs/inputs.md) -----------------------------------------
// Validators that read the option's text themselves, so that garbage, NaN and infinity get the
// same one-line message naming the option ("--fov: must be a number above 0 and below 180, got
// 'nan'") as a value out of range. Upper bounds that depend on the work (sizes, samples,
// sweeps) are checked later against the memory and time estimates below.
enum class Bound { Closed, Open };
// A finite real number in [lo, hi] (Open: the end itself is excluded); either may be infinite.
TextCheck realIn(double lo, double hi, Bound lower = Bound::Closed, Bound upper = Bound::Closed);
// A whole number in [lo, hi] written in decimal digits (an optional leading minus).
TextCheck integerIn(int64_t lo, int64_t hi);
// A whole number n*n in [1, INT_MAX] (samples per pixel of an n x n grid), or 0 as well.
TextCheck squareCount(bool zeroAllowed = false);
// 0 (all cores) up to the machine's hardware threads.
TextCheck threadCount();
// --seed: any unsigned 64-bit number.
TextCheck seedValue();

// ---- Memory and time limits (jobs/limits.h) ------------------------------------------------
// Adds --max-memory GiB (jobs::limits().maxMemoryGiB) to `cmd`; the last one given wins.
void addMemoryLimitOption(Command& cmd);
// Adds --max-time SECONDS (jobs::limits().maxSeconds).
void addTimeLimitOption(Command& cmd);
// Both limit options at once.
void addLimitOptions(Command& cmd);
using jobs::checkMemoryEstimate;
using jobs::checkPixelCount;
using jobs::checkTimeEstimate;
using jobs::formatDuration;
using jobs::formatRate;
using jobs::memoryLimitBytes;

// ---- Requests' fields as options ----------------------------------------------------------
// The option that spells a request's field: "--" and the field with '-' for '_' ("spp" ->
// "--spp"), except where the command line says it otherwise.
std::string optionName(const std::string& field);
// The one line main prints for an InputError: fields spelled as options.
std::string errorLine(const InputError& error);
// Notes and warnings on stderr ("note: ...", "warning: ..."), results on stdout, a progress bar
// on a terminal; fields spelled as options. Under mpirun, what each rank says (runners say
// job-wide things on rank 0 only).
jobs::Reporter& cliReporter();

// "X,Y,Z" -> Vec3f; throws InputError naming the option.
Vec3f parseVec3(const std::string& option, const std::string& text);

// --spp, --threads, --seed, --jitter, --adaptive, --bounces: how every rendering command samples.
// Adds the four options to `cmd`; what one sample is differs between commands: `sppHelp`.
void addSamplingOptions(Command& cmd, SamplingRequest& options, const std::string& sppHelp);

using jobs::parseInteger;
using jobs::parseSize;
using jobs::setFramingFigures;

// --fit, --focus and --depth-budget (render, and design --scene, view --display-eye): how the
// content is framed for the display (camera/framing.h). Empty: the scene's own choice.
// Adds the three options to `cmd`; `scope` begins their help ("" or "With --scene: ").
void addFramingOptions(Command& cmd, FramingRequest& options, const std::string& scope);

// --filter and --filter-width (render, bench, lenticular render): how a display pixel's rays
// spread in angle (display/view_filter.h).
// Adds the two options to `cmd`; `scope` begins their help ("" or "With --camera display: "),
// `viewUnit` says what one view is for this display.
void addFilterOptions(Command& cmd, FilterRequest& options, const std::string& scope,
                      const std::string& viewUnit);

// --display PATH (`name` instead for a positional argument such as lenticular's calibration):
// the display a command works on (jobs::DisplayRequest::path), `help` saying what it may be and
// what it is when omitted.
Option* addDisplayOption(Command& cmd, DisplayRequest& display, const std::string& help,
                         const std::string& name = "--display");
// --lens-spot W and --bundles parallel|converging: the lenticular optics a simulator reads a panel
// under (jobs::SimulatorRequest::lens), or a render renders for (`forRender`,
// jobs::DisplayRequest::lens); unset when not given.
void addLensReadingOptions(Command& cmd, LensReadingRequest& lens, bool forRender = false);

// --up auto|y|z (also --mesh-up; only that on view, whose --up is the camera's) and --crease
// DEGREES (docs/import.md): how the scene's mesh files are imported (a scene file's mesh
// objects may say otherwise). addSamplingOptions and addFramingOptions add them, so every
// command that loads a scene has them (render, view, bench, lenticular render, design; info
// adds them itself); a second call on the same command does nothing.
void addImportOptions(Command& cmd);
// What the command line chose (the defaults if the command has no such options).
ImportOptions importOptions();

// The built-in scene when `path` is empty, otherwise the scene or mesh file.
Scene loadSceneOrDefault(const std::string& path, const SceneLoadOptions& options = {});
// --camera NAME|INDEX (render, view): which camera of the scene's glTF files to use
// (importer/scene_file.h, SceneLoadOptions::camera).
void addSceneLoadOptions(Command& cmd, SceneLoadOptions& options);

// The built-in display when `path` is empty, otherwise the display file; checked (G1-G4).
// A lenticular calibration is refused.
DisplayDesign loadDesignOrDefault(const std::string& path);

// --frames, --chunk, --turntable, --duration, --fps, and --video with its codec and quality;
// `frames` says what a video's frames are.
void addSequenceOptions(Command& cmd, SequenceRequest& options, const std::string& frames);
// --video, --video-codec, --video-quality and (unless `withFps` is false: the sequence options
// have it) --fps.
void addVideoOptions(Command& cmd, VideoRequest& o, const std::string& frames, bool withFps = true);
// --rgbd COLOUR DEPTH, --depth-convention, --depth-range, --rgbd-edges, --rgbd-fov. Returns the
// --rgbd option, so that the caller can make it exclude its scene argument.
Option* addRgbdOptions(Command& cmd, RgbdRequest& options);

}  // namespace parallax::app
