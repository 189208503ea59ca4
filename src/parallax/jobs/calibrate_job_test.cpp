#include "parallax/jobs/calibrate_job.h"

#include <gtest/gtest.h>

#include <string>

#include "parallax/core/error.h"
#include "parallax/io/display_file.h"
#include "parallax/jobs/jobs_test_support.h"

namespace parallax::jobs {
namespace {

CalibrationPatternsRequest smallPatterns() {
  CalibrationPatternsRequest r;
  r.display.path = kSmallDisplayFile;
  return r;
}

// The set: the four fixed patterns, the period sweep's steps and the phase sweep, each at its
// layer's resolution, described in the index and the README in the same order.
TEST(CalibrationPatterns, OneOfEachStepEachAtItsLayersSize) {
  CalibrationPatternsRequest r = smallPatterns();
  r.settings.periodSteps = 5;
  r.settings.phaseStepPx = 1;
  const CalibrationPatternSet set = calibrationPatterns(r, silentReporter(), true);
  int periods = 0, phases = 0;
  for (const PatternDescription& p : set.patterns) {
    periods += p.file.rfind("mask-period-", 0) == 0;
    phases += p.file.rfind("mask-phase-", 0) == 0;
  }
  EXPECT_EQ(periods, 5);
  // One phase step a mask pixel across one slit period (about nine pixels).
  EXPECT_GE(phases, 8);
  EXPECT_LE(phases, 10);
  EXPECT_EQ(set.patterns.size(), size_t(periods + phases + 4));
  ASSERT_EQ(set.viewDistancesMm.size(), set.patterns.size());
  for (size_t i = 0; i < set.patterns.size(); ++i) {
    const Image picture = set.draw(i);
    EXPECT_EQ(picture.width(), 320) << set.patterns[i].file;
    EXPECT_EQ(picture.height(), 180) << set.patterns[i].file;
    EXPECT_NE(set.index.find("\"" + set.patterns[i].file + "\""), std::string::npos);
    EXPECT_NE(set.readme.find(set.patterns[i].file), std::string::npos);
    EXPECT_GT(set.viewDistancesMm[i], 0);
  }
}

// The RequestError `call` throws (an empty one, and a failure, if none).
template <class Call>
RequestError refusal(Call call) {
  try {
    call();
  } catch (const RequestError& e) {
    return e;
  }
  ADD_FAILURE() << "no refusal";
  return RequestError("", "");
}

TEST(CalibrationPatterns, RefusalsNameTheSettingsFields) {
  CalibrationPatternsRequest r = smallPatterns();
  r.settings.fromPx = 9.02;  // without to_px
  RequestError e = refusal([&] { calibrationPatterns(r, silentReporter()); });
  EXPECT_EQ(e.field(), "from_px");
  // The other fields the message names are left for the front end to spell.
  EXPECT_EQ(e.message(), "give both ends of the period range ({from_px} and {to_px})");
  r = smallPatterns();
  r.settings.labelScale = 1000;  // a label taller than the panel
  e = refusal([&] { calibrationPatterns(r, silentReporter()); });
  EXPECT_EQ(e.field(), "label_scale");
  EXPECT_EQ(e.value(), "1000");
  r = smallPatterns();
  r.settings.periodSteps = 1000000000;  // beyond the time limit
  EXPECT_EQ(refusal([&] { calibrationPatterns(r, silentReporter()); }).field(), "period_steps");
  r = smallPatterns();
  r.display.loaded = loadDisplayDescription("lkg:portrait");
  EXPECT_THROW(calibrationPatterns(r, silentReporter()), InputError);
}

TEST(CalibrationPredict, RefusesAnEyeBehindTheDisplay) {
  CalibrationPredictRequest r;
  r.display.path = kSmallDisplayFile;
  r.eye = Vec3d{0, 0, -5};
  EXPECT_EQ(refusal([&] { runCalibrationPredict(r, silentReporter()); }).field(), "eye");
}

// The measured periods become the display: D = g / (Tv/Tx - 1) (G1, barrier-back), the phase
// the mask panel's offset; periods that break G1 are refused under their display-file key.
TEST(CalibrationApply, TheMeasuredPeriodsMakeTheDisplay) {
  CalibrationApplyRequest r;
  r.display.path = kSmallDisplayFile;
  r.screenPeriodPx = 9;
  r.slitPeriodPx = 9.0347;
  r.phasePx = 0.25;
  r.gapMm = 2.7;
  const DisplayDesign d = appliedCalibration(r, silentReporter());
  EXPECT_DOUBLE_EQ(d.screenPeriodPx, 9);
  EXPECT_DOUBLE_EQ(d.slitPeriodPx, 9.0347);
  EXPECT_NEAR(d.viewDistanceMm, 2.7 / (9.0347 / 9 - 1), 1e-6);
  EXPECT_DOUBLE_EQ(d.spec.mask.panelOffsetPx, 0.25);
  r.slitPeriodPx = 8.9;
  try {
    appliedCalibration(r, silentReporter());
    ADD_FAILURE() << "periods that break G1";
  } catch (const RequestError& e) {
    // The field the option sets, not the key of the display file it makes.
    EXPECT_EQ(e.field(), "slit_period");
    EXPECT_EQ(e.message().rfind("G1 needs", 0), 0u) << e.message();
  }
  r.slitPeriodPx = 9.0347, r.gapMm = 2000;
  try {
    appliedCalibration(r, silentReporter());
    ADD_FAILURE() << "a gap of 2 m";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.field(), "gap");
  }
}

}  // namespace
}  // namespace parallax::jobs
