// `parallax calibrate`: the paper's calibration of a real display (section 3.1,
// docs/calibration.md). `patterns` writes slit patterns to show on the panels, `predict` asks
// the simulator which periods and phase should look right, `apply` turns measured periods
// into a display file.
#include <CLI/CLI.hpp>

#include <climits>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/io/display_file.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/jobs/layer_output.h"
#include "parallax/sim/calibration.h"

namespace parallax::app {

namespace {

// The library names a calibration setting by its field; the user knows the option.
template <class Call>
auto withOptionNames(Call call) {
  try {
    return call();
  } catch (const InputError& e) {
    if (e.file() != kCalibrationSettings) throw;
    static const std::pair<const char*, const char*> kOptions[] = {
        {"/screen_period_px", "--screen-period"},
        {"/slit_period_px", "--slit-period"},
        {"/from_px", "--from"},
        {"/to_px", "--to"},
        {"/period_steps", "--steps"},
        {"/phase_step_px", "--phase-step"},
        {"/duty", "--duty"},
        {"/phase_px", "--phase"},
        {"/label_scale", "--label-scale"}};
    std::string option = e.path();
    for (const auto& [field, name] : kOptions)
      if (e.path() == field) option = name;
    // what() is "file: path: message".
    std::string message = std::string(e.what()).substr(e.file().size() + e.path().size() + 4);
    for (const auto& [field, name] : kOptions) {
      const std::string bare = std::string(field).substr(1);
      for (size_t at = message.find(bare); at != std::string::npos; at = message.find(bare))
        message.replace(at, bare.size(), name);
    }
    throw InputError("command line", option, message);
  }
}

namespace fs = std::filesystem;

BarrierDisplayFile loadSpecOrDefault(const std::string& path) {
  BarrierDisplayFile file =
      path.empty() ? BarrierDisplayFile{defaultDisplaySpec(), {}} : loadDisplayFile(path);
  designDisplay(file.spec, file.camera);  // the display itself must be possible
  return file;
}

const char* orderName(LayerOrder order) {
  return order == LayerOrder::BarrierBack ? "barrier-back" : "barrier-front";
}

std::string text(const char* format, double a, double b = 0, double c = 0) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, format, a, b, c);
  return buffer;
}

// ---- patterns ----------------------------------------------------------------------------

struct PatternsOptions {
  std::string display, output = "calibration";
  PatternSettings settings;
};

void runPatterns(const PatternsOptions& o) {
  const DisplaySpec display = loadSpecOrDefault(o.display).spec;
  const Panel& maskPanel = display.maskPanel;
  if (o.settings.labelScale > maskPanel.height)
    throw InputError(
        "--label-scale " + std::to_string(o.settings.labelScale), "",
        "is more than the panel's height of " + std::to_string(maskPanel.height) + " pixels");
  // One pattern at a time: its picture and the writer's 8-bit copy; every pixel of every
  // pattern drawn (a few more than the steps: the phase sweep and the tests).
  const double pixels = double(maskPanel.width) * maskPanel.height;
  checkMemoryEstimate(pixels * (kFloatRgbPixelBytes + kRgba8PixelBytes),
                      o.display.empty() ? "<built-in display>" : o.display, "one pattern",
                      "use a smaller display");
  checkTimeEstimate(pixels * (double(o.settings.periodSteps) + 8), 0, "steps",
                    std::to_string(o.settings.periodSteps), "use fewer steps");
  // Everything is checked here, before the first file is written.
  const std::vector<PatternDescription> set =
      withOptionNames([&] { return calibrationPatternSet(display, o.settings); });
  OutputSet out(o.output);
  const fs::path dir(out.path(""));
  const Panel &image = display.imagePanel, &mask = display.maskPanel;
  JsonWriter index;
  index.set("/display", display.source);
  index.set("/layer_order", orderName(display.order));
  index.set("/gap_mm", display.gapMm);
  index.set("/image_resolution/0", image.width);
  index.set("/image_resolution/1", image.height);
  index.set("/mask_resolution/0", mask.width);
  index.set("/mask_resolution/1", mask.height);
  std::string readme =
      "Calibration patterns (parallax calibrate patterns) for " + display.source + ", " +
      orderName(display.order) + ".\n" +
      "Show image-slits.png on the image layer and one mask-*.png at a time on the mask layer;\n"
      "the steps are in docs/calibration.md. D is what each slit period implies at g = " +
      text("%g", display.gapMm) + " mm (G1).\n\n" +
      "file                    layer  Tx  Tv (mask px)  phase (px)  D (mm)   purpose\n";
  for (size_t i = 0; i < set.size(); ++i) {
    const PatternDescription& p = set[i];
    writeImage((dir / p.file).string(), drawPattern(display, p));
    const double distance =
        designDisplay(measuredDisplaySpec(display, p.screenPeriodPx, p.slitPeriodPx, p.phasePx))
            .viewDistanceMm;
    const std::string at = "/patterns/" + std::to_string(i);
    index.set(at + "/file", p.file);
    index.set(at + "/layer", p.maskLayer ? "mask" : "image");
    index.set(at + "/purpose", p.purpose);
    index.set(at + "/label", p.label);
    index.set(at + "/screen_period_px", p.screenPeriodPx);
    index.set(at + "/slit_period_px", p.slitPeriodPx);
    index.set(at + "/phase_px", p.phasePx);
    index.set(at + "/view_distance_mm", distance);
    char line[256];
    std::snprintf(line, sizeof line, "%-23s %-6s %3d  %12.4f  %10.2f  %7.1f  %s\n", p.file.c_str(),
                  p.maskLayer ? "mask" : "image", p.screenPeriodPx, p.slitPeriodPx, p.phasePx,
                  distance, p.purpose.c_str());
    readme += line;
  }
  writeFileAtomically((dir / "index.json").string(), index.dump() + "\n");
  writeFileAtomically((dir / "README.txt").string(), readme);
  out.commit();
  std::printf("wrote %zu patterns, index.json and README.txt to %s\n", set.size(),
              out.dir().c_str());
}

// ---- predict -----------------------------------------------------------------------------

struct PredictOptions {
  std::string display, eye;
  PredictionSettings settings;
  bool json = false;
};

void runPredict(const PredictOptions& o) {
  const DisplayDesign design = loadDesignOrDefault(o.display);
  const DisplaySpec& spec = design.spec;
  Vec3d eye{spec.viewZoneCenterXMm, spec.viewZoneHeightMm, design.viewDistanceMm};
  if (!o.eye.empty()) {
    const Vec3f e = parseVec3("--eye", o.eye);
    if (!(e.z > 0)) throw InputError("command line", "--eye", "the eye must be in front (z > 0)");
    eye = {e.x, e.y, e.z};
  }
  // Each candidate period simulates every front pixel `samples` times.
  checkTimeEstimate(
      double(o.settings.samplesPerPixel) * spec.imagePanel.width * spec.imagePanel.height, 0,
      "samples", std::to_string(o.settings.samplesPerPixel), "use fewer samples");
  const CalibrationPrediction p =
      withOptionNames([&] { return predictCalibration(spec, design, eye, o.settings); });
  const double distance = p.distanceOverGap * design.gapMm;
  if (o.json) {
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
    std::printf("%s\n", json.dump().c_str());
    return;
  }
  std::printf("display              %s (%s)\n", spec.source.c_str(), orderName(spec.order));
  std::printf("eye                  %g, %g, %g mm\n", eye.x, eye.y, eye.z);
  std::printf("screen period Tx     %d px\n", p.screenPeriodPx);
  std::printf("slit period Tv       %.5f mask px (searched %.4f .. %.4f, finest step %.5f)\n",
              p.slitPeriodPx, p.fromPx, p.toPx, p.stepPx);
  std::printf("phase                %.3f mask px\n", p.phasePx);
  std::printf("D/g (G1)             %.2f: D = %.1f mm at the display's gap of %g mm\n",
              p.distanceOverGap, distance, design.gapMm);
  std::printf("contrast             %.3f (Michelson, against one view to each side)\n",
              p.score.contrast);
  std::printf("uniformity           %.3f (1 - std/mean across the view)\n", p.score.uniformity);
  if (p.atRangeEdge)
    std::printf(
        "note                 the best period is at the edge of the searched range; "
        "widen it with --from/--to\n");
}

// ---- apply -------------------------------------------------------------------------------

struct ApplyOptions {
  std::string display, output;
  double screenPeriod = 0, slitPeriod = 0;
  std::optional<double> phase, gap;
};

void runApply(const ApplyOptions& o) {
  const BarrierDisplayFile file = loadSpecOrDefault(o.display);
  DisplaySpec base = file.spec;
  // What is wrong from here on came from the command line.
  base.source = "command line";
  if (o.gap) base.gapMm = *o.gap;
  // The phase measured from the view-zone centre is the panels' sideways misalignment: it
  // moves the drawn mask (panel_offset_px), not the apertures the rays are traced through.
  DisplaySpec spec = measuredDisplaySpec(base, o.screenPeriod, o.slitPeriod, base.mask.phasePx);
  if (o.phase) spec.mask.panelOffsetPx = *o.phase;
  const DisplayDesign d = designDisplay(spec, file.camera);
  writeFileAtomically(o.output, displayFileText(spec, file.camera));
  std::printf("wrote %s\n", o.output.c_str());
  std::printf(
      "Tx %g px, Tv %g mask px, panel offset %g px, g %g mm: D = %.1f mm (G1), S = %.1f mm, "
      "%.4g views\n",
      d.screenPeriodPx, d.slitPeriodPx, spec.mask.panelOffsetPx, d.gapMm, d.viewDistanceMm,
      d.viewZoneWidthMm, d.views);
}

}  // namespace

void registerCalibrateCommand(CLI::App& cli) {
  CLI::App* cmd = cli.add_subcommand(
      "calibrate", "Calibrate a real display: slit patterns, predicted periods, display file");
  cmd->require_subcommand(1);

  auto patterns = std::make_shared<PatternsOptions>();
  CLI::App* p = cmd->add_subcommand("patterns", "Write calibration patterns for both layers");
  PatternSettings& s = patterns->settings;
  p->add_option("--display", patterns->display, "Display file (built-in display if omitted)");
  p->add_option("-o,--output", patterns->output, "Output folder")->capture_default_str();
  p->add_option("--screen-period", s.screenPeriodPx,
                "Integer screen period Tx in image pixels (default: the design's, rounded)")
      ->check(integerIn(0, INT_MAX));
  p->add_option("--slit-period", s.slitPeriodPx,
                "Slit period Tv (mask px) of the phase sweep and tests (default: G1's for Tx)")
      ->check(realIn(0, kInfinity));
  p->add_option("--phase", s.phasePx, "Mask phase (mask px) of the period sweep and tests")
      ->check(realIn(-kInfinity, kInfinity));
  p->add_option("--from", s.fromPx, "First slit period of the sweep (default: Tv - |Tv - Tx|/2)")
      ->check(realIn(0, kInfinity));
  p->add_option("--to", s.toPx, "Last slit period of the sweep (default: Tv + |Tv - Tx|/2)")
      ->check(realIn(0, kInfinity));
  p->add_option("--steps", s.periodSteps, "Slit periods in the sweep")
      ->capture_default_str()
      ->check(integerIn(1, INT_MAX));
  p->add_option("--phase-step", s.phaseStepPx, "Phase sweep step (mask px, default 0.5)")
      ->check(realIn(0, kInfinity, Bound::Open));
  p->add_option("--duty", s.duty, "Slit width / period on both layers (default: one pixel)")
      ->check(realIn(0, 1, Bound::Open));
  p->add_option("--label-scale", s.labelScale,
                "Label font scale, 1 to the panel's height (default: panel height / 180, at "
                "least 1)")
      ->check(integerIn(1, INT_MAX));
  addLimitOptions(*p);
  p->callback([patterns] { runPatterns(*patterns); });

  auto predict = std::make_shared<PredictOptions>();
  CLI::App* q = cmd->add_subcommand(
      "predict", "Simulate the patterns: the periods and phase with the most contrast");
  q->add_option("--display", predict->display, "Display file (built-in display if omitted)");
  q->add_option("--eye", predict->eye,
                "Eye position X,Y,Z in display mm (default: the view-zone centre at D)");
  q->add_option("--screen-period", predict->settings.screenPeriodPx,
                "Integer screen period Tx (default: the design's, rounded)")
      ->check(integerIn(0, INT_MAX));
  q->add_option("--from", predict->settings.fromPx,
                "Smallest slit period searched (default: g/D a quarter of the design's)")
      ->check(realIn(0, kInfinity));
  q->add_option("--to", predict->settings.toPx,
                "Largest slit period searched (default: g/D twice the design's)")
      ->check(realIn(0, kInfinity));
  q->add_option("--duty", predict->settings.duty, "Slit width / period (default: one pixel)")
      ->check(realIn(0, 1, Bound::Open));
  q->add_option("--samples", predict->settings.samplesPerPixel,
                "Simulated samples across each front pixel")
      ->capture_default_str()
      ->check(integerIn(1, INT_MAX));
  addLimitOptions(*q);
  q->add_flag("--json", predict->json, "Print one JSON object");
  q->callback([predict] { runPredict(*predict); });

  auto apply = std::make_shared<ApplyOptions>();
  CLI::App* a = cmd->add_subcommand("apply", "Write a display file with the measured periods");
  a->add_option("--screen-period", apply->screenPeriod, "Measured screen period Tx (image px)")
      ->required()
      ->check(realIn(0, kInfinity, Bound::Open));
  a->add_option("--slit-period", apply->slitPeriod, "Measured slit period Tv (mask px)")
      ->required()
      ->check(realIn(0, kInfinity, Bound::Open));
  a->add_option("--phase", apply->phase,
                "Mask phase (mask px) that looked right from the view-zone centre: written as "
                "the mask panel's offset (moves the drawn mask, not the traced apertures)")
      ->check(realIn(-kInfinity, kInfinity));
  a->add_option("--gap", apply->gap, "Gap g in mm, above 0 (default: the base display's)")
      ->check(realIn(0, kInfinity, Bound::Open));
  a->add_option("--display", apply->display, "Base display file (built-in display if omitted)");
  a->add_option("-o,--output", apply->output, "Display file to write")->required();
  a->callback([apply] { runApply(*apply); });
}

}  // namespace parallax::app
