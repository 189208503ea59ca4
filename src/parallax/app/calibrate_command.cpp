// `parallax calibrate`: the paper's calibration of a real display (section 3.1,
// docs/calibration.md). `patterns` writes slit patterns to show on the panels, `predict` asks
// the simulator which periods and phase should look right, `apply` turns measured periods
// into a display file. The work: jobs/calibrate_job.h.
#include <CLI/CLI.hpp>

#include <climits>
#include <memory>
#include <optional>
#include <string>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/jobs/calibrate_job.h"

namespace parallax::app {

namespace {

// predict's request, and its eye as the command line spells it (X,Y,Z).
struct PredictOptions {
  CalibrationPredictRequest request;
  std::string eye;
};

void runPredict(PredictOptions o) {
  if (!o.eye.empty()) {
    const Vec3f e = parseVec3("--eye", o.eye);
    o.request.eye = Vec3d{e.x, e.y, e.z};
  }
  runCalibrationPredict(o.request, cliReporter());
}

}  // namespace

void registerCalibrateCommand(CLI::App& cli) {
  CLI::App* cmd = cli.add_subcommand(
      "calibrate", "Calibrate a real display: slit patterns, predicted periods, display file");
  cmd->require_subcommand(1);

  auto patterns = std::make_shared<CalibrationPatternsRequest>();
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
  p->callback([patterns] { runCalibrationPatterns(*patterns, cliReporter()); });

  auto predict = std::make_shared<PredictOptions>();
  CLI::App* q = cmd->add_subcommand(
      "predict", "Simulate the patterns: the periods and phase with the most contrast");
  CalibrationPredictRequest& prediction = predict->request;
  q->add_option("--display", prediction.display, "Display file (built-in display if omitted)");
  q->add_option("--eye", predict->eye,
                "Eye position X,Y,Z in display mm (default: the view-zone centre at D)");
  q->add_option("--screen-period", prediction.settings.screenPeriodPx,
                "Integer screen period Tx (default: the design's, rounded)")
      ->check(integerIn(0, INT_MAX));
  q->add_option("--from", prediction.settings.fromPx,
                "Smallest slit period searched (default: g/D a quarter of the design's)")
      ->check(realIn(0, kInfinity));
  q->add_option("--to", prediction.settings.toPx,
                "Largest slit period searched (default: g/D twice the design's)")
      ->check(realIn(0, kInfinity));
  q->add_option("--duty", prediction.settings.duty, "Slit width / period (default: one pixel)")
      ->check(realIn(0, 1, Bound::Open));
  q->add_option("--samples", prediction.settings.samplesPerPixel,
                "Simulated samples across each front pixel")
      ->capture_default_str()
      ->check(integerIn(1, INT_MAX));
  addLimitOptions(*q);
  q->add_flag("--json", prediction.json, "Print one JSON object");
  q->callback([predict] { runPredict(*predict); });

  auto apply = std::make_shared<CalibrationApplyRequest>();
  CLI::App* a = cmd->add_subcommand("apply", "Write a display file with the measured periods");
  a->add_option("--screen-period", apply->screenPeriodPx, "Measured screen period Tx (image px)")
      ->required()
      ->check(realIn(0, kInfinity, Bound::Open));
  a->add_option("--slit-period", apply->slitPeriodPx, "Measured slit period Tv (mask px)")
      ->required()
      ->check(realIn(0, kInfinity, Bound::Open));
  a->add_option("--phase", apply->phasePx,
                "Mask phase (mask px) that looked right from the view-zone centre: written as "
                "the mask panel's offset (moves the drawn mask, not the traced apertures)")
      ->check(realIn(-kInfinity, kInfinity));
  a->add_option("--gap", apply->gapMm, "Gap g in mm, above 0 (default: the base display's)")
      ->check(realIn(0, kInfinity, Bound::Open));
  a->add_option("--display", apply->display, "Base display file (built-in display if omitted)");
  a->add_option("-o,--output", apply->output, "Display file to write")->required();
  a->callback([apply] { runCalibrationApply(*apply, cliReporter()); });
}

}  // namespace parallax::app
