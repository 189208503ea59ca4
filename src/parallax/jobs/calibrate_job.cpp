// The calibration runners: the barrier display, the settings checked under their own names,
// then the patterns (drawn one at a time), the prediction, or the applied display file.
#include "parallax/jobs/calibrate_job.h"

#include <cstdio>
#include <filesystem>

#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/core/output_path.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/layer_output.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/requests.h"

namespace parallax::jobs {

namespace {

// The library names a calibration setting by its field (sim/calibration.h,
// kCalibrationSettings), as the request does: the refusal names the field, and the other
// fields its message mentions become {field}s for the front end to spell.
template <class Call>
auto withFieldNames(Call call) {
  try {
    return call();
  } catch (const InputError& e) {
    if (e.file() != kCalibrationSettings || dynamic_cast<const RequestError*>(&e)) throw;
    static const char* const kFields[] = {
        "screen_period_px", "slit_period_px", "from_px",  "to_px",      "period_steps",
        "phase_step_px",    "duty",           "phase_px", "label_scale"};
    // what() is "file: path: message".
    const std::string message = std::string(e.what()).substr(e.file().size() + e.path().size() + 4);
    std::string marked;
    for (size_t at = 0; at < message.size();) {
      size_t end = at;
      while (end < message.size() &&
             (std::islower(static_cast<unsigned char>(message[end])) || message[end] == '_'))
        ++end;
      if (end == at) {
        marked += message[at++];
        continue;
      }
      const std::string word = message.substr(at, end - at);
      bool field = false;
      for (const char* name : kFields) field = field || word == name;
      marked += field ? "{" + word + "}" : word;
      at = end;
    }
    throw RequestError(e.path().substr(1), marked);
  }
}

// A barrier display as its file describes it ("" the built-in), designed: the display itself
// must be possible. A display already loaded must be a barrier.
DisplayDesign barrierDisplay(const DisplayRequest& request) {
  const std::string& path = request.path;
  const std::optional<DisplayDescription>& loaded = request.loaded;
  // Any kind is read (lkg:NAME too), so that a lenticular panel is told what it can use.
  const DisplayDescription display =
      loaded ? *loaded : (path.empty() ? DisplayDescription{} : loadDisplayDescription(path));
  if (display.kind != DisplayKind::Barrier)
    throw InputError(display.source(), "",
                     "is a lenticular display: the paper's slit patterns are for barrier "
                     "displays; `calibrate patterns --photo` makes its photo shots");
  if (path.empty() && !loaded) return designDisplay(defaultDisplaySpec());
  return designDisplay(display.barrier, display.camera);
}

const char* orderName(LayerOrder order) {
  return order == LayerOrder::BarrierBack ? "barrier-back" : "barrier-front";
}

}  // namespace

// ---- patterns --------------------------------------------------------------------------------

CalibrationPatternSet calibrationPatterns(const CalibrationPatternsRequest& r, Reporter&,
                                          bool inMemory) {
  CalibrationPatternSet set;
  set.display = barrierDisplay(r.display).spec;
  const DisplaySpec& display = set.display;
  const Panel &image = display.imagePanel, &mask = display.maskPanel;
  if (r.settings.labelScale > mask.height)
    throw RequestError(
        "label_scale",
        "is more than the panel's height of " + std::to_string(mask.height) + " pixels",
        std::to_string(r.settings.labelScale));
  // One pattern at a time: its picture and the writer's 8-bit copy; every pixel of every
  // pattern drawn (a few more than the steps: the phase sweep and the tests).
  const double pixels = double(mask.width) * mask.height;
  const std::string subject = r.display.loaded ? display.source : r.display.named();
  checkMemoryEstimate(pixels * (kFloatRgbPixelBytes + kRgba8PixelBytes), subject, "one pattern",
                      "use a smaller display");
  checkTimeEstimate(pixels * (double(r.settings.periodSteps) + 8), 0, "period_steps",
                    std::to_string(r.settings.periodSteps), "use fewer steps");
  set.patterns = withFieldNames([&] { return calibrationPatternSet(display, r.settings); });
  if (inMemory)
    checkMemoryEstimate(pixels * kFloatRgbPixelBytes * double(set.patterns.size()), subject,
                        "all " + std::to_string(set.patterns.size()) + " patterns",
                        "use fewer steps, or write them to files");

  JsonWriter index;
  index.set("/display", display.source);
  index.set("/layer_order", orderName(display.order));
  index.set("/gap_mm", display.gapMm);
  index.set("/image_resolution/0", image.width);
  index.set("/image_resolution/1", image.height);
  index.set("/mask_resolution/0", mask.width);
  index.set("/mask_resolution/1", mask.height);
  set.readme =
      "Calibration patterns (parallax calibrate patterns) for " + display.source + ", " +
      orderName(display.order) + ".\n" +
      "Show image-slits.png on the image layer and one mask-*.png at a time on the mask layer;\n"
      "the steps are in docs/calibration.md. D is what each slit period implies at g = " +
      printed("%g", display.gapMm) + " mm (G1).\n\n" +
      "file                    layer  Tx  Tv (mask px)  phase (px)  D (mm)   purpose\n";
  for (size_t i = 0; i < set.patterns.size(); ++i) {
    const PatternDescription& p = set.patterns[i];
    const double distance =
        designDisplay(measuredDisplaySpec(display, p.screenPeriodPx, p.slitPeriodPx, p.phasePx))
            .viewDistanceMm;
    set.viewDistancesMm.push_back(distance);
    const std::string at = "/patterns/" + std::to_string(i);
    index.set(at + "/file", p.file);
    index.set(at + "/layer", p.maskLayer ? "mask" : "image");
    index.set(at + "/purpose", p.purpose);
    index.set(at + "/label", p.label);
    index.set(at + "/screen_period_px", p.screenPeriodPx);
    index.set(at + "/slit_period_px", p.slitPeriodPx);
    index.set(at + "/phase_px", p.phasePx);
    index.set(at + "/view_distance_mm", distance);
    set.readme += printed("%-23s %-6s %3d  %12.4f  %10.2f  %7.1f  %s\n", p.file.c_str(),
                          p.maskLayer ? "mask" : "image", p.screenPeriodPx, p.slitPeriodPx,
                          p.phasePx, distance, p.purpose.c_str());
  }
  set.index = index.dump() + "\n";
  return set;
}

void runCalibrationPatterns(const CalibrationPatternsRequest& r, Reporter& reporter) {
  // Everything is checked here, before the first file is written.
  const CalibrationPatternSet set = calibrationPatterns(r, reporter);
  std::vector<std::string> names;
  for (const auto& pattern : set.patterns) names.push_back(pattern.file);
  names.insert(names.end(), {"index.json", "README.txt"});
  OutputSet::check(r.output, names);
  OutputSet out(r.output);
  for (size_t i = 0; i < set.patterns.size(); ++i)
    writeImage(out.path(set.patterns[i].file), set.draw(i));
  writeFileAtomically(out.path("index.json"), set.index);
  writeFileAtomically(out.path("README.txt"), set.readme);
  out.commit();
  reporter.result(printed("wrote %zu patterns, index.json and README.txt to %s",
                          set.patterns.size(), out.dir().c_str()));
}

// ---- predict ---------------------------------------------------------------------------------

void runCalibrationPredict(const CalibrationPredictRequest& r, Reporter& reporter) {
  const DisplayDesign design =
      r.display.loaded ? barrierDisplay(r.display) : loadBarrierDesign(r.display.path, reporter);
  const DisplaySpec& spec = design.spec;
  Vec3d eye{spec.viewZoneCenterXMm, spec.viewZoneHeightMm, design.viewDistanceMm};
  if (r.eye) {
    if (!(r.eye->z > 0)) throw RequestError("eye", "the eye must be in front (z > 0)");
    eye = *r.eye;
  }
  // Each candidate period simulates every front pixel `samples` times.
  checkTimeEstimate(
      double(r.settings.samplesPerPixel) * spec.imagePanel.width * spec.imagePanel.height, 0,
      "samples", std::to_string(r.settings.samplesPerPixel), "use fewer samples");
  const CalibrationPrediction p =
      withFieldNames([&] { return predictCalibration(spec, design, eye, r.settings); });
  const double distance = p.distanceOverGap * design.gapMm;
  if (r.json) {
    JsonWriter json;
    json.set("/display", spec.source);
    json.set("/eye", Vec3f{float(eye.x), float(eye.y), float(eye.z)});
    json.set("/screen_period_px", p.screenPeriodPx);
    json.set("/slit_period_px", p.slitPeriodPx);
    json.set("/phase_px", p.phasePx);
    json.set("/distance_over_gap", p.distanceOverGap);
    json.set("/gap_mm", design.gapMm);
    json.set("/view_distance_mm", distance);
    json.set("/score", p.score.score);
    json.set("/contrast", p.score.contrast);
    json.set("/uniformity", p.score.uniformity);
    json.set("/search/from_px", p.fromPx);
    json.set("/search/to_px", p.toPx);
    json.set("/search/step_px", p.stepPx);
    json.set("/search/at_range_edge", p.atRangeEdge);
    reporter.result(json.dump());
    return;
  }
  reporter.result(
      printed("display              %s (%s)", spec.source.c_str(), orderName(spec.order)));
  reporter.result(printed("eye                  %g, %g, %g mm", eye.x, eye.y, eye.z));
  reporter.result(printed("screen period Tx     %d px", p.screenPeriodPx));
  reporter.result(
      printed("slit period Tv       %.5f mask px (searched %.4f .. %.4f, finest step %.5f)",
              p.slitPeriodPx, p.fromPx, p.toPx, p.stepPx));
  reporter.result(printed("phase                %.3f mask px", p.phasePx));
  reporter.result(printed("D/g (G1)             %.2f: D = %.1f mm at the display's gap of %g mm",
                          p.distanceOverGap, distance, design.gapMm));
  reporter.result(printed("contrast             %.3f (Michelson, against one view to each side)",
                          p.score.contrast));
  reporter.result(
      printed("uniformity           %.3f (1 - std/mean across the view)", p.score.uniformity));
  if (p.atRangeEdge)
    reporter.result(
        "note                 the best period is at the edge of the searched range; "
        "widen it with {from_px}/{to_px}");
}

// ---- apply -----------------------------------------------------------------------------------

DisplayDesign appliedCalibration(const CalibrationApplyRequest& r, Reporter&) {
  const DisplayDesign file = barrierDisplay(r.display);
  DisplaySpec base = file.spec;
  // What is wrong from here on came from the request (core/error.h, errorText).
  base.source = RequestError::kRequestSource;
  if (r.gapMm) base.gapMm = *r.gapMm;
  // The phase measured from the view-zone centre is the panels' sideways misalignment: it
  // moves the drawn mask (panel_offset_px), not the apertures the rays are traced through.
  try {
    DisplaySpec spec =
        measuredDisplaySpec(base, r.screenPeriodPx, r.slitPeriodPx, base.mask.phasePx);
    if (r.phasePx) spec.mask.panelOffsetPx = *r.phasePx;
    return designDisplay(spec, file.camera);
  } catch (const InputError& e) {
    // The keys of the display this request made that are the request's own fields: the
    // refusal names the option (--slit-period), not the file key (/slit_period_px).
    static const std::pair<const char*, const char*> kFields[] = {
        {"/screen_period_px", "screen_period"},
        {"/slit_period_px", "slit_period"},
        {"/gap_mm", "gap"},
        {"/mask/panel_offset_px", "phase"}};
    const std::string prefix = e.file() + ": " + e.path() + ": ";
    const std::string text = e.what();
    if (e.file() != RequestError::kRequestSource || dynamic_cast<const RequestError*>(&e) ||
        text.rfind(prefix, 0) != 0)
      throw;
    for (const auto& [key, field] : kFields)
      if (e.path() == key) throw RequestError(field, text.substr(prefix.size()));
    throw;
  }
}

void runCalibrationApply(const CalibrationApplyRequest& r, Reporter& reporter) {
  const DisplayDesign d = appliedCalibration(r, reporter);
  const DisplaySpec& spec = d.spec;
  checkOutputFile(r.output);
  writeFileAtomically(r.output, displayFileText(spec, d.camera));
  reporter.result("wrote " + r.output);
  reporter.result(printed(
      "Tx %g px, Tv %g mask px, panel offset %g px, g %g mm: D = %.1f mm (G1), S = %.1f mm, "
      "%.4g views",
      d.screenPeriodPx, d.slitPeriodPx, spec.mask.panelOffsetPx, d.gapMm, d.viewDistanceMm,
      d.viewZoneWidthMm, d.views));
}

}  // namespace parallax::jobs
