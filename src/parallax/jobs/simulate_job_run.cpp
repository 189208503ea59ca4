// runSimulate (jobs/simulate_job.h): the inputs of a render folder, the pictures of one or more
// eyes or a sweep (contact sheet, animation, slider page, video), a sequence's frames, and the
// figures at the eyes.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/core/output_path.h"
#include "parallax/image/contact_sheet.h"
#include "parallax/importer/scene_file.h"
#include "parallax/io/animation.h"
#include "parallax/io/html_viewer.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_reader.h"
#include "parallax/io/json_writer.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/lens_readings.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/sequence.h"
#include "parallax/jobs/simulate_parts.h"
#include "parallax/jobs/video_output.h"
#include "parallax/sim/simulated_display.h"

namespace parallax::jobs {

namespace fs = std::filesystem;

LayerSet loadLayerSet(const std::string& folder, bool hasMask) {
  const fs::path dir(folder);
  LayerSet set;
  const fs::path recordPath = dir / "render.json";
  if (fs::exists(recordPath)) {
    const JsonDocument record = JsonDocument::parseFile(recordPath.string());
    if (const auto layers = record.root().find("layers"))
      if (const auto n = layers->find("normalisation")) set.normalisation = n->number(0, 1e6);
    if (const auto frames = record.root().find("frames")) {
      for (const JsonReader& frame : frames->elements()) {
        LayerImages f;
        f.image = readImage((dir / frame["image"].string()).string());
        if (hasMask) f.mask = readImage((dir / frame["mask"].string()).string());
        set.frames.push_back(std::move(f));
      }
      if (set.frames.empty()) frames->fail("lists no frames");
      return set;
    }
  }
  LayerImages f;
  f.image = readImage((dir / "image.png").string());
  if (hasMask) f.mask = readImage((dir / "mask.png").string());
  set.frames.push_back(std::move(f));
  return set;
}

SimulateInputs loadSimulateInputs(const SimulateRequest& r, Reporter& reporter) {
  const fs::path dir(r.dir);
  const auto inDir = [&dir](const char* name) { return (dir / name).string(); };
  // The display: the request's, else the folder's display.json (barrier) or visual.json
  // (lenticular), else the built-in one.
  std::string folderDisplay;
  for (const char* name : {"display.json", "visual.json"})
    if (folderDisplay.empty() && fs::exists(inDir(name))) folderDisplay = inDir(name);
  SimulateInputs in;
  in.scene = r.scene;
  in.display = makeDisplay(r.display.describe(reporter, folderDisplay), r.display.camera()).model;
  checkMaskLayer(*in.display, !r.mask.empty());
  if (r.image.empty() && r.mask.empty()) {
    LayerSet set = loadLayerSet(r.dir, in.display->hasMaskLayer());
    in.frames = std::move(set.frames);
    in.normalisation = set.normalisation;
    in.layers = in.frames.front();
  } else {
    in.layers.image = readImage(r.image.empty() ? inDir("image.png") : r.image);
    if (in.display->hasMaskLayer())
      in.layers.mask = readImage(r.mask.empty() ? inDir("mask.png") : r.mask);
    in.frames = {in.layers};
  }
  if (in.scene.empty() && fs::exists(inDir("render.json"))) {
    const JsonDocument record = JsonDocument::parseFile(inDir("render.json"));
    in.scene = record.root().string("scene", "<built-in>");
  }
  if (in.scene == "<built-in>") in.scene.clear();
  return in;
}

RenderedReference renderedScene(const SimulateInputs& in, const SimulateRequest& r) {
  applyImporterLimits();
  return referenceScene(loadSceneAsRendered(in.scene, r.dir), *in.display);
}

namespace {

// FILE for one output, FILE-K for the K-th of several.
std::string numbered(const std::string& path, size_t index, size_t count) {
  if (count == 1) return path;
  const fs::path p(path);
  return (p.parent_path() /
          (p.stem().string() + "-" + std::to_string(index) + p.extension().string()))
      .string();
}

std::string eyeLabel(const Vec3d& e) {
  return printed("x=%.0f z=%.0f", e.x, e.z);
}

// frames: what one eye sees in each frame of a sequence that `render` wrote (DIR/frame-NNNN),
// as OUTPUT-NNNN.png, and with a video as one video.
void runSimulateFrames(const SimulateRequest& r, Reporter& reporter) {
  if (r.sweep.count > 0)
    throw RequestError("frames",
                       "simulates one eye per frame: give {eye} (or none: the zone's centre), not "
                       "{sweep}");
  if (r.eyes.size() > 1) throw RequestError("frames", "simulates one eye per frame: one {eye}");
  if (r.reference && r.eyes.empty())
    throw RequestError("frames",
                       "with {reference}, give the eye ({eye}): the dense measure is per frame");
  // The frames there are: frame-NNNN folders holding a finished render.
  int lastFound = 0;
  std::error_code ec;
  for (fs::directory_iterator it(r.dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind("frame-", 0) != 0 || name.size() > 15) continue;
    const std::string digits = name.substr(6);
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    if (fs::is_regular_file(it->path() / "render.json"))
      lastFound = std::max(lastFound, std::stoi(digits));
  }
  if (lastFound == 0)
    throw InputError(r.dir, "", "holds no rendered frames (frame-NNNN folders of render {frames})");
  int first = 1, last = lastFound;
  if (r.frames != "all") parseFrameRange(r.frames, lastFound, first, last);
  if (r.video.wanted()) checkVideoRequest(r.video);
  const std::string output = r.output.empty() ? "out/simulated.png" : r.output;
  checkOutputFile(output);
  std::vector<std::string> pictures;
  for (int frame = first; frame <= last; ++frame) {
    SimulateRequest one = r;
    one.frames.clear();
    one.video = {};
    one.dir = (fs::path(r.dir) / frameName(frame)).string();
    one.output = numberedPicture(output, frame);
    if (!fs::is_regular_file(fs::path(one.dir) / "render.json"))
      throw InputError(one.dir, "", "is missing: the sequence is not finished (render it again)");
    runSimulate(one, reporter);
    pictures.push_back(one.output);
  }
  if (r.video.wanted()) writeVideo(pictures, r.video, reporter);
}

// The outputs' record (json): the display, the files, the video and the eyes with their figures.
void reportJson(const DisplayModel& display, const std::vector<std::string>& written,
                const VideoOutput* video, const std::vector<Vec3d>& eyes,
                const std::vector<EyeFigures>& figures, Reporter& reporter) {
  JsonWriter json;
  json.set("/display", display.source());
  json.set("/display_kind", displayKindName(display.kind()));
  for (size_t i = 0; i < written.size(); ++i) json.set("/outputs/" + std::to_string(i), written[i]);
  if (video) {
    const VideoWriter& v = video->writer();
    json.set("/video/file", v.path());
    json.set("/video/frames", v.frames());
    json.set("/video/codec", v.codec());
    json.set("/video/coded_width", v.codedWidth());
    json.set("/video/coded_height", v.codedHeight());
  }
  recordEyeFigures(json, eyes, figures);
  reporter.result(json.dump());
}

// The figures' table, one row an eye.
void reportFigures(const std::vector<Vec3d>& eyes, const std::vector<EyeFigures>& figures,
                   Reporter& reporter) {
  reporter.result(printed("%-24s %8s %7s %10s %9s %4s", "eye (mm)", "PSNR dB", "SSIM", "brightness",
                          "crosstalk", "view"));
  for (size_t i = 0; i < eyes.size(); ++i) {
    const std::string eye = printed("%.1f,%.1f,%.1f", eyes[i].x, eyes[i].y, eyes[i].z);
    const EyeFigures& q = figures[i];
    reporter.result(printed("%-24s %8.2f %7.4f %10.4f %9.4f %4d", eye.c_str(), q.psnr, q.ssim,
                            q.brightness, q.crosstalk, q.ownView));
  }
}

}  // namespace

namespace {

// The contact sheet's thumbnail width: at most 480 pixels and the picture's width, and small
// enough that the thumbnails of all `eyes` hold at most kSweepSheetPixels, so that a long sweep's
// sheet stays bounded (its PNGs are what grows with the eyes).
constexpr double kSweepSheetPixels = 4e6;
int sweepThumbnailWidth(int width, int height, size_t eyes) {
  const double fit = std::sqrt(kSweepSheetPixels / double(eyes) * double(width) / double(height));
  return std::max(1, std::min({480, width, int(fit)}));
}

// The sweep's estimate, made once its first picture's PNG is known (the others compress alike):
// per eye its PNG and thumbnail, kept to the end; then the contact sheet (the thumbnails again,
// the sheet and its PNG codes) or, after it, the animated PNG (the PNGs again) and the
// slider page (the PNGs in base64, 4/3 their size).
void checkSweepMemory(size_t eyes, double pngBytes, int width, int height, int thumbnailWidth,
                      int sweep) {
  const double n = double(eyes);
  const double thumbnailHeight = std::max(1.0, std::round(double(height) * thumbnailWidth / width));
  const double thumbnails = n * imageBytes(thumbnailWidth, thumbnailHeight);
  const double sheetRows = std::ceil(n / std::min(n, 3.0));
  const double sheetPixels = (std::min(n, 3.0) * (thumbnailWidth + 4) + 4) * sheetRows *
                             (thumbnailHeight + kLabelStripHeight + 4);
  const double sheet = thumbnails + sheetPixels * (kFloatRgbPixelBytes + kRgb8PixelBytes);
  const double pages = std::max(sheet, n * pngBytes * 4.0 / 3.0);
  checkPeakMemory(n * pngBytes + thumbnails + pages, "{sweep} " + std::to_string(sweep),
                  std::to_string(eyes) + " simulated views (their PNGs, contact sheet and page)",
                  "use fewer steps");
}

}  // namespace

void runSimulate(const SimulateRequest& r, Reporter& reporter) {
  // The measure's own inputs without the measure: refused, not ignored.
  if (!r.compare.empty() && !(r.reference && r.eyes.empty() && r.sweep.count == 0))
    throw RequestError("compare",
                       "scores other renders in the dense measure: needs {reference} without "
                       "{eye} or {sweep}");
  if (!r.scene.empty() && !r.reference)
    throw RequestError("scene",
                       "is the scene {reference} renders the ideal views of: add {reference}");
  if (!r.frames.empty()) return runSimulateFrames(r, reporter);
  if (r.video.wanted()) {
    if (r.sweep.count == 0)
      throw RequestError("video",
                         "needs {sweep} N or {frames}: the video's frames are the sweep's pictures "
                         "or the sequence's");
    checkVideoRequest(r.video);
  }
  if (r.reference) checkReferenceSpp(r.referenceSpp);
  // Where the pictures go can take them, before anything is loaded (docs/inputs.md, "Outputs"):
  // one file, or a sweep's files beside its prefix.
  if (r.sweep.count > 0)
    checkOutputFolder(fs::path(r.output.empty() ? "out/sweep" : r.output).parent_path().string());
  else
    checkOutputFile(r.output.empty() ? "out/simulated.png" : r.output);
  const SimulateInputs in = loadSimulateInputs(r, reporter);
  const DisplayModel& display = *in.display;
  SimulationOptions sim = simulationOptions(r.simulator, display);
  const std::vector<Vec3d> eyes = simulatedEyes(display, r.eyes, r.sweep);
  checkSimulationWork(display, in.layers, r.simulator, eyes.size(), r.sweep.count,
                      r.reference ? r.referenceSpp : 0);
  if (r.allReadings && !(r.reference && r.eyes.empty() && r.sweep.count == 0))
    throw RequestError("all_readings",
                       "applies to the dense measure ({reference} without {eye} "
                       "or {sweep})");
  if (r.allReadings && lensReadings(display).empty())
    throw RequestError("all_readings", "applies to lenticular displays (the lenses' optics)");
  if (const std::string line = lensReadingLine(display, sim); !line.empty() && !r.allReadings)
    reporter.note(line);
  if (r.reference && r.eyes.empty() && r.sweep.count == 0)
    return runDenseReference(r, in, sim, reporter);
  // reference: the scene is read (and checked) before any picture is written.
  std::optional<RenderedReference> scene;
  if (r.reference) scene = renderedScene(in, r);
  if (sim.normalise) sim.normalisation = in.normalisation;
  const std::unique_ptr<SimulatedDisplay> simulator = simulateDisplay(display, in.frames, sim);
  std::optional<Accelerator> accelerator;
  std::optional<QualityReference> reference;
  if (r.reference) {
    accelerator.emplace(scene->scene);
    reference.emplace(QualityReference{scene->scene, *accelerator, *scene->display, *simulator,
                                       in.frames, sim, r.referenceSpp});
  }

  // One eye at a time: its view, the picture, the figures, then only the encoded picture (and a
  // sweep's thumbnail) is kept, so memory does not grow with the eyes.
  const bool sweep = r.sweep.count > 0;
  const fs::path sweepOut(r.output.empty() ? "out/sweep" : r.output);
  // The sweep's files share a prefix: a given extension is dropped (-o out/sweep.png).
  const std::string prefix = (sweepOut.parent_path() / sweepOut.stem()).string();
  const std::string path = r.output.empty() ? "out/simulated.png" : r.output;
  std::vector<std::string> written, labels, pngs;
  std::vector<Image> thumbnails;
  int thumbnailWidth = 1;
  std::vector<EyeFigures> figures;
  // A sweep's video: each picture is encoded as it is made (the file is moved into place at the
  // end, with the sweep's other files).
  std::optional<VideoOutput> video;
  if (r.video.wanted()) video.emplace(r.video);
  std::string videoLine;
  for (size_t i = 0; i < eyes.size(); ++i) {
    const Image view = simulator->view(eyes[i]);
    // Pictures as perceived: a viewer at the design distance does not resolve single pixels
    // (0.27 mm at 600 mm is about 1.5 arc minutes), so each output pixel shows the light of one
    // screen period (one lens) around it; raw pixels keep the eye's samples as they are.
    const Image picture = seenPicture(*simulator, view, r.simulator.rawPixels);
    if (reference)
      figures.push_back(
          eyeFigures(*reference, eyes[i], view,
                     r.simulator.rawPixels ? simulator->atDisplayResolution(view) : picture));
    if (sweep) {
      labels.push_back(eyeLabel(eyes[i]));
      pngs.push_back(pngBytes(picture, false));
      if (i == 0) {
        thumbnailWidth = sweepThumbnailWidth(picture.width(), picture.height(), eyes.size());
        // The first picture's PNG tells the others' size: the estimate of the whole sweep.
        checkSweepMemory(eyes.size(), double(pngs[0].size()), picture.width(), picture.height(),
                         thumbnailWidth, r.sweep.count);
      }
      // The contact sheet's thumbnail now, so the picture need not be kept.
      thumbnails.push_back(contactThumbnail(picture, thumbnailWidth));
      if (video) video->add(picture);
    } else {
      writeImage(numbered(path, i, eyes.size()), picture);
      written.push_back(numbered(path, i, eyes.size()));
    }
  }
  if (sweep) {
    writeImage(prefix + "-sheet.png",
               contactSheet(thumbnails, std::min<int>(int(thumbnails.size()), 3),
                            thumbnails.front().width(), labels));
    std::vector<Image>().swap(thumbnails);  // the sheet is written: free before the page
    writeFileAtomically(prefix + "-anim.png", encodeApngFromPngs(pngs, 250));
    // The display file's name, not its path: a page is shared, and the path is the sharer's.
    const std::string title =
        "parallax: eye sweep across " + fs::path(display.source()).filename().string();
    writeFileAtomically(prefix + ".html", sliderPage(title, pngs, labels));
    written = {prefix + "-sheet.png", prefix + "-anim.png", prefix + ".html"};
    if (video) {
      videoLine = video->finish();
      written.push_back(r.video.file);
    }
  }
  if (r.json)
    return reportJson(display, written, video ? &*video : nullptr, eyes, figures, reporter);
  for (const std::string& file : written)
    if (!video || file != r.video.file) reporter.result("wrote " + file);
  if (video) reporter.result(videoLine);
  if (!figures.empty()) reportFigures(eyes, figures, reporter);
}

}  // namespace parallax::jobs
