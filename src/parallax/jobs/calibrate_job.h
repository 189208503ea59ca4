// The calibration runners (the paper's section 3.1, docs/calibration.md): the slit patterns to
// show on a barrier display's panels, the simulator's prediction of the periods and phase that
// should look right, and the display file with the measured periods. `parallax calibrate
// patterns|predict|apply` and Python's calibration functions are spellings of these requests.
// The settings' fields keep the library's names (screen_period_px, slit_period_px, phase_px,
// from_px, to_px, period_steps, phase_step_px, duty, label_scale, samples): refusals name them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "parallax/core/math.h"
#include "parallax/display/display.h"
#include "parallax/image/image.h"
#include "parallax/jobs/display_request.h"
#include "parallax/jobs/reporter.h"
#include "parallax/sim/calibration.h"

namespace parallax::jobs {

// ---- patterns --------------------------------------------------------------------------------

struct CalibrationPatternsRequest {
  DisplayRequest display;    // "" the built-in barrier, or a barrier display file
  PatternSettings settings;  // 0: each field's default
  std::string output = "calibration";
};

// The set, checked and described: what index.json and README.txt say of each pattern.
struct CalibrationPatternSet {
  DisplaySpec display;
  std::vector<PatternDescription> patterns;
  std::vector<double> viewDistancesMm;  // D each pattern's slit period implies (G1)
  std::string index, readme;            // index.json and README.txt
  // Pattern i's picture (linear RGB at its layer's resolution).
  Image draw(size_t i) const { return drawPattern(display, patterns[i]); }
};

// Checks the request and describes its set (nothing drawn). Throws RequestError naming the
// settings' fields, and refuses a set that would not be drawn within the time limit (or, with
// `inMemory`, kept within the memory limit: every picture at once).
CalibrationPatternSet calibrationPatterns(const CalibrationPatternsRequest& request,
                                          Reporter& reporter, bool inMemory = false);

// Writes the patterns, index.json and README.txt into request.output as one set.
void runCalibrationPatterns(const CalibrationPatternsRequest& request, Reporter& reporter);

// ---- predict ---------------------------------------------------------------------------------

struct CalibrationPredictRequest {
  DisplayRequest display;       // "" the built-in barrier, or a barrier display file
  std::optional<Vec3d> eye;     // display mm; default the view-zone centre at D
  PredictionSettings settings;  // screen_period_px, from_px, to_px, duty, samples
  bool json = false;            // report one JSON object instead of the text
};

// The prediction, reported as result lines (the text or the JSON object).
void runCalibrationPredict(const CalibrationPredictRequest& request, Reporter& reporter);

// ---- apply -----------------------------------------------------------------------------------

struct CalibrationApplyRequest {
  DisplayRequest display;  // the base display: "" the built-in barrier, or a barrier display file
  double screenPeriodPx = 0, slitPeriodPx = 0;  // measured Tx (image px), Tv (mask px)
  // phase_px: the mask phase that looked right from the view-zone centre, written as the mask
  // panel's offset (it moves the drawn mask, not the traced apertures).
  std::optional<double> phasePx;
  std::optional<double> gapMm;  // gap_mm: default the base display's
  std::string output;           // the display file to write
};

// The display with the measured periods: its spec (and camera settings) and its design. Errors
// in the measured values name their key in the display file ("/slit_period_px").
DisplayDesign appliedCalibration(const CalibrationApplyRequest& request, Reporter& reporter);

// Writes request.output, the display file of appliedCalibration.
void runCalibrationApply(const CalibrationApplyRequest& request, Reporter& reporter);

}  // namespace parallax::jobs
