// The dense quality measure of `simulate` (reference without eyes or a sweep; docs/simulator.md):
// K eyes inside every view's window at several distances against the ideal views, the design
// eyes as their own column, and other renders of the same scene side by side (compare).
#include <algorithm>
#include <cstdlib>
#include <memory>
#include <optional>

#include "parallax/accel/accelerator.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/io/json_writer.h"
#include "parallax/jobs/lens_readings.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/simulate_parts.h"
#include "parallax/quality/viewer_quality.h"
#include "parallax/sim/simulated_display.h"

namespace parallax::jobs {

namespace {

std::string summaryRow(const char* label, const QualitySummary& s) {
  return printed("%-22s %5d %9.2f %7.4f %9.2f %9.4f", label, s.eyes, s.meanPsnr, s.meanSsim,
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

// The summaries by distance under `at` (/by_distance/K).
void setByDistance(JsonWriter& json, const std::string& at, const ViewerQuality& result) {
  for (size_t i = 0; i < result.byDistance.size(); ++i) {
    const std::string row = at + "/by_distance/" + std::to_string(i);
    json.set(row + "/distance", result.byDistance[i].first);
    setSummary(json, row, result.byDistance[i].second);
  }
}

// Several renders side by side: one row (one JSON entry) each. `brightness[k]`: what render k's
// views send to the eye (their mean luminance times the normalisation the simulator divided
// by), over the first render's.
void reportComparison(const SimulateRequest& r, const std::vector<std::string>& labels,
                      const std::vector<ViewerQuality>& results,
                      const std::vector<double>& brightness, Reporter& reporter) {
  if (r.json) {
    JsonWriter json;
    json.set("/eyes_per_view", r.eyesPerView);
    for (size_t k = 0; k < results.size(); ++k) {
      const std::string at = "/renders/" + std::to_string(k);
      json.set(at + "/dir", labels[k]);
      setSummary(json, at + "/mean", results[k].all);
      setSummary(json, at + "/design_eyes", results[k].designOnly);
      json.set(at + "/brightness_vs_first", brightness[k]);
      setByDistance(json, at, results[k]);
    }
    return reporter.result(json.dump());
  }
  reporter.result(printed("%-48s %5s %9s %7s %9s %9s %12s %11s", "render", "eyes", "mean dB",
                          "SSIM", "worst dB", "flicker", "design eyes", "brightness"));
  for (size_t k = 0; k < results.size(); ++k) {
    const QualitySummary& s = results[k].all;
    reporter.result(printed("%-48s %5d %9.2f %7.4f %9.2f %9.4f %12.2f %10.2fx", labels[k].c_str(),
                            s.eyes, s.meanPsnr, s.meanSsim, s.worstPsnr, s.meanFlicker,
                            results[k].designOnly.meanPsnr, brightness[k]));
  }
}

// One render's measure: every eye, then the summaries.
void reportMeasure(const SimulateRequest& r, const DisplayModel& display,
                   const ViewerQuality& result, Reporter& reporter) {
  // Listed by place: nearest distance first, then left to right, the design eyes among the
  // others where they stand (they are measured last, after the rows that flicker is taken along).
  std::vector<const EyeQuality*> byPlace;
  for (const EyeQuality& q : result.eyes) byPlace.push_back(&q);
  std::stable_sort(byPlace.begin(), byPlace.end(), [](const EyeQuality* a, const EyeQuality* b) {
    return std::pair(a->eye.position.z, a->eye.position.x) <
           std::pair(b->eye.position.z, b->eye.position.x);
  });
  if (r.json) {
    JsonWriter json;
    json.set("/display", display.source());
    json.set("/eyes_per_view", r.eyesPerView);
    for (size_t i = 0; i < byPlace.size(); ++i) {
      const EyeQuality& q = *byPlace[i];
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
    setByDistance(json, "", result);
    return reporter.result(json.dump());
  }
  reporter.result(printed("%-22s %5s %9s %7s %4s %9s", "eye (mm)", "dist", "PSNR dB", "SSIM",
                          "view", "flicker"));
  for (const EyeQuality* eyeQuality : byPlace) {
    const EyeQuality& q = *eyeQuality;
    const std::string eye =
        printed("%.1f,%.1f,%.1f", q.eye.position.x, q.eye.position.y, q.eye.position.z);
    reporter.result(printed("%-22s %5.2f %9.2f %7.4f %4d %9.4f%s", eye.c_str(), q.eye.distance,
                            q.psnr, q.ssim, q.eye.view, q.flicker,
                            q.eye.designEye ? "  (design eye)" : ""));
  }
  reporter.result(printed("\n%-22s %5s %9s %7s %9s %9s", "summary", "eyes", "mean dB", "SSIM",
                          "worst dB", "flicker"));
  for (const auto& [distance, summary] : result.byDistance)
    reporter.result(summaryRow(printed("at %.2f D", distance).c_str(), summary));
  reporter.result(summaryRow("dense eyes", result.all));
  reporter.result(summaryRow("design eyes (biased)", result.designOnly));
}

}  // namespace

namespace {

// The dense measure's estimate, its scene loaded: the BVH; the layers of every set (the first
// one's copied again, each --compare's read) held by its simulator; per eye the ideal view, its
// sRGB encoding and the one before it (flicker), the next eye's ideal view and encoding made
// while this eye is compared (measured: one picture more at the peak), per set the eye's
// picture, its encoding and the one before, and the ideal render's temporaries (measured: one and a
// half pictures; SSIM works in bands of rows).
void checkDenseMemory(const SimulateInputs& in, const SimulateRequest& r, const Scene& scene) {
  double frames = 0;
  for (const LayerImages& f : in.frames)
    frames +=
        imageBytes(f.image.width(), f.image.height()) + imageBytes(f.mask.width(), f.mask.height());
  // Each reading of --all-readings is one more simulator holding its copy of the layers.
  const double readings = r.allReadings && !lensReadings(*in.display).empty()
                              ? double(lensReadings(*in.display).size())
                              : 1.0;
  const double sets = (1.0 + double(r.compare.size())) * readings;
  const auto [w, h] = seenPictureSize(*in.display, r.simulator);
  checkPeakMemory(acceleratorBytes(scene) + sets * frames +
                      imageBytes(w, h, kFloatRgbPixelBytes, 4.0 + 3.0 * sets + 1.5),
                  "{reference}",
                  "the dense measure's views and " + std::to_string(int(sets)) + " layer sets",
                  "use a smaller size or fewer {compare}");
}

}  // namespace

void runDenseReference(const SimulateRequest& r, const SimulateInputs& in,
                       const SimulationOptions& sim, Reporter& reporter) {
  const DisplayModel& display = *in.display;
  if (r.eyesPerView < 1 || r.eyesPerView > 64)
    throw RequestError("eyes_per_view",
                       "expected 1 to 64 eyes per view, got " + std::to_string(r.eyesPerView));
  const std::vector<double> distances = parseDistances(r.distances, "distances");
  const RenderedReference rendered = renderedScene(in, r);
  const Scene& scene = rendered.scene;
  checkDenseMemory(in, r, scene);
  const Accelerator accelerator(scene);
  // compare: more renders of the same scene for the same display, scored at the same eyes
  // against the same ideal views (rendered once).
  std::vector<std::string> labels{r.dir};
  std::vector<LayerSet> sets{{in.frames, in.normalisation}};
  const Image& firstImage = in.frames.front().image;
  for (const std::string& other : r.compare) {
    labels.push_back(other);
    sets.push_back(loadLayerSet(other, display.hasMaskLayer()));
    // Named here, as the compared folder's: the display is the first folder's, so its check
    // would blame that folder for this one's size.
    const Image& image = sets.back().frames.front().image;
    if (image.width() != firstImage.width() || image.height() != firstImage.height())
      throw RequestError("compare",
                         "its image layer is " + std::to_string(image.width()) + "x" +
                             std::to_string(image.height()) + " pixels, " + r.dir + "'s is " +
                             std::to_string(firstImage.width()) + "x" +
                             std::to_string(firstImage.height()) +
                             ": compare renders made for the same display",
                         other);
  }
  // all_readings: each render under each reading of the lens optics, as more rows.
  std::vector<std::pair<std::string, std::optional<LensOptics>>> readings{{"", sim.lensOptics}};
  if (r.allReadings) {
    readings.clear();
    for (const auto& [label, optics] : lensReadings(display))
      readings.push_back({" [" + label + "]", optics});
  }
  std::vector<std::string> rowLabels;
  std::vector<std::unique_ptr<SimulatedDisplay>> simulators;
  std::vector<const SimulatedDisplay*> pointers;
  std::vector<double> normalisers;  // what each simulator divided its views by
  for (size_t k = 0; k < sets.size(); ++k) {
    LayerSet& set = sets[k];
    SimulationOptions options = sim;
    if (options.normalise) options.normalisation = set.normalisation;
    double maskMean = 0;
    for (const LayerImages& f : set.frames)
      for (const Vec3f& p : f.mask.pixels()) maskMean += (double(p.x) + p.y + p.z) / 3.0;
    const size_t maskPixels = set.frames.front().mask.pixels().size() * set.frames.size();
    maskMean = maskPixels > 0 ? maskMean / double(maskPixels) : 1.0;
    for (size_t i = 0; i < readings.size(); ++i) {
      options.lensOptics = readings[i].second;
      normalisers.push_back(!options.normalise          ? 1.0
                            : options.normalisation > 0 ? options.normalisation
                                                        : maskMean);
      // The last reading takes the layers, the others a copy.
      simulators.push_back(simulateDisplay(
          display,
          i + 1 < readings.size() ? std::vector<LayerImages>(set.frames) : std::move(set.frames),
          options));
      pointers.push_back(simulators.back().get());
      rowLabels.push_back(labels[k] + readings[i].first);
    }
  }
  std::vector<DenseEye> eyes = denseEyes(display, r.eyesPerView, distances);
  for (const DenseEye& eye : designEyes(display)) eyes.push_back(eye);
  std::vector<ViewerQuality> results;
  {
    // Every eye makes and drops pictures of the same few sizes: kept, they are not handed out
    // again zeroed page by page (a tenth of the measure's time before).
    const KeepFreedBlocks keepFreedBlocks;
    const std::unique_ptr<Progress> progress = reporter.progress("measure");
    results = measureViewerQuality(scene, accelerator, *rendered.display, pointers, eyes,
                                   {r.referenceSpp, r.simulator.threads}, progress->callback());
  }
  if (results.size() > 1) {
    std::vector<double> brightness;
    const double first = results[0].all.meanLuminance * normalisers[0];
    for (size_t k = 0; k < results.size(); ++k)
      brightness.push_back(first > 0 ? results[k].all.meanLuminance * normalisers[k] / first : 0);
    return reportComparison(r, rowLabels, results, brightness, reporter);
  }
  reportMeasure(r, display, results.front(), reporter);
}

}  // namespace parallax::jobs
