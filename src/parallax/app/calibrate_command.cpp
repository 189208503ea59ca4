// `parallax calibrate`: the paper's calibration of a real display (section 3.1,
// docs/calibration.md). `patterns` writes slit patterns to show on the panels, `predict` asks
// the simulator which periods and phase should look right, `apply` turns measured periods
// into a display file. The work: jobs/calibrate_job.h.
#include <climits>
#include <memory>
#include <optional>
#include <string>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/jobs/calibrate_job.h"
#include "parallax/jobs/calibrate_photo_job.h"
#include "parallax/jobs/calibrate_study.h"

namespace parallax::app {

namespace {

// patterns' request, or with --photo the shots' (the same display and output folder).
struct PatternsOptions {
  CalibrationPatternsRequest request;
  bool photo = false;
};

void runPatterns(const PatternsOptions& o) {
  if (o.photo) {
    runCalibrationShots({o.request.display, o.request.output}, cliReporter());
    return;
  }
  runCalibrationPatterns(o.request, cliReporter());
}

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

void registerCalibrateCommand(Command& cli) {
  Command* cmd = cli.addSubcommand(
      "calibrate", "Calibrate a real display: slit patterns, predicted periods, display file");
  cmd->requireSubcommand(1);

  auto patternOptions = std::make_shared<PatternsOptions>();
  CalibrationPatternsRequest* patterns = &patternOptions->request;
  Command* p = cmd->addSubcommand("patterns", "Write calibration patterns for both layers");
  PatternSettings& s = patterns->settings;
  p->addFlag("--photo", patternOptions->photo,
             "Write the shots to photograph with a phone instead (any display kind; then "
             "`calibrate photo`)");
  addDisplayOption(*p, patterns->display, "Display file (built-in display if omitted)");
  p->addOption("-o,--output", patterns->output, "Output folder")->captureDefault();
  p->addOption("--screen-period", s.screenPeriodPx,
               "Integer screen period Tx in image pixels (default: the design's, rounded)")
      ->check(integerIn(0, INT_MAX));
  p->addOption("--slit-period", s.slitPeriodPx,
               "Slit period Tv (mask px) of the phase sweep and tests (default: G1's for Tx)")
      ->check(realIn(0, kInfinity));
  p->addOption("--phase", s.phasePx, "Mask phase (mask px) of the period sweep and tests")
      ->check(realIn(-kInfinity, kInfinity));
  p->addOption("--from", s.fromPx, "First slit period of the sweep (default: Tv - |Tv - Tx|/2)")
      ->check(realIn(0, kInfinity));
  p->addOption("--to", s.toPx, "Last slit period of the sweep (default: Tv + |Tv - Tx|/2)")
      ->check(realIn(0, kInfinity));
  p->addOption("--steps", s.periodSteps, "Slit periods in the sweep")
      ->captureDefault()
      ->check(integerIn(1, INT_MAX));
  p->addOption("--phase-step", s.phaseStepPx, "Phase sweep step (mask px, default 0.5)")
      ->check(realIn(0, kInfinity, Bound::Open));
  p->addOption("--duty", s.duty, "Slit width / period on both layers (default: one pixel)")
      ->check(realIn(0, 1, Bound::Open));
  p->addOption("--label-scale", s.labelScale,
               "Label font scale, 1 to the panel's height (default: panel height / 180, at "
               "least 1)")
      ->check(integerIn(1, INT_MAX));
  addLimitOptions(*p);
  p->callback([patternOptions] { runPatterns(*patternOptions); });

  auto predict = std::make_shared<PredictOptions>();
  Command* q = cmd->addSubcommand(
      "predict", "Simulate the patterns: the periods and phase with the most contrast");
  CalibrationPredictRequest& prediction = predict->request;
  addDisplayOption(*q, prediction.display, "Display file (built-in display if omitted)");
  q->addOption("--eye", predict->eye,
               "Eye position X,Y,Z in display mm (default: the view-zone centre at D)");
  q->addOption("--screen-period", prediction.settings.screenPeriodPx,
               "Integer screen period Tx (default: the design's, rounded)")
      ->check(integerIn(0, INT_MAX));
  q->addOption("--from", prediction.settings.fromPx,
               "Smallest slit period searched (default: g/D a quarter of the design's)")
      ->check(realIn(0, kInfinity));
  q->addOption("--to", prediction.settings.toPx,
               "Largest slit period searched (default: g/D twice the design's)")
      ->check(realIn(0, kInfinity));
  q->addOption("--duty", prediction.settings.duty, "Slit width / period (default: one pixel)")
      ->check(realIn(0, 1, Bound::Open));
  q->addOption("--samples", prediction.settings.samplesPerPixel,
               "Simulated samples across each front pixel")
      ->captureDefault()
      ->check(integerIn(1, INT_MAX));
  addLimitOptions(*q);
  q->addFlag("--json", prediction.json, "Print one JSON object");
  q->callback([predict] { runPredict(*predict); });

  auto apply = std::make_shared<CalibrationApplyRequest>();
  Command* a = cmd->addSubcommand("apply", "Write a display file with the measured periods");
  a->addOption("--screen-period", apply->screenPeriodPx, "Measured screen period Tx (image px)")
      ->required()
      ->check(realIn(0, kInfinity, Bound::Open));
  a->addOption("--slit-period", apply->slitPeriodPx, "Measured slit period Tv (mask px)")
      ->required()
      ->check(realIn(0, kInfinity, Bound::Open));
  a->addOption("--phase", apply->phasePx,
               "Mask phase (mask px) that looked right from the view-zone centre: written as "
               "the mask panel's offset (moves the drawn mask, not the traced apertures)")
      ->check(realIn(-kInfinity, kInfinity));
  a->addOption("--gap", apply->gapMm, "Gap g in mm, above 0 (default: the base display's)")
      ->check(realIn(0, kInfinity, Bound::Open));
  addDisplayOption(*a, apply->display, "Base display file (built-in display if omitted)");
  a->addOption("-o,--output", apply->output, "Display file to write")->required();
  a->callback([apply] { runCalibrationApply(*apply, cliReporter()); });

  auto photo = std::make_shared<CalibratePhotoRequest>();
  Command* f = cmd->addSubcommand(
      "photo", "Measure the display from phone photos of the shots (calibrate patterns --photo)");
  f->addOption("--shots", photo->shots, "The shots' folder (calibrate patterns --photo)")
      ->required();
  f->addOption("photos", photo->photos,
               "Photos (JPEG or PNG), each named after its shot: grid-1.jpg, grid.far.png")
      ->required();
  addDisplayOption(*f, photo->display,
                   "The nominal display (default: the one the shots were made for)");
  f->addOption("-o,--output", photo->output, "The measured display file to write")->required();
  f->addFlag("--json", photo->json, "Print one JSON object");
  addLimitOptions(*f);
  f->callback([photo] { runCalibratePhoto(*photo, cliReporter()); });

  auto check = std::make_shared<CalibrationCheckRequest>();
  Command* k = cmd->addSubcommand(
      "check",
      "What each seat sees of a lenticular panel, from a photo taken there of the lens shot drawn "
      "with the calibration to check (calibrate patterns --photo --display FILE)");
  k->addOption("--shots", check->shots, "The shots' folder (calibrate patterns --photo)")
      ->required();
  k->addOption("photos", check->photos,
               "Photos (JPEG or PNG), one from each seat, named after the shot: lens-left.jpg")
      ->required();
  addDisplayOption(*k, check->display,
                   "The display the shots show (default: the one they were made for)");
  k->addFlag("--json", check->json, "Print one JSON object");
  addLimitOptions(*k);
  k->callback([check] { runCalibrationCheck(*check, cliReporter()); });

  auto study = std::make_shared<CalibrationStudyRequest>();
  Command* t = cmd->addSubcommand(
      "study",
      "How precise calibrate photo is: random true displays, photographed by the photo "
      "maker, measured and compared with the truth");
  addDisplayOption(*t, study->display, "The nominal display (built-in display if omitted)");
  t->addOption("--sets", study->sets, "Photo sets (trials)")
      ->captureDefault()
      ->check(integerIn(1, 100000));
  t->addOption("--photos-per-set", study->photosPerSet, "Photos of the shot in each set")
      ->captureDefault()
      ->check(integerIn(1, 6));
  t->addOption("--snr", study->snrDb, "The pattern's amplitude over the sensor's noise, dB")
      ->captureDefault()
      ->check(realIn(-20, 120));
  t->addOption("--photo-width", study->photoWidth, "The phone's photos, pixels across")
      ->captureDefault()
      ->check(integerIn(320, 12000));
  t->addOption("--photo-height", study->photoHeight, "The phone's photos, pixels down")
      ->captureDefault()
      ->check(integerIn(240, 12000));
  t->addOption("--samples", study->samplesPerPixel, "The photo maker's samples per photo pixel")
      ->captureDefault()
      ->check(integerIn(1, 256));
  t->addOption("--max-off-axis", study->maxOffAxisDegrees,
               "The photos' largest angle from the panel's normal, degrees")
      ->captureDefault()
      ->check(realIn(0, 60));
  t->addFlag("--true-camera", study->trueCamera,
             "Lenticular: tell the estimator where each phone stood (the error left without the "
             "camera's)");
  t->addOption("--aperture", study->blurMm,
               "The phone lens's aperture, mm (default: random, 1.5 to 3)")
      ->check(realIn(0, 50));
  t->addOption("--seed", study->seed, "The study's random seed")->captureDefault();
  t->addOption("--keep-photos", study->photos, "Keep the photos (JPEG) in this folder");
  t->addFlag("--json", study->json, "Print one JSON object");
  addLimitOptions(*t);
  t->callback([study] { runCalibrationStudy(*study, cliReporter()); });
}

}  // namespace parallax::app
