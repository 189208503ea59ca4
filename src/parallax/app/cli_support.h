// Shared pieces of the command-line front end: argument parsing helpers, the progress bar, and
// the conversion of library errors into one-line messages and exit codes.
#pragma once

#include <chrono>
#include <mutex>
#include <string>

#include "parallax/core/math.h"
#include "parallax/display/display.h"
#include "parallax/render/render.h"
#include "parallax/scene/scene.h"

namespace CLI {
class App;
}

namespace parallax::app {

inline constexpr int kExitInputError = 2;

// "X,Y,Z" -> Vec3f; throws InputError naming the option.
Vec3f parseVec3(const std::string& option, const std::string& text);
// "WxH" -> (W, H) with both positive; throws InputError naming the option.
void parseSize(const std::string& option, const std::string& text, int& width, int& height);

// --spp, --threads, --seed and --jitter: how every rendering command samples.
struct SamplingOptions {
  int spp = 16;
  int threads = 0;
  uint64_t seed = 0;
  std::string jitter = "auto";
  // The render settings; throws InputError naming --spp (below 1) or --jitter (not auto,
  // pixel or packet).
  RenderSettings settings() const;
};
// Adds the four options to `cmd`; what one sample is differs between commands: `sppHelp`.
void addSamplingOptions(CLI::App& cmd, SamplingOptions& options, const std::string& sppHelp);

// The built-in scene when `path` is empty, otherwise the scene or mesh file.
Scene loadSceneOrDefault(const std::string& path);
// The same, with the scene's warnings printed to stderr (for the commands that render it).
Scene loadSceneReportingWarnings(const std::string& path);

// The built-in display when `path` is empty, otherwise the display file; checked (G1-G4).
DisplayDesign loadDesignOrDefault(const std::string& path);

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

}  // namespace parallax::app
