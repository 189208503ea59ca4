// `parallax show DIR`: the layers on the real panels, full screen with 1:1 pixels, and the
// calibration pattern sets stepped through with the keyboard (docs/calibration.md, "On the
// panels").
#include <algorithm>
#include <chrono>
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
#include "parallax/jobs/limits.h"
#include "parallax/jobs/quilt_player.h"
#include "parallax/jobs/show_set.h"
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
  double fps = 0;  // frames: per second (0: pairs at the monitor's refresh, sequences at theirs)
  DisplayRequest display;  // a quilt's lenticular panel (a calibration or lkg:NAME)
};

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

void printPattern(const std::vector<jobs::MaskPattern>& patterns, int k) {
  const jobs::MaskPattern& p = patterns[size_t(k)];
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

// The panels' modes against the layers: 1:1 pixels need a layer the monitor's size, and two
// layers need two monitors.
void noteMonitorModes(const LayerWindows& windows, const std::vector<WindowRequest>& requests,
                      const std::vector<std::pair<int, int>>& sizes) {
  for (int k = 0; k < int(requests.size()); ++k) {
    const LayerWindows::Mode mode = windows.monitorMode(k);
    const auto [width, height] = sizes[size_t(k)];
    if (mode.width > 0 && (mode.width != width || mode.height != height))
      cliReporter().note(printed(
          "monitor %d is %dx%d and the %s layer %dx%d: shown 1:1 from the top-left corner, %s",
          requests[size_t(k)].monitor, mode.width, mode.height, requests[size_t(k)].title.c_str(),
          width, height,
          mode.width < width || mode.height < height ? "cut off at the monitor's edges"
                                                     : "not filling the monitor"));
  }
  if (requests.size() == 2 && requests[0].monitor == requests[1].monitor)
    cliReporter().note(printed(
        "both layers are on monitor %d, one over the other's place: a two-panel display needs "
        "each layer on its own monitor (--image-monitor, --mask-monitor)",
        requests[0].monitor));
}

// A quilt picture or video on a lenticular panel, interlaced as it is shown.
void runQuiltShow(const ShowOptions& o, const std::string& quilt) {
  const std::vector<ShowKey> keys = parseKeys(o.keys);
  if (o.display.path.empty())
    throw RequestError("display",
                       "a quilt is shown on the lenticular panel it is interlaced for: give "
                       "lkg:NAME or the panel's visual.json");
  jobs::QuiltPlayRequest request;
  request.quilt = quilt;
  request.display = o.display;
  request.otherBytes = kWindowSystemBytes;
  request.otherBytesPerPanelPixel = kWindowPixelBytes;
  jobs::QuiltPlayer player(request, cliReporter());
  const std::vector<WindowRequest> requests{{"image", o.imageMonitor, !o.windowed, 0, 0}};
  LayerWindows windows(requests);
  if (!o.windowed) noteMonitorModes(windows, requests, {{player.width(), player.height()}});
  long shown = 0;
  windows.streamFrames(0, player.width(), player.height(), [&](std::vector<uint8_t>& rgb) {
    ++shown;
    return player.next(rgb);
  });
  double period = 0;
  if (player.isVideo()) {
    const double fps = o.fps > 0 ? o.fps : player.fps() > 0 ? player.fps() : 30.0;
    period = 1.0 / fps;
    std::printf("playing %s: %d frames at %.3g frames/s (%s), interlaced for %dx%d as shown\n",
                fs::path(quilt).filename().c_str(), player.frames(), fps,
                o.fps > 0 ? "--fps" : "the video's", player.width(), player.height());
  } else {
    std::printf("showing %s interlaced for %dx%d\n", fs::path(quilt).filename().c_str(),
                player.width(), player.height());
  }
  std::fflush(stdout);
  const auto start = std::chrono::steady_clock::now();
  windows.run([](ShowKey key) { return key != ShowKey::Quit; }, o.exitAfter, keys, period);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const jobs::QuiltPlayer::Timing t = player.timing();
  if (player.isVideo() && t.frames > 0)
    std::printf(
        "shown %ld frames in %.2f s (%.1f frames/s); per frame: decode %.1f ms, interlace "
        "%.1f ms\n",
        shown, wall, double(shown) / std::max(wall, 1e-9), 1e3 * t.decodeSeconds / t.frames,
        1e3 * t.interlaceSeconds / t.frames);
}

void runShow(const ShowOptions& o) {
  if (const std::string quilt = jobs::quiltFile(o.dir); !quilt.empty())
    return runQuiltShow(o, quilt);
  if (!o.display.path.empty())
    throw RequestError("display", "applies to a quilt picture or video (NAME_qs{C}x{R}...)");
  const std::vector<ShowKey> keys = parseKeys(o.keys);
  const jobs::ShowSet set = jobs::readShowSet(o.dir, o.pattern);
  jobs::checkShowMemory(o.dir, set, {kWindowSystemBytes, kWindowPixelBytes, kRgba8PixelBytes});
  // Read every picture before a window opens: a bad file is refused with nothing shown.
  const Image image = readImage(set.imagePath);
  Image mask;
  std::vector<Image> masks, imageFrames, maskFrames;
  for (const jobs::MaskPattern& p : set.maskPatterns) masks.push_back(readImage(p.file));
  if (!set.maskPath.empty()) mask = readImage(set.maskPath);
  for (const std::string& f : set.imageFrames) imageFrames.push_back(readImage(f));
  for (const std::string& f : set.maskFrames) maskFrames.push_back(readImage(f));
  for (const auto* frames : {&imageFrames, &maskFrames})
    for (size_t k = 1; k < frames->size(); ++k)
      if ((*frames)[k].width() != frames->front().width() ||
          (*frames)[k].height() != frames->front().height())
        throw InputError(frames == &imageFrames ? set.imageFrames[k] : set.maskFrames[k], "",
                         "its size differs from the first frame's");
  const bool twoLayers = !masks.empty() || !mask.empty();

  std::vector<WindowRequest> requests{{"image", o.imageMonitor, !o.windowed, 0, 0}};
  if (twoLayers) {
    int maskMonitor = o.maskMonitor;
    if (maskMonitor < 0) maskMonitor = LayerWindows::monitorCount() > 1 ? 1 : 0;
    requests.push_back({"mask", maskMonitor, !o.windowed, image.width(), 0});
  }
  LayerWindows windows(requests);
  if (!o.windowed) {
    std::vector<std::pair<int, int>> sizes{{image.width(), image.height()}};
    if (twoLayers) {
      const Image& layer = mask.empty() ? masks.front() : mask;
      sizes.emplace_back(layer.width(), layer.height());
    }
    noteMonitorModes(windows, requests, sizes);
  }
  double framePeriod = 0;
  if (!imageFrames.empty()) {
    windows.showFrames(0, imageFrames);
    if (!maskFrames.empty()) windows.showFrames(1, maskFrames);
    const int refresh = windows.monitorMode(0).refreshHz;
    const double fps = o.fps > 0 ? o.fps : set.fps > 0 ? set.fps : refresh > 0 ? refresh : 60.0;
    framePeriod = 1.0 / fps;
    std::printf("playing %zu %s at %.3g frames/s (%s)\n", imageFrames.size(), set.framesKind, fps,
                o.fps > 0     ? "--fps"
                : set.fps > 0 ? "the sequence's"
                : refresh > 0 ? "the monitor's refresh rate"
                              : "60 Hz: the monitor's refresh rate is unknown");
    std::fflush(stdout);
  } else {
    windows.show(0, image);
  }
  int current = o.pattern;
  if (!masks.empty()) {
    windows.show(1, masks[size_t(current)]);
    printPattern(set.maskPatterns, current);
    std::printf("keys: right/space/n next, left/p previous, i the pattern's figures, q quit\n");
  } else if (!mask.empty() && maskFrames.empty()) {
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
      o.exitAfter, keys, framePeriod);
}

}  // namespace

void registerShowCommand(Command& cli) {
  auto o = std::make_shared<ShowOptions>();
  Command* cmd =
      cli.addSubcommand("show",
                        "Show layers on the real panels (full screen, 1:1 pixels); step through "
                        "calibration patterns with the keyboard");
  cmd->addOption("dir", o->dir,
                 "Output folder of `render` (image.png, mask.png; nmf's image-K.png and "
                 "mask-K.png pairs and a sequence's frame-NNNN folders are played) or of "
                 "`calibrate patterns` (index.json); or a quilt picture or video "
                 "(NAME_qs{C}x{R}a{aspect}.png/.mp4/.webm, or a folder holding one) with "
                 "--display, interlaced for that lenticular panel as it is shown")
      ->required();
  addDisplayOption(*cmd, o->display,
                   "With a quilt: the lenticular panel it is shown on (lkg:NAME or its "
                   "visual.json)");
  cmd->addOption("--image-monitor", o->imageMonitor,
                 "Monitor for the image layer (or a lenticular panel), from 0")
      ->captureDefault()
      ->check(integerIn(0, 63));
  cmd->addOption("--mask-monitor", o->maskMonitor,
                 "Monitor for the mask layer, from 0 (default: 1 if there are two, else 0)")
      ->check(integerIn(0, 63));
  cmd->addFlag("--windowed", o->windowed,
               "Plain windows side by side instead of full screen (a look without the panels)");
  cmd->addOption("--pattern", o->pattern, "The calibration mask pattern to start at, from 0")
      ->captureDefault()
      ->check(integerIn(0, 100000));
  cmd->addOption("--exit-after", o->exitAfter, "Close after this many seconds (0: on q or Esc)")
      ->check(realIn(0, 1e6));
  cmd->addOption("--fps", o->fps,
                 "Frames per second for a folder of frames: nmf's time-multiplexed pairs "
                 "(default: the monitor's refresh rate) or a sequence's frame-NNNN folders "
                 "(default: the sequence's fps); for a quilt video (default: the video's)")
      ->check(realIn(0.001, 1000));
  cmd->addOption("--keys", o->keys,
                 "Keys to act on first, as if pressed: next, previous, info, quit (comma "
                 "separated)");
  cmd->callback([o] { runShow(*o); });
}

}  // namespace parallax::app
