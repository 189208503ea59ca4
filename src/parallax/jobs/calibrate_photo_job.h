// Calibration from phone photos (docs/calibration.md, "From photos"): the shots to show on the
// panels, and the display measured from photos of them. `parallax calibrate patterns --photo`,
// `parallax calibrate photo` and Python's calibration_photo_patterns / calibrate_photo are
// spellings of these requests.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "parallax/image/image.h"
#include "parallax/io/display_file.h"
#include "parallax/jobs/display_request.h"
#include "parallax/jobs/reporter.h"
#include "parallax/photocal/barrier_estimate.h"
#include "parallax/photocal/lenticular_check.h"
#include "parallax/photocal/lenticular_estimate.h"

namespace parallax::jobs {

// ---- the shots -------------------------------------------------------------------------------

struct CalibrationShotsRequest {
  DisplayRequest display;  // "" the built-in barrier, a display file, or lkg:NAME
  std::string output = "shots";
};

// One picture of one shot, at its layer's native resolution.
struct ShotPicture {
  std::string shot;   // the shot's name ("grid")
  std::string layer;  // "image", "mask" (barrier) or "panel" (lenticular)
  std::string file;   // its file name in the set
  Image picture;      // linear RGB
};

struct CalibrationShotSet {
  DisplayDescription display;
  std::string kind;  // "barrier" or "lenticular"
  std::vector<ShotPicture> pictures;
  std::string displayFile, displayText;  // the nominal display, as the set keeps it
  std::string index, readme;             // index.json and README.txt
};

// The set for the display, drawn (a few pictures at the panels' size). Throws InputError naming
// the display when it cannot carry the shots.
CalibrationShotSet calibrationShots(const CalibrationShotsRequest& request, Reporter& reporter);
// Writes the set's pictures, index.json, README.txt and the nominal display into
// request.output, as one set.
void runCalibrationShots(const CalibrationShotsRequest& request, Reporter& reporter);

// ---- the photos ------------------------------------------------------------------------------

struct CalibratePhotoRequest {
  DisplayRequest display;           // the nominal display; "" the one the shots were made for
  std::string shots;                // the folder calibrationShots wrote
  std::vector<std::string> photos;  // JPEG or PNG, each named after its shot
  std::string output;               // MEASURED.json ("" writes nothing: Python)
  bool json = false;                // report one JSON object instead of the text
};

struct PhotoCalibration {
  std::string kind;
  photocal::BarrierMeasurement barrier;        // kind barrier
  photocal::LenticularMeasurement lenticular;  // kind lenticular
  DisplayDescription measured;                 // the nominal display with the measured keys
  std::string measuredText;                    // as MEASURED.json holds it
  std::string json;                            // the report as one JSON object
  std::vector<std::string> lines;              // the report as text
};

// Reads the shots and the photos and measures. Refusals name the photo and what it lacks, the
// shots folder and its key, or the request's field.
PhotoCalibration calibrateFromPhotos(const CalibratePhotoRequest& request, Reporter& reporter);
// The same, then writes request.output and reports.
void runCalibratePhoto(const CalibratePhotoRequest& request, Reporter& reporter);

// ---- the check -------------------------------------------------------------------------------

// What each seat sees (photocal/lenticular_check.h): photos of a lenticular display's lens shot
// drawn with the calibration to check (`calibrate patterns --photo --display FILE`), one from
// each place a viewer sits. `parallax calibrate check`, Python's calibration_check.
struct CalibrationCheckRequest {
  DisplayRequest display;  // the display the shots show; "" the one they were made for
  std::string shots;
  std::vector<std::string> photos;
  bool json = false;
};

struct SeatCheckReport {
  std::vector<photocal::SeatCheck> seats;
  std::string json;                // one JSON object
  std::vector<std::string> lines;  // the report as text
};

SeatCheckReport checkSeats(const CalibrationCheckRequest& request, Reporter& reporter);
void runCalibrationCheck(const CalibrationCheckRequest& request, Reporter& reporter);

}  // namespace parallax::jobs
