// What `parallax show DIR` shows (docs/calibration.md, "On the panels"): a render's layers, nmf's
// frame pairs, a sequence's frames, a calibration set's patterns, or one quilt; read from the
// folder and checked before any picture is decoded. The windows are the front end's.
#pragma once

#include <string>
#include <vector>

namespace parallax::jobs {

// A calibration pattern set's mask patterns, as index.json lists them.
struct MaskPattern {
  std::string file, purpose, label;
  double screenPeriodPx = 0, slitPeriodPx = 0, phasePx = 0, distanceMm = 0;
};

struct ShowSet {
  std::string imagePath;                  // the image layer (or the lenticular panel)
  std::string maskPath;                   // a render's mask layer; empty for one panel
  std::vector<MaskPattern> maskPatterns;  // a calibration set's, stepped through
  // Frames played one after another: nmf's time-multiplexed pairs (image-K.png, mask-K.png;
  // imagePath and maskPath are the first) or a sequence's frames (frame-NNNN/).
  std::vector<std::string> imageFrames, maskFrames;
  double fps = 0;  // a sequence's own; 0 for pairs (the monitor's refresh)
  const char* framesKind = "";
};

// The set in `dir` (a render's or calibrate's output folder); `pattern`: the calibration
// pattern shown first (refused when the set has no such pattern).
ShowSet readShowSet(const std::string& dir, int pattern);

// A quilt's file: `path` itself, or the one quilt picture or video (a name with _qs) in the
// folder `path` when it has no image.png; "" for neither.
std::string quiltFile(const std::string& path);

// What the windows cost (window/layer_windows.h): the window system, a window's copy of a
// pixel it shows, and a frame's texture pixel.
struct WindowCosts {
  double systemBytes = 0, pixelBytes = 0, texturePixelBytes = 0;
};
// The whole estimate before any picture is decoded, from their headers (docs/inputs.md,
// "Memory"): every picture kept as a float image; while one is read, its file and stb_image's
// samples; the window system and the windows' copies of what they show.
void checkShowMemory(const std::string& dir, const ShowSet& set, const WindowCosts& windows);

}  // namespace parallax::jobs
