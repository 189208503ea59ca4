#include "parallax/app/cli_support.h"

#include <unistd.h>
#include <CLI/CLI.hpp>

#include <cstdio>
#include <sstream>

#include "parallax/core/error.h"
#include "parallax/io/display_file.h"
#include "parallax/io/scene_file.h"

namespace parallax::app {

Vec3f parseVec3(const std::string& option, const std::string& text) {
  Vec3f v;
  char c1 = 0, c2 = 0;
  std::istringstream in(text);
  if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || !in.eof() || !isFinite(v))
    throw InputError("command line", option, "expected X,Y,Z, got '" + text + "'");
  return v;
}

void parseSize(const std::string& option, const std::string& text, int& width, int& height) {
  char x = 0;
  std::istringstream in(text);
  int w = 0, h = 0;
  if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || !in.eof() || w <= 0 || h <= 0 ||
      w > 65536 || h > 65536)
    throw InputError("command line", option, "expected WIDTHxHEIGHT, got '" + text + "'");
  width = w;
  height = h;
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

RenderSettings SamplingOptions::settings() const {
  if (spp < 1) throw InputError("command line", "--spp", "must be at least 1");
  RenderSettings s;
  s.samplesPerPixel = spp;
  s.threads = threads;
  s.seed = seed;
  s.jitter = parseJitter(jitter);
  return s;
}

void addSamplingOptions(CLI::App& cmd, SamplingOptions& options, const std::string& sppHelp) {
  cmd.add_option("--spp", options.spp, sppHelp)->capture_default_str();
  cmd.add_option("--threads", options.threads, "Worker threads (0: all cores)");
  cmd.add_option("--seed", options.seed, "Seed of the sample jitter");
  cmd.add_option("--jitter", options.jitter,
                 "Within-stratum jitter: auto (the camera's choice: shared by the 16 rays of a "
                 "packet for the barrier camera, which keeps them parallel), pixel (independent) "
                 "or packet (shared)")
      ->capture_default_str();
}

Scene loadSceneOrDefault(const std::string& path) {
  return path.empty() ? defaultScene() : loadScene(path);
}

Scene loadSceneReportingWarnings(const std::string& path) {
  Scene scene = loadSceneOrDefault(path);
  for (const auto& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  return scene;
}

DisplayDesign loadDesignOrDefault(const std::string& path) {
  return designDisplay(path.empty() ? defaultDisplaySpec() : loadDisplayFile(path));
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

std::string formatRate(double raysPerSecond) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f M rays/s", raysPerSecond / 1e6);
  return text;
}

}  // namespace parallax::app
