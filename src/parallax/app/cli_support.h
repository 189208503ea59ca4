// Shared pieces of the command-line front end: argument parsing helpers, the progress bar, and
// the conversion of library errors into one-line messages and exit codes.
#pragma once

#include <chrono>
#include <mutex>
#include <string>

#include "parallax/core/math.h"
#include "parallax/display/display.h"
#include "parallax/render/tile_packets.h"
#include "parallax/scene/scene.h"

namespace parallax::app {

inline constexpr int kExitInputError = 2;

// "X,Y,Z" -> Vec3f; throws InputError naming the option.
Vec3f parseVec3(const std::string& option, const std::string& text);
// "WxH" -> (W, H) with both positive; throws InputError naming the option.
void parseSize(const std::string& option, const std::string& text, int& width, int& height);

// "auto", "pixel" or "packet" (--jitter) -> JitterSharing; throws InputError naming the option.
JitterSharing parseJitter(const std::string& text);

// The built-in scene when `path` is empty, otherwise the scene or mesh file.
Scene loadSceneOrDefault(const std::string& path);

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
