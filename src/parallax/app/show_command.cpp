// `parallax show DIR`: the layers on the real panels, full screen with 1:1 pixels, and the
// calibration pattern sets stepped through with the keyboard (docs/calibration.md, "On the
// panels").
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_reader.h"
#include "parallax/jobs/limits.h"
#include "parallax/window/layer_windows.h"

namespace parallax::app {

namespace {

namespace fs = std::filesystem;

struct ShowOptions {
  std::string dir;
  int imageMonitor = 0, maskMonitor = -1;  // -1: the second monitor if there is one
  bool windowed = false;
  int pattern = 0;
  double exitAfter = 0;
  std::string keys;
};

// A calibration pattern set's mask patterns, as index.json lists them.
struct MaskPattern {
  std::string file, purpose, label;
  double screenPeriodPx = 0, slitPeriodPx = 0, phasePx = 0, distanceMm = 0;
};

struct ShowSet {
  std::string imagePath;                  // the image layer (or the lenticular panel)
  std::string maskPath;                   // a render's mask layer; empty for one panel
  std::vector<MaskPattern> maskPatterns;  // a calibration set's, stepped through
};

ShowSet readShowSet(const ShowOptions& o) {
  const fs::path dir(o.dir);
  if (!fs::is_directory(dir))
    throw InputError(o.dir, "", "not a folder: give the output folder of render or calibrate");
  ShowSet set;
  const fs::path index = dir / "index.json";
  if (fs::exists(index)) {  // calibrate patterns: one image pattern, mask patterns to step
    const JsonDocument doc = JsonDocument::parseFile(index.string());
    const JsonReader patterns = doc.root()["patterns"];
    for (const JsonReader& p : patterns.elements()) {
      const std::string file = (dir / p["file"].string()).string();
      if (p["layer"].string() == "image") {
        if (set.imagePath.empty()) set.imagePath = file;
        continue;
      }
      set.maskPatterns.push_back({file, p["purpose"].string(), p["label"].string(),
                                  p["screen_period_px"].number(), p["slit_period_px"].number(),
                                  p["phase_px"].number(), p["view_distance_mm"].number()});
    }
    if (set.imagePath.empty() || set.maskPatterns.empty())
      throw InputError(index.string(), "/patterns", "needs an image pattern and mask patterns");
    if (o.pattern < 0 || o.pattern >= int(set.maskPatterns.size()))
      throw InputError("command line", "--pattern",
                       "expected 0 to " + std::to_string(set.maskPatterns.size() - 1));
    return set;
  }
  set.imagePath = (dir / "image.png").string();
  if (fs::exists(dir / "mask.png")) set.maskPath = (dir / "mask.png").string();
  if (!fs::exists(set.imagePath))
    throw InputError(set.imagePath, "", "missing: give the output folder of render or calibrate");
  return set;
}

std::vector<ShowKey> parseKeys(const std::string& text) {
  std::vector<ShowKey> keys;
  size_t start = 0;
  while (start < text.size()) {
    const size_t end = std::min(text.find(',', start), text.size());
    const std::string key = text.substr(start, end - start);
    if (key == "next")
      keys.push_back(ShowKey::Next);
    else if (key == "previous")
      keys.push_back(ShowKey::Previous);
    else if (key == "info")
      keys.push_back(ShowKey::Info);
    else if (key == "quit")
      keys.push_back(ShowKey::Quit);
    else
      throw InputError(
          "command line", "--keys",
          "expected next, previous, info or quit separated by commas, got '" + key + "'");
    start = end + 1;
  }
  return keys;
}

void printPattern(const std::vector<MaskPattern>& patterns, int k) {
  const MaskPattern& p = patterns[size_t(k)];
  std::printf(
      "pattern %d/%zu %s: screen period %.0f px, slit period %.4f mask px, phase %.2f px, "
      "D %.1f mm (%s)\n",
      k + 1, patterns.size(), fs::path(p.file).filename().c_str(), p.screenPeriodPx, p.slitPeriodPx,
      p.phasePx, p.distanceMm, p.purpose.c_str());
  std::fflush(stdout);
}

// SDL's video subsystem with the X11 client libraries it loads, and per pixel shown, the window
// system's copies beside our RGBA one (the texture, the window's surface, the shared image):
// measured under Xvfb (SDL's software renderer), 1 to 8 M pixels shown. The libraries' share
// is the release's: 96 MB on Debian 12 (SDL 2.26), 124 MB on Debian 13 (SDL 2.32); the constant
// is their middle (peak / estimate 0.92-1.08 on both). A GPU's driver loads other libraries.
constexpr double kWindowSystemBytes = 110e6;
constexpr double kWindowPixelBytes = 5 * kRgba8PixelBytes;

// The whole estimate before any picture is decoded, from their headers (docs/inputs.md,
// "Memory"): every picture kept as a float image; while one is read, its file and stb_image's
// samples; the window system and the windows' copies of what they show.
void checkShowMemory(const ShowOptions& o, const ShowSet& set) {
  std::vector<std::string> files{set.imagePath};
  for (const MaskPattern& p : set.maskPatterns) files.push_back(p.file);
  if (!set.maskPath.empty()) files.push_back(set.maskPath);
  double kept = 0, reading = 0, shown = 0;
  for (size_t i = 0; i < files.size(); ++i) {
    const ImageInfo info = readImageInfo(files[i]);
    const double pixels = double(info.width) * double(info.height);
    kept += pixels * kFloatRgbPixelBytes;
    reading = std::max(reading, info.fileBytes + pixels * info.channels * info.bytesPerSample);
    if (i < 2) shown += pixels * kWindowPixelBytes;  // the image's window and the mask's
  }
  checkPeakMemory(kWindowSystemBytes + kept + reading + shown, o.dir,
                  std::to_string(files.size()) + " pictures and their windows",
                  "show fewer or smaller pictures");
}

void runShow(const ShowOptions& o) {
  const std::vector<ShowKey> keys = parseKeys(o.keys);
  const ShowSet set = readShowSet(o);
  checkShowMemory(o, set);
  // Read every picture before a window opens: a bad file is refused with nothing shown.
  const Image image = readImage(set.imagePath);
  Image mask;
  std::vector<Image> masks;
  for (const MaskPattern& p : set.maskPatterns) masks.push_back(readImage(p.file));
  if (!set.maskPath.empty()) mask = readImage(set.maskPath);
  const bool twoLayers = !masks.empty() || !mask.empty();

  std::vector<WindowRequest> requests{{"image", o.imageMonitor, !o.windowed, 0, 0}};
  if (twoLayers) {
    int maskMonitor = o.maskMonitor;
    if (maskMonitor < 0) maskMonitor = LayerWindows::monitorCount() > 1 ? 1 : 0;
    requests.push_back({"mask", maskMonitor, !o.windowed, image.width(), 0});
  }
  LayerWindows windows(requests);
  windows.show(0, image);
  int current = o.pattern;
  if (!masks.empty()) {
    windows.show(1, masks[size_t(current)]);
    printPattern(set.maskPatterns, current);
    std::printf("keys: right/space/n next, left/p previous, i the pattern's figures, q quit\n");
  } else if (!mask.empty()) {
    windows.show(1, mask);
  }
  std::fflush(stdout);
  windows.run(
      [&](ShowKey key) {
        if (key == ShowKey::Quit) return false;
        if (masks.empty()) return true;
        const int n = int(masks.size());
        if (key == ShowKey::Next || key == ShowKey::Previous) {
          current = (current + (key == ShowKey::Next ? 1 : n - 1)) % n;
          windows.show(1, masks[size_t(current)]);
          printPattern(set.maskPatterns, current);
        } else if (key == ShowKey::Info) {
          printPattern(set.maskPatterns, current);
        }
        return true;
      },
      o.exitAfter, keys);
}

}  // namespace

void registerShowCommand(CLI::App& cli) {
  auto o = std::make_shared<ShowOptions>();
  CLI::App* cmd =
      cli.add_subcommand("show",
                         "Show layers on the real panels (full screen, 1:1 pixels); step through "
                         "calibration patterns with the keyboard");
  cmd->add_option("dir", o->dir,
                  "Output folder of `render` (image.png, mask.png) or of `calibrate patterns` "
                  "(index.json)")
      ->required();
  cmd->add_option("--image-monitor", o->imageMonitor,
                  "Monitor for the image layer (or a lenticular panel), from 0")
      ->capture_default_str()
      ->check(integerIn(0, 63));
  cmd->add_option("--mask-monitor", o->maskMonitor,
                  "Monitor for the mask layer, from 0 (default: 1 if there are two, else 0)")
      ->check(integerIn(0, 63));
  cmd->add_flag("--windowed", o->windowed,
                "Plain windows side by side instead of full screen (a look without the panels)");
  cmd->add_option("--pattern", o->pattern, "The calibration mask pattern to start at, from 0")
      ->capture_default_str()
      ->check(integerIn(0, 100000));
  cmd->add_option("--exit-after", o->exitAfter, "Close after this many seconds (0: on q or Esc)")
      ->check(realIn(0, 1e6));
  cmd->add_option("--keys", o->keys,
                  "Keys to act on first, as if pressed: next, previous, info, quit (comma "
                  "separated)");
  cmd->callback([o] { runShow(*o); });
}

}  // namespace parallax::app
