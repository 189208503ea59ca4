// `parallax simulate`: what an eye in front of the display sees, without the hardware; eye
// sweeps (contact sheet, animation, slider page), and quality figures against the ideal view.
#include <CLI/CLI.hpp>

#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>

#include "parallax/accel/accelerator.h"
#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/camera/display_camera.h"
#include "parallax/camera/framing.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/image/contact_sheet.h"
#include "parallax/image/metrics.h"
#include "parallax/io/animation.h"
#include "parallax/io/display_file.h"
#include "parallax/io/html_viewer.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_reader.h"
#include "parallax/io/json_writer.h"
#include "parallax/io/scene_file.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/sequence.h"
#include "parallax/jobs/video_output.h"
#include "parallax/quality/viewer_quality.h"
#include "parallax/render/render.h"
#include "parallax/sim/crosstalk.h"
#include "parallax/sim/simulated_display.h"
#include "parallax/sim/simulator.h"

namespace parallax::app {

namespace {

namespace fs = std::filesystem;

struct SimulateOptions {
  std::string dir = "out";
  std::string frames;  // --frames FIRST:LAST|all: DIR is a sequence (docs/animation.md)
  std::string image, mask, display, scene;
  std::vector<std::string> eyes;
  std::string output;
  std::string size;
  int spp = 0;  // 0: each output pixel's area exactly; n*n: point samples (for comparison)
  double pupil = 0.0;
  int pupilSamples = 16;
  double diffuser = 0.0;
  bool colourFilters = false;
  bool raw = false;
  int sweep = 0;
  double sweepRange = 1.0;
  double sweepDistance = 0.0;
  bool reference = false;
  int referenceSpp = 16;
  int eyesPerView = 4;
  std::string distances = "0.8,1,1.25";
  std::vector<std::string> compare;
  bool json = false;
  int threads = 0;
  bool rawPixels = false;
  VideoCliOptions video;
};

// The inputs: a `render` output folder, or its pictures with a display file, of any kind.
struct Inputs {
  std::unique_ptr<DisplayModel> display;
  LayerImages layers;               // the first frame
  std::vector<LayerImages> frames;  // every frame (render --layers nmf --rank T), layers first
  double normalisation = 0;         // render.json's /layers/normalisation (0: the mask's mean)
  std::string scene;                // for --reference: the scene the layers were rendered from
  const DisplayDesign* barrier() const { return display->barrierDesign(); }
};

// The layers of a render folder: its frames when render.json lists them (/frames), else
// image.png and mask.png; and the normalisation optimised layers aimed at.
struct LayerSet {
  std::vector<LayerImages> frames;
  double normalisation = 0;
};

LayerSet loadLayerSet(const fs::path& dir, bool hasMask) {
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

Inputs loadInputs(const SimulateOptions& o) {
  const fs::path dir(o.dir);
  const auto inDir = [&dir](const char* name) { return (dir / name).string(); };
  // The display: --display, else the folder's display.json (barrier) or visual.json
  // (lenticular), else the built-in one.
  std::string displayPath = o.display;
  for (const char* name : {"display.json", "visual.json"})
    if (displayPath.empty() && fs::exists(inDir(name))) displayPath = inDir(name);
  const DisplayDescription description = loadDisplayOrDefault(displayPath);
  Inputs in;
  in.scene = o.scene;
  in.display = jobs::makeDisplay(description).model;
  if (!o.mask.empty() && !in.display->hasMaskLayer())
    throw InputError("command line", "--mask", "a lenticular display has no mask layer");
  if (o.image.empty() && o.mask.empty()) {
    LayerSet set = loadLayerSet(dir, in.display->hasMaskLayer());
    in.frames = std::move(set.frames);
    in.normalisation = set.normalisation;
    in.layers = in.frames.front();
  } else {
    in.layers.image = readImage(o.image.empty() ? inDir("image.png") : o.image);
    if (in.display->hasMaskLayer())
      in.layers.mask = readImage(o.mask.empty() ? inDir("mask.png") : o.mask);
    in.frames = {in.layers};
  }
  if (in.scene.empty() && fs::exists(inDir("render.json"))) {
    const JsonDocument record = JsonDocument::parseFile(inDir("render.json"));
    in.scene = record.root().string("scene", "<built-in>");
  }
  if (in.scene == "<built-in>") in.scene.clear();
  return in;
}

// The scene the layers were rendered from, as they framed it (a barrier's framing; a
// lenticular render places the scene as it is).
Scene referenceScene(const Inputs& in, const SimulateOptions& o) {
  Scene scene = loadSceneAsRendered(in.scene, o.dir);
  if (const DisplayDesign* d = in.barrier()) return framedScene(std::move(scene), *d);
  return scene;
}

std::vector<Vec3d> eyePositions(const SimulateOptions& o, const DisplayModel& display) {
  std::vector<Vec3d> eyes;
  for (const std::string& text : o.eyes) {
    const Vec3f e = parseVec3("--eye", text);
    if (!(e.z > 0)) throw InputError("command line", "--eye", "the eye must be in front (z > 0)");
    eyes.push_back({e.x, e.y, e.z});
  }
  const Vec3d centre = display.window().eyeMm;  // the zone's centre at the design distance D
  if (o.sweep > 0) {
    if (o.sweepDistance > 100 * centre.z)
      throw InputError("--sweep-distance", "",
                       "must be at most 100 times the design distance D = " +
                           std::to_string(int(centre.z)) + " mm");
    const double z = o.sweepDistance > 0 ? o.sweepDistance : centre.z;
    // Across the view zone (scaled by --sweep-range), scaled to the distance so that a
    // farther sweep covers the same views.
    for (int i = 0; i < o.sweep; ++i) {
      const double t = o.sweep == 1 ? 0.5 : double(i) / double(o.sweep - 1);
      const Vec3d e = display.eyeAcrossZone(0.5 + o.sweepRange * (t - 0.5));
      eyes.push_back({centre.x + (e.x - centre.x) * z / centre.z, centre.y, z});
    }
  }
  if (eyes.empty()) eyes.push_back(centre);
  return eyes;
}

// FILE for one output, FILE-K for the K-th of several.
std::string numbered(const std::string& path, size_t index, size_t count) {
  if (count == 1) return path;
  const fs::path p(path);
  return (p.parent_path() /
          (p.stem().string() + "-" + std::to_string(index) + p.extension().string()))
      .string();
}

std::string eyeLabel(const Vec3d& e) {
  char text[64];
  std::snprintf(text, sizeof text, "x=%.0f z=%.0f", e.x, e.z);
  return text;
}

struct Quality {
  double psnr = 0, ssim = 0, brightness = 0, crosstalk = 0;
  int ownView = 0;
};

// "0.8,1,1.25": eye distances in units of the design distance D.
std::vector<double> parseDistances(const std::string& text) {
  std::vector<double> distances;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t end = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, end - start);
    char* rest = nullptr;
    const double f = std::strtod(item.c_str(), &rest);
    if (item.empty() || *rest != '\0' || !(f >= 0.1 && f <= 10))
      throw InputError("command line", "--distances",
                       "expected distances in units of D between 0.1 and 10, separated by commas, "
                       "got '" +
                           text + "'");
    distances.push_back(f);
    start = end + 1;
  }
  return distances;
}

void printSummaryRow(const char* label, const QualitySummary& s) {
  std::printf("%-22s %5d %9.2f %7.4f %9.2f %9.4f\n", label, s.eyes, s.meanPsnr, s.meanSsim,
              s.worstPsnr, s.meanFlicker);
}

void setSummary(JsonWriter& json, const std::string& at, const QualitySummary& s) {
  json.set(at + "/eyes", s.eyes);
  json.set(at + "/psnr", s.meanPsnr);
  json.set(at + "/ssim", s.meanSsim);
  json.set(at + "/worst_psnr", s.worstPsnr);
  json.set(at + "/worst_eye", Vec3f{float(s.worstEye.x), float(s.worstEye.y), float(s.worstEye.z)});
  json.set(at + "/flicker", s.meanFlicker);
}

// The dense measure of several renders side by side: one row (one JSON entry) each.
// `brightness[k]`: what render k's views send to the eye (their mean luminance times the
// normalisation the simulator divided by), over the first render's.
void printComparison(const SimulateOptions& o, const std::vector<std::string>& labels,
                     const std::vector<ViewerQuality>& results,
                     const std::vector<double>& brightness) {
  if (o.json) {
    JsonWriter json;
    json.set("/eyes_per_view", o.eyesPerView);
    for (size_t k = 0; k < results.size(); ++k) {
      const std::string at = "/renders/" + std::to_string(k);
      json.set(at + "/dir", labels[k]);
      setSummary(json, at + "/mean", results[k].all);
      setSummary(json, at + "/design_eyes", results[k].designOnly);
      json.set(at + "/brightness_vs_first", brightness[k]);
      for (size_t i = 0; i < results[k].byDistance.size(); ++i) {
        const std::string row = at + "/by_distance/" + std::to_string(i);
        json.set(row + "/distance", results[k].byDistance[i].first);
        setSummary(json, row, results[k].byDistance[i].second);
      }
    }
    std::printf("%s\n", json.dump().c_str());
    return;
  }
  std::printf("%-28s %5s %9s %7s %9s %9s %12s %11s\n", "render", "eyes", "mean dB", "SSIM",
              "worst dB", "flicker", "design eyes", "brightness");
  for (size_t k = 0; k < results.size(); ++k) {
    const QualitySummary& s = results[k].all;
    std::printf("%-28s %5d %9.2f %7.4f %9.2f %9.4f %12.2f %10.2fx\n", labels[k].c_str(), s.eyes,
                s.meanPsnr, s.meanSsim, s.worstPsnr, s.meanFlicker, results[k].designOnly.meanPsnr,
                brightness[k]);
  }
}

// `simulate --reference` without --eye or --sweep: the dense measure (docs/simulator.md), K eyes
// inside every view's window at several distances, and the design eyes as their own column.
void runDenseReference(const SimulateOptions& o, const Inputs& in, const SimulationOptions& sim) {
  const DisplayModel& display = *in.display;
  if (o.eyesPerView < 1 || o.eyesPerView > 64)
    throw InputError("command line", "--eyes-per-view",
                     "expected 1 to 64 eyes per view, got " + std::to_string(o.eyesPerView));
  const std::vector<double> distances = parseDistances(o.distances);
  const Scene scene = referenceScene(in, o);
  const Accelerator accelerator(scene);
  // --compare: more renders of the same scene for the same display, scored at the same eyes
  // against the same ideal views (rendered once).
  std::vector<std::string> labels{o.dir};
  std::vector<LayerSet> sets{{in.frames, in.normalisation}};
  for (const std::string& other : o.compare) {
    labels.push_back(other);
    sets.push_back(loadLayerSet(fs::path(other), display.hasMaskLayer()));
  }
  std::vector<std::unique_ptr<SimulatedDisplay>> simulators;
  std::vector<const SimulatedDisplay*> pointers;
  std::vector<double> normalisers;  // what each simulator divided its views by
  for (LayerSet& set : sets) {
    SimulationOptions options = sim;
    if (options.normalise) options.normalisation = set.normalisation;
    double maskMean = 0;
    for (const LayerImages& f : set.frames)
      for (const Vec3f& p : f.mask.pixels()) maskMean += (double(p.x) + p.y + p.z) / 3.0;
    const size_t maskPixels = set.frames.front().mask.pixels().size() * set.frames.size();
    maskMean = maskPixels > 0 ? maskMean / double(maskPixels) : 1.0;
    normalisers.push_back(!options.normalise          ? 1.0
                          : options.normalisation > 0 ? options.normalisation
                                                      : maskMean);
    simulators.push_back(simulateDisplay(display, std::move(set.frames), options));
    pointers.push_back(simulators.back().get());
  }
  std::vector<DenseEye> eyes = denseEyes(display, o.eyesPerView, distances);
  for (const DenseEye& eye : designEyes(display)) eyes.push_back(eye);
  std::vector<ViewerQuality> results;
  {
    ProgressBar bar("measure");
    results = measureViewerQuality(scene, accelerator, display, pointers, eyes,
                                   {o.referenceSpp, o.threads},
                                   [&bar](int done, int total) { bar.update(done, total); });
  }
  if (results.size() > 1) {
    std::vector<double> brightness;
    const double first = results[0].all.meanLuminance * normalisers[0];
    for (size_t k = 0; k < results.size(); ++k)
      brightness.push_back(first > 0 ? results[k].all.meanLuminance * normalisers[k] / first : 0);
    return printComparison(o, labels, results, brightness);
  }
  const ViewerQuality& result = results.front();
  if (o.json) {
    JsonWriter json;
    json.set("/display", display.source());
    json.set("/eyes_per_view", o.eyesPerView);
    for (size_t i = 0; i < result.eyes.size(); ++i) {
      const EyeQuality& q = result.eyes[i];
      const std::string at = "/eyes/" + std::to_string(i);
      const Vec3d& e = q.eye.position;
      json.set(at + "/eye", Vec3f{float(e.x), float(e.y), float(e.z)});
      json.set(at + "/distance", q.eye.distance);
      json.set(at + "/view", q.eye.view);
      json.set(at + "/design_eye", q.eye.designEye);
      json.set(at + "/psnr", q.psnr);
      json.set(at + "/ssim", q.ssim);
      json.set(at + "/flicker", q.flicker);
    }
    setSummary(json, "/mean", result.all);
    setSummary(json, "/design_eyes", result.designOnly);
    for (size_t i = 0; i < result.byDistance.size(); ++i) {
      json.set("/by_distance/" + std::to_string(i) + "/distance", result.byDistance[i].first);
      setSummary(json, "/by_distance/" + std::to_string(i), result.byDistance[i].second);
    }
    std::printf("%s\n", json.dump().c_str());
    return;
  }
  std::printf("%-22s %5s %9s %7s %4s %9s\n", "eye (mm)", "dist", "PSNR dB", "SSIM", "view",
              "flicker");
  for (const EyeQuality& q : result.eyes) {
    char eye[48];
    std::snprintf(eye, sizeof eye, "%.1f,%.1f,%.1f", q.eye.position.x, q.eye.position.y,
                  q.eye.position.z);
    std::printf("%-22s %5.2f %9.2f %7.4f %4d %9.4f%s\n", eye, q.eye.distance, q.psnr, q.ssim,
                q.eye.view, q.flicker, q.eye.designEye ? "  (design eye)" : "");
  }
  std::printf("\n%-22s %5s %9s %7s %9s %9s\n", "summary", "eyes", "mean dB", "SSIM", "worst dB",
              "flicker");
  for (const auto& [distance, summary] : result.byDistance) {
    char label[32];
    std::snprintf(label, sizeof label, "at %.2f D", distance);
    printSummaryRow(label, summary);
  }
  printSummaryRow("dense eyes", result.all);
  printSummaryRow("design eyes (biased)", result.designOnly);
}

// Before the simulator allocates: one eye's view and picture, each eye's encoded copy, beside
// two copies of the layers (the simulator's, a blurred rear layer); and the
// time of every sample (spp x pupil samples per output pixel, and the reference views').
void checkSimulationWork(const SimulateOptions& o, const DisplayModel& display,
                         const LayerImages& layers, const SimulationOptions& sim, size_t eyes) {
  const DisplayWindow window = display.window();
  if (o.diffuser > window.widthMm)
    throw InputError("--diffuser", "",
                     "a blur wider than the display (" + std::to_string(int(window.widthMm)) +
                         " mm) is no diffuser");
  double w = display.film().panelWidth, h = display.film().panelHeight;
  if (const DisplayDesign* d = display.barrierDesign()) {
    const Panel& front =
        d->spec.order == LayerOrder::BarrierBack ? d->spec.imagePanel : d->spec.maskPanel;
    w = sim.width > 0 ? sim.width : front.width;
    h = sim.height > 0 ? sim.height : front.height;
  }
  const double layerBytes = imageBytes(layers.image.width(), layers.image.height()) +
                            imageBytes(layers.mask.width(), layers.mask.height());
  // Eyes are seen one at a time: one view and its picture at once, and per eye only what is
  // kept (a sweep's PNG, at most about the 8-bit codes, and a small thumbnail).
  const double oneEye = imageBytes(w, h, 2 * kFloatRgbPixelBytes + kRgba8PixelBytes);
  const double perEye = imageBytes(w, h, kRgba8PixelBytes);
  const std::string subject = o.sweep > 0      ? "--sweep " + std::to_string(o.sweep)
                              : o.size.empty() ? "--eye"
                                               : "--size " + o.size;
  checkMemoryEstimate(2 * layerBytes + oneEye + double(eyes) * perEye, subject,
                      std::to_string(eyes) + " simulated views",
                      o.sweep > 0 ? "use fewer steps" : "use a smaller size or fewer eyes");
  checkPixelCount(w * h, subject);
  // The exact integral costs about as much as 3 x 3 point samples (the pieces between the two
  // layers' pixel edges: 2 to 3 along each axis).
  const double perPixel = o.spp > 0 ? o.spp : 9;
  const double samples = double(eyes) * w * h * perPixel * (o.pupil > 0 ? o.pupilSamples : 1);
  if (o.sweep > 0)
    checkTimeEstimate(samples, o.threads, "sweep", std::to_string(o.sweep),
                      "use fewer samples or eyes");
  else
    checkTimeEstimate(samples, o.threads, "spp", std::to_string(o.spp),
                      "use fewer samples or eyes");
  if (o.reference)
    checkTimeEstimate(double(eyes) * w * h * o.referenceSpp, o.threads, "reference_spp",
                      std::to_string(o.referenceSpp), "use fewer samples");
}

// Options that only the two-layer simulator has, refused for other kinds by name.
void checkKindOptions(const SimulateOptions& o, const DisplayModel& display) {
  if (display.barrierDesign()) return;
  const auto refuse = [](const char* option) {
    throw InputError("command line", option,
                     "applies to the two-layer (barrier) simulator; a lenticular panel is seen "
                     "through its lenses at the panel's resolution");
  };
  if (!o.size.empty()) refuse("--size");
  if (o.spp != 0) refuse("--spp");
  if (o.pupil > 0) refuse("--pupil");
  if (o.diffuser > 0) refuse("--diffuser");
  if (o.colourFilters) refuse("--color-filters");
  if (o.raw) refuse("--raw");
}

// The ideal view's PSNR and SSIM at one eye, and (two-layer displays) the brightness and
// cross-talk there.
Quality qualityAt(const SimulateOptions& o, const Inputs& in, const SimulationOptions& sim,
                  const Scene& scene, const Accelerator& accelerator,
                  const SimulatedDisplay& simulator, const Vec3d& eye, const Image& view,
                  const Image& picture) {
  const Image reference = idealView(scene, accelerator, *in.display, simulator, eye, view.width(),
                                    view.height(), o.referenceSpp, o.threads);
  Quality q;
  const Image seen = o.rawPixels ? simulator.atDisplayResolution(view) : picture;
  q.psnr = psnr(seen, reference);
  q.ssim = ssim(seen, reference);
  if (const DisplayDesign* d = in.barrier()) {
    // Brightness is the raw mean transmittance, whatever --raw says for the pictures; with
    // time-multiplexed frames, the mean over the frames' masks (the eye averages them).
    SimulationOptions raw = sim;
    raw.normalise = false;
    q.brightness = q.crosstalk = 0;
    for (const LayerImages& frame : in.frames) {
      const CrosstalkResult c = measureCrosstalk(*d, frame.mask, raw, eye);
      q.brightness += c.brightness / double(in.frames.size());
      q.crosstalk += c.crosstalk / double(in.frames.size());
      q.ownView = c.ownView;
    }
  } else {
    q.brightness = 1.0;  // a lens passes all its light (no barrier)
    q.crosstalk = std::numeric_limits<double>::quiet_NaN();
    q.ownView = -1;
  }
  return q;
}

void runSimulate(const SimulateOptions& o);

// simulate DIR --frames A:B|all: what one eye sees in each frame of a sequence that `render`
// wrote (DIR/frame-NNNN), as OUTPUT-NNNN.png, and with --video as one video.
void runSimulateFrames(const SimulateOptions& o) {
  if (o.sweep > 0)
    throw InputError("command line", "--frames",
                     "simulates one eye per frame: give --eye (or none: the zone's centre), not "
                     "--sweep");
  if (o.eyes.size() > 1)
    throw InputError("command line", "--frames", "simulates one eye per frame: one --eye");
  if (o.reference && o.eyes.empty())
    throw InputError("command line", "--frames",
                     "with --reference, give the eye (--eye): the dense measure is per frame");
  // The frames there are: frame-NNNN folders holding a finished render.
  int lastFound = 0;
  std::error_code ec;
  for (fs::directory_iterator it(o.dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind("frame-", 0) != 0 || name.size() > 15) continue;
    const std::string digits = name.substr(6);
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    if (fs::is_regular_file(it->path() / "render.json"))
      lastFound = std::max(lastFound, std::stoi(digits));
  }
  if (lastFound == 0)
    throw InputError(o.dir, "", "holds no rendered frames (frame-NNNN folders of render --frames)");
  int first = 1, last = lastFound;
  if (o.frames != "all") parseFrameRange(o.frames, lastFound, first, last);
  if (o.video.wanted()) checkVideoRequest(o.video);
  const std::string output = o.output.empty() ? "out/simulated.png" : o.output;
  std::vector<std::string> pictures;
  for (int frame = first; frame <= last; ++frame) {
    SimulateOptions one = o;
    one.frames.clear();
    one.video = {};
    one.dir = (fs::path(o.dir) / frameName(frame)).string();
    one.output = numberedPicture(output, frame);
    if (!fs::is_regular_file(fs::path(one.dir) / "render.json"))
      throw InputError(one.dir, "", "is missing: the sequence is not finished (render it again)");
    runSimulate(one);
    pictures.push_back(one.output);
  }
  if (o.video.wanted()) writeVideo(pictures, o.video, cliReporter());
}

void runSimulate(const SimulateOptions& o) {
  if (!o.frames.empty()) return runSimulateFrames(o);
  if (o.video.wanted()) {
    if (o.sweep == 0)
      throw InputError("command line", "--video",
                       "needs --sweep N or --frames: the video's frames are the sweep's pictures "
                       "or the sequence's");
    checkVideoRequest(o.video);
  }
  const Inputs in = loadInputs(o);
  const DisplayModel& display = *in.display;
  checkKindOptions(o, display);
  SimulationOptions sim;
  if (!o.size.empty()) parseSize("--size", o.size, sim.width, sim.height);
  sim.samplesPerPixel = o.spp;
  sim.pupilDiameterMm = o.pupil;
  sim.pupilSamples = o.pupilSamples;
  sim.diffuserSigmaMm = o.diffuser;
  sim.colourFilters = o.colourFilters;
  sim.normalise = !o.raw;
  sim.threads = o.threads;
  checkSimulationWork(o, display, in.layers, sim, eyePositions(o, display).size());
  if (o.reference && o.eyes.empty() && o.sweep == 0) return runDenseReference(o, in, sim);
  // --reference: the scene is read (and checked) before any picture is written.
  std::optional<Scene> scene;
  if (o.reference) scene = referenceScene(in, o);
  if (sim.normalise) sim.normalisation = in.normalisation;
  const std::unique_ptr<SimulatedDisplay> simulator = simulateDisplay(display, in.frames, sim);
  const std::vector<Vec3d> eyes = eyePositions(o, display);
  std::optional<Accelerator> accelerator;
  if (o.reference) accelerator.emplace(*scene);

  // One eye at a time: its view, the picture, the quality, then only the encoded picture (and a
  // sweep's thumbnail) is kept, so memory does not grow with the eyes.
  const fs::path sweepOut(o.output.empty() ? "out/sweep" : o.output);
  // The sweep's files share a prefix: a given extension is dropped (-o out/sweep.png).
  const std::string prefix = (sweepOut.parent_path() / sweepOut.stem()).string();
  const std::string path = o.output.empty() ? "out/simulated.png" : o.output;
  std::vector<std::string> written, labels, pngs;
  std::vector<Image> thumbnails;
  std::vector<Quality> quality;
  // --video: each sweep picture is encoded as it is made (the file is moved into place at the
  // end, with the sweep's other files).
  std::optional<VideoOutput> video;
  if (o.video.wanted()) video.emplace(o.video);
  std::string videoLine;
  for (size_t i = 0; i < eyes.size(); ++i) {
    const Image view = simulator->view(eyes[i]);
    // Pictures as perceived: a viewer at the design distance does not resolve single pixels
    // (0.27 mm at 600 mm is about 1.5 arc minutes), so each output pixel shows the light of one
    // screen period (one lens) around it; --raw-pixels keeps the eye's samples as they are.
    const Image picture = o.rawPixels ? view : simulator->atDisplayResolution(view);
    if (o.reference)
      quality.push_back(
          qualityAt(o, in, sim, *scene, *accelerator, *simulator, eyes[i], view, picture));
    if (o.sweep > 0) {
      labels.push_back(eyeLabel(eyes[i]));
      pngs.push_back(pngBytes(picture, false));
      // The contact sheet's thumbnail now, so the picture need not be kept.
      thumbnails.push_back(contactThumbnail(picture, std::min(480, picture.width())));
      if (video) video->add(picture);
    } else {
      writeImage(numbered(path, i, eyes.size()), picture);
      written.push_back(numbered(path, i, eyes.size()));
    }
  }
  if (o.sweep > 0) {
    writeImage(prefix + "-sheet.png",
               contactSheet(thumbnails, std::min<int>(int(thumbnails.size()), 3),
                            thumbnails.front().width(), labels));
    writeFileAtomically(prefix + "-anim.png", encodeApngFromPngs(pngs, 250));
    writeFileAtomically(prefix + ".html",
                        sliderPage("parallax: eye sweep across " + display.source(), pngs, labels));
    written = {prefix + "-sheet.png", prefix + "-anim.png", prefix + ".html"};
    if (video) {
      videoLine = video->finish();
      written.push_back(o.video.file);
    }
  }

  if (o.json) {
    JsonWriter json;
    json.set("/display", display.source());
    json.set("/display_kind", displayKindName(display.kind()));
    for (size_t i = 0; i < written.size(); ++i)
      json.set("/outputs/" + std::to_string(i), written[i]);
    if (video) {
      const VideoWriter& v = video->writer();
      json.set("/video/file", v.path());
      json.set("/video/frames", v.frames());
      json.set("/video/codec", v.codec());
      json.set("/video/coded_width", v.codedWidth());
      json.set("/video/coded_height", v.codedHeight());
    }
    Quality mean;
    for (size_t i = 0; i < eyes.size(); ++i) {
      const std::string at = "/eyes/" + std::to_string(i);
      json.set(at + "/eye", Vec3f{float(eyes[i].x), float(eyes[i].y), float(eyes[i].z)});
      if (quality.empty()) continue;
      const Quality& q = quality[i];
      json.set(at + "/psnr", q.psnr);
      json.set(at + "/ssim", q.ssim);
      json.set(at + "/brightness", q.brightness);
      json.set(at + "/crosstalk", q.crosstalk);
      json.set(at + "/own_view", q.ownView);
      mean.psnr += q.psnr / double(eyes.size());
      mean.ssim += q.ssim / double(eyes.size());
      mean.brightness += q.brightness / double(eyes.size());
      mean.crosstalk += q.crosstalk / double(eyes.size());
    }
    if (!quality.empty()) {
      json.set("/mean/psnr", mean.psnr);
      json.set("/mean/ssim", mean.ssim);
      json.set("/mean/brightness", mean.brightness);
      json.set("/mean/crosstalk", mean.crosstalk);
    }
    std::printf("%s\n", json.dump().c_str());
    return;
  }
  for (const std::string& file : written)
    if (!video || file != o.video.file) std::printf("wrote %s\n", file.c_str());
  if (video) std::printf("%s\n", videoLine.c_str());
  if (quality.empty()) return;
  std::printf("%-24s %8s %7s %10s %9s %4s\n", "eye (mm)", "PSNR dB", "SSIM", "brightness",
              "crosstalk", "view");
  for (size_t i = 0; i < eyes.size(); ++i) {
    char eye[48];
    std::snprintf(eye, sizeof eye, "%.1f,%.1f,%.1f", eyes[i].x, eyes[i].y, eyes[i].z);
    const Quality& q = quality[i];
    std::printf("%-24s %8.2f %7.4f %10.4f %9.4f %4d\n", eye, q.psnr, q.ssim, q.brightness,
                q.crosstalk, q.ownView);
  }
}

}  // namespace

void registerSimulateCommand(CLI::App& cli) {
  auto o = std::make_shared<SimulateOptions>();
  CLI::App* cmd = cli.add_subcommand(
      "simulate", "See the display without hardware: what an eye in front of it sees");
  cmd->add_option("dir", o->dir,
                  "Output folder of `parallax render` (image.png, mask.png, "
                  "display.json, render.json)")
      ->capture_default_str();
  cmd->add_option("--image", o->image, "Image layer (instead of DIR/image.png)");
  cmd->add_option("--mask", o->mask, "Mask layer (instead of DIR/mask.png)");
  cmd->add_option("--display", o->display,
                  "Display file of any kind, or lkg:NAME (instead of DIR/display.json or "
                  "DIR/visual.json)");
  cmd->add_option("--frames", o->frames,
                  "DIR is a sequence of render --frames: what the eye sees in frames FIRST:LAST "
                  "(or all), as OUTPUT-NNNN.png (and --video)")
      ->type_name("FIRST:LAST|all");
  cmd->add_option("--eye", o->eyes,
                  "Eye position X,Y,Z in display mm (origin: front layer centre, z toward the "
                  "viewer); repeatable. Default: the view-zone centre");
  cmd->add_option("-o,--output", o->output,
                  "Output image (several eyes: FILE-K), or the prefix of the sweep's files");
  cmd->add_option("--size", o->size, "Output size WIDTHxHEIGHT (default: the front layer's)");
  cmd->add_option("--spp", o->spp,
                  "0: integrate each output pixel's area exactly (the default); n*n: point "
                  "samples per output pixel instead (1: the centre, which aliases against the "
                  "mask between design eyes)")
      ->capture_default_str()
      ->check(squareCount(true));
  cmd->add_option("--pupil", o->pupil, "Pupil diameter in mm, 0 (a pinhole eye) to 100")
      ->check(realIn(0, 100));
  cmd->add_option("--pupil-samples", o->pupilSamples, "Points averaged over the pupil")
      ->capture_default_str()
      ->check(integerIn(1, INT_MAX));
  cmd->add_option("--diffuser", o->diffuser,
                  "Blur of the rear layer by a diffuser foil, Gaussian sigma in mm (0 to the "
                  "display's width)")
      ->check(realIn(0, kInfinity));
  cmd->add_flag("--color-filters", o->colourFilters,
                "Model the R, G, B colour-filter stripes of both layers (rainbow fringes)");
  cmd->add_flag("--raw", o->raw, "Raw brightness (default: normalised by the aperture ratio)");
  cmd->add_flag("--raw-pixels", o->rawPixels,
                "Write the pinhole eye's samples unfiltered (default: integrated over one "
                "screen period, as a viewer at the design distance perceives them)");
  cmd->add_option("--sweep", o->sweep,
                  "Move the eye across the view zone in N steps: contact sheet, APNG, HTML")
      ->check(integerIn(0, INT_MAX));
  cmd->add_option("--sweep-range", o->sweepRange,
                  "Sweep width in view-zone widths, above 0 and at most 10 (> 1 goes beyond the "
                  "zone)")
      ->capture_default_str()
      ->check(realIn(0, 10, Bound::Open));
  cmd->add_option("--sweep-distance", o->sweepDistance,
                  "Eye distance of the sweep in mm, above 0 and at most 100 D (default D)")
      ->check(realIn(0, kInfinity, Bound::Open));
  cmd->add_flag("--reference", o->reference,
                "Quality figures against the ideal view: PSNR, SSIM, brightness, cross-talk at "
                "the --eye positions; without --eye, the dense measure over the view zone "
                "(--eyes-per-view, --distances): mean, worst eye, flicker");
  cmd->add_option("--scene", o->scene, "Scene for --reference (default: from render.json)");
  cmd->add_option("--reference-spp", o->referenceSpp, "Samples per pixel of the ideal view")
      ->capture_default_str()
      ->check(integerIn(1, INT_MAX));
  cmd->add_option("--eyes-per-view", o->eyesPerView,
                  "With --reference and no --eye: eyes evenly inside every view's window "
                  "(the dense measure)")
      ->capture_default_str();
  cmd->add_option("--compare", o->compare,
                  "With the dense measure: another render folder of the same scene and display, "
                  "scored at the same eyes against the same ideal views; repeatable")
      ->type_name("DIR");
  cmd->add_option("--distances", o->distances,
                  "With --reference and no --eye: eye distances of the dense measure, in units "
                  "of the design distance D")
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "Worker threads (0: all cores)")->check(threadCount());
  // As many frames a second as the sweep's APNG (250 ms a frame).
  o->video.fps = 4;
  addVideoOptions(*cmd, o->video, "the sweep's pictures (with --sweep)");
  addLimitOptions(*cmd);
  cmd->add_flag("--json", o->json, "Print one JSON object");
  cmd->callback([o] { runSimulate(*o); });
}

}  // namespace parallax::app
