// How well calibration from photos works, measured against the photo maker's truth
// (docs/calibration.md, "Accuracy"): many random displays that differ from the nominal one as
// real panels do, each photographed by a random hand-held phone, measured, and compared with the
// truth. `parallax calibrate study` prints the table the docs hold; the tests run a few trials.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "parallax/jobs/display_request.h"
#include "parallax/jobs/reporter.h"

namespace parallax::jobs {

struct CalibrationStudyRequest {
  DisplayRequest display;  // the nominal display ("" the built-in barrier, a file, lkg:NAME)
  int sets = 100;          // photo sets (trials), each with its own true display and photos
  int photosPerSet = 2;    // photos of the one shot per set, from distances 25 % apart
  double snrDb = 20;       // the pattern's contrast over the read noise
  int photoWidth = 4032, photoHeight = 3024;  // the phone's sensor (landscape)
  int samplesPerPixel = 8;                    // the photo maker's samples per photo pixel
  double maxOffAxisDegrees = 30;
  double blurMm = -1;  // the aperture's diameter; < 0: random, 1.5 to 3 mm
  // Lenticular: the estimator is told where each phone stood (the fringes' lever from the truth,
  // the photo still read through the markers' camera): the error left without the camera's.
  bool trueCamera = false;
  uint64_t seed = 1;
  std::string photos;  // a folder to keep the photos in ("" none)
  bool json = false;
};

// One trial: the truth, the estimate (or why the photos were refused) and the errors.
struct CalibrationTrial {
  bool refused = false;
  std::string refusal;
  // barrier: gap (relative), offset (mask px), rotation (degrees), slit period at D (mask px)
  // lenticular: pitch (relative), slant (degrees), center (lens periods)
  std::vector<double> errors, sigmas;
  // The truth and the estimate of each quantity (empty where not recorded).
  std::vector<double> truths, estimates;
  // Per photo, where the phone stood and where the estimate put it (display frame, mm, over
  // the front: the lens sheet, the barrier's front panel), and the sheet's or barrier's gap,
  // true and measured: what an error comes from.
  std::vector<std::array<double, 3>> truePhones, measuredPhones;
  double trueGapMm = 0, measuredGapMm = 0;
  double seconds = 0;
};

struct CalibrationStudy {
  std::string kind;
  std::vector<std::string> quantities;  // what errors[i] measures
  std::vector<CalibrationTrial> trials;
};

CalibrationStudy calibrationStudy(const CalibrationStudyRequest& request, Reporter& reporter);
// The study, reported: per quantity the median and 95th percentile of |error| and the share of
// errors within two sigmas, and the refusals.
void runCalibrationStudy(const CalibrationStudyRequest& request, Reporter& reporter);

}  // namespace parallax::jobs
