// The show set (show_set.h).
#include "parallax/jobs/show_set.h"

#include <algorithm>
#include <filesystem>

#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_reader.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/quilt_player.h"

namespace parallax::jobs {

namespace {

namespace fs = std::filesystem;

// nmf's frame pairs of a render folder: image-1.png, mask-1.png, image-2.png, ...
void readFramePairs(const fs::path& dir, ShowSet& set) {
  for (int k = 1;; ++k) {
    const fs::path image = dir / ("image-" + std::to_string(k) + ".png");
    const fs::path mask = dir / ("mask-" + std::to_string(k) + ".png");
    if (!fs::exists(image)) break;
    if (!fs::exists(mask))
      throw InputError(mask.string(), "",
                       "missing: frame pair " + std::to_string(k) + " has no mask");
    set.imageFrames.push_back(image.string());
    set.maskFrames.push_back(mask.string());
  }
  set.framesKind = "time-multiplexed frame pairs";
}

// A sequence's frames (render --frames): frame-NNNN/image.png (and mask.png), at the fps its
// render.json records.
void readSequence(const fs::path& dir, ShowSet& set) {
  std::vector<fs::path> frames;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_directory() && name.rfind("frame-", 0) == 0 &&
        fs::exists(entry.path() / "image.png"))
      frames.push_back(entry.path());
  }
  std::sort(frames.begin(), frames.end());
  for (const fs::path& frame : frames) {
    set.imageFrames.push_back((frame / "image.png").string());
    if (fs::exists(frame / "mask.png")) set.maskFrames.push_back((frame / "mask.png").string());
  }
  if (!set.maskFrames.empty() && set.maskFrames.size() != set.imageFrames.size())
    throw InputError(dir.string(), "", "some frames have a mask.png and others not");
  const fs::path record = frames.front() / "render.json";
  if (fs::exists(record)) {
    const JsonDocument doc = JsonDocument::parseFile(record.string());
    if (const auto sequence = doc.root().find("sequence"))
      set.fps = (*sequence)["fps"].number(1e-3, 1000);
  }
  set.framesKind = "sequence frames";
}

bool hasSequenceFrames(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_directory() && entry.path().filename().string().rfind("frame-", 0) == 0 &&
        fs::exists(entry.path() / "image.png"))
      return true;
  return false;
}

}  // namespace

ShowSet readShowSet(const std::string& folder, int pattern) {
  const fs::path dir(folder);
  if (!fs::is_directory(dir))
    throw InputError(folder, "", "not a folder: give the output folder of render or calibrate");
  ShowSet set;
  const fs::path index = dir / "index.json";
  if (fs::exists(index)) {  // calibrate patterns: one image pattern, mask patterns to step
    const JsonDocument doc = JsonDocument::parseFile(index.string());
    if (doc.root().has("shots")) {
      // calibrate patterns --photo: one shot, on both layers (barrier) or the panel.
      const JsonReader shots = doc.root()["shots"];
      if (shots.size() != 1) throw InputError(index.string(), "/shots", "expected one shot");
      const JsonReader shot = shots.elements().front();
      if (shot.has("panel")) {
        set.imagePath = (dir / shot["panel"].string()).string();
      } else {
        set.imagePath = (dir / shot["image"].string()).string();
        set.maskPath = (dir / shot["mask"].string()).string();
      }
      return set;
    }
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
    if (pattern < 0 || pattern >= int(set.maskPatterns.size()))
      throw RequestError("pattern", "expected 0 to " + std::to_string(set.maskPatterns.size() - 1));
    return set;
  }
  set.imagePath = (dir / "image.png").string();
  if (fs::exists(dir / "mask.png")) set.maskPath = (dir / "mask.png").string();
  if (!fs::exists(set.imagePath)) {
    if (fs::exists(dir / "image-1.png"))
      readFramePairs(dir, set);
    else if (hasSequenceFrames(dir))
      readSequence(dir, set);
    if (set.imageFrames.empty()) {
      bool quilt = false;
      for (const auto& entry : fs::directory_iterator(dir))
        quilt |= entry.path().filename().string().find("_qs") != std::string::npos;
      throw InputError(set.imagePath, "",
                       quilt ? "missing: the folder holds several quilts: show one of them "
                               "(with --display, the lenticular panel), or map one onto a "
                               "barrier with `parallax interlace` (docs/quilts.md)"
                             : "missing: give the output folder of render (image.png, nmf's "
                               "image-K.png pairs, or a sequence's frame-NNNN folders) or of "
                               "calibrate");
    }
    set.imagePath = set.imageFrames.front();
    if (!set.maskFrames.empty()) set.maskPath = set.maskFrames.front();
  }
  return set;
}

std::string quiltFile(const std::string& given) {
  const fs::path path(given);
  const auto isQuilt = [](const fs::path& p) {
    const std::string name = p.filename().string();
    std::string ext = p.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return name.find("_qs") != std::string::npos &&
           (ext == ".png" || ext == ".jpg" || ext == ".jpeg" || isVideoPath(name));
  };
  if (!fs::is_directory(path)) return isQuilt(path) ? path.string() : "";
  if (fs::exists(path / "image.png") || fs::exists(path / "image-1.png")) return "";
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(path))
    if (entry.is_regular_file() && isQuilt(entry.path())) found.push_back(entry.path().string());
  std::sort(found.begin(), found.end());
  return found.size() == 1 ? found.front() : "";
}

void checkShowMemory(const std::string& dir, const ShowSet& set, const WindowCosts& windows) {
  std::vector<std::string> files{set.imagePath};
  for (const MaskPattern& p : set.maskPatterns) files.push_back(p.file);
  if (!set.maskPath.empty()) files.push_back(set.maskPath);
  double kept = 0, reading = 0, shown = 0;
  for (size_t i = 0; i < files.size(); ++i) {
    const ImageInfo info = readImageInfo(files[i]);
    const double pixels = double(info.width) * double(info.height);
    kept += pixels * kFloatRgbPixelBytes;
    reading = std::max(reading, info.fileBytes + pixels * info.channels * info.bytesPerSample);
    if (i < 2) shown += pixels * windows.pixelBytes;  // the image's window and the mask's
  }
  // Frames after the first: each kept as a float image and as its window's texture.
  for (const auto* list : {&set.imageFrames, &set.maskFrames})
    for (size_t i = 1; i < list->size(); ++i) {
      const ImageInfo info = readImageInfo((*list)[i]);
      const double pixels = double(info.width) * double(info.height);
      kept += pixels * kFloatRgbPixelBytes;
      reading = std::max(reading, info.fileBytes + pixels * info.channels * info.bytesPerSample);
      shown += pixels * windows.texturePixelBytes;
    }
  checkPeakMemory(windows.systemBytes + kept + reading + shown, dir,
                  std::to_string(files.size()) + " pictures and their windows",
                  "show fewer or smaller pictures");
}

}  // namespace parallax::jobs
