#include "parallax/io/lenticular_file.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "parallax/core/error.h"
#include "parallax/display/lenticular_presets.h"

namespace parallax {
namespace {

namespace fs = std::filesystem;

// A device-style file: every field an object {"value": n}.
const char* kDeviceStyle = R"({
  "configVersion": "3.0", "serial": "TEST-0001",
  "pitch": {"value": 47.61}, "slope": {"value": -6.21}, "center": {"value": 0.413},
  "fringe": {"value": 0.0}, "viewCone": {"value": 40.0}, "invView": {"value": 1.0},
  "verticalAngle": {"value": 0.0}, "DPI": {"value": 324.0},
  "screenW": {"value": 1536.0}, "screenH": {"value": 2048.0},
  "flipImageX": {"value": 0.0}, "flipImageY": {"value": 1.0}, "flipSubp": {"value": 1.0},
  "CellPatternMode": {"value": 1},
  "subpixelCells": [
    {"ROffsetX": 0.0, "ROffsetY": 0.0, "GOffsetX": 0.0002, "GOffsetY": 0.0,
     "BOffsetX": 0.0004, "BOffsetY": 0.0001},
    {"ROffsetX": 0.0004, "ROffsetY": 0.0, "GOffsetX": 0.0002, "GOffsetY": 0.0,
     "BOffsetX": 0.0, "BOffsetY": -0.0001}
  ]
})";

std::string errorOf(const std::string& text) {
  try {
    parseLenticularCalibration(text, "visual.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(LenticularFile, ReadsValueObjects) {
  const LenticularCalibration c = parseLenticularCalibration(kDeviceStyle, "visual.json");
  EXPECT_EQ(c.source, "visual.json");
  EXPECT_DOUBLE_EQ(c.pitch, 47.61);
  EXPECT_DOUBLE_EQ(c.slope, -6.21);
  EXPECT_DOUBLE_EQ(c.center, 0.413);
  EXPECT_DOUBLE_EQ(c.viewConeDegrees, 40.0);
  EXPECT_DOUBLE_EQ(c.dpi, 324.0);
  EXPECT_EQ(c.screenW, 1536);
  EXPECT_EQ(c.screenH, 2048);
  EXPECT_TRUE(c.invView);
  EXPECT_FALSE(c.flipImageX);
  EXPECT_TRUE(c.flipImageY);
  EXPECT_TRUE(c.flipSubpixels);
  EXPECT_EQ(c.cellPatternMode, 1);
  ASSERT_EQ(c.subpixelCells.size(), 2u);
  EXPECT_DOUBLE_EQ(c.subpixelCells[0].offsetX[1], 0.0002);
  EXPECT_DOUBLE_EQ(c.subpixelCells[0].offsetY[2], 0.0001);
  EXPECT_DOUBLE_EQ(c.subpixelCells[1].offsetX[0], 0.0004);
  EXPECT_DOUBLE_EQ(c.subpixelCells[1].offsetY[2], -0.0001);
}

TEST(LenticularFile, AcceptsPlainNumbers) {
  const LenticularCalibration c = parseLenticularCalibration(
      R"({"pitch": 50, "slope": -5, "center": 0.2, "viewCone": 40, "invView": 0, "DPI": 300,
          "screenW": 1500, "screenH": 2000, "flipImageX": {"value": 1}})",
      "plain.json");
  EXPECT_DOUBLE_EQ(c.pitch, 50);
  EXPECT_EQ(c.screenH, 2000);
  EXPECT_FALSE(c.invView);
  EXPECT_TRUE(c.flipImageX);
  EXPECT_FALSE(c.flipSubpixels);  // absent flags are 0
  EXPECT_TRUE(c.subpixelCells.empty());
}

// A calibration as a 16" Gen3 unit writes it: no invView, cell pattern 2, offsets in pixels, and
// a key from newer firmware. Read with the shaders' defaults and one warning line per choice.
TEST(LenticularFile, ReadsGen3CalibrationsAsDevicesWriteThem) {
  const LenticularCalibration c = parseLenticularCalibration(
      R"({"configVersion": "3.0", "serial": "LKG-J00000", "pitch": {"value": 44.7506},
          "slope": {"value": -6.87457}, "center": {"value": 0.16936}, "viewCone": {"value": 50},
          "DPI": {"value": 283}, "screenW": {"value": 3840}, "screenH": {"value": 2160},
          "CellPatternMode": {"value": 2}, "newFirmwareKey": {"value": 7},
          "subpixelCells": [
            {"ROffsetX": -0.31, "ROffsetY": 0.25, "GOffsetX": 0.28, "GOffsetY": 0.25,
             "BOffsetX": 0, "BOffsetY": -0.25},
            {"ROffsetX": -0.31, "ROffsetY": -0.25, "GOffsetX": 0.28, "GOffsetY": -0.25,
             "BOffsetX": 0, "BOffsetY": 0.25}]})",
      "gen3.json");
  EXPECT_TRUE(c.invView);  // the shaders' 1 - frac
  EXPECT_EQ(c.cellPatternMode, 2);
  EXPECT_DOUBLE_EQ(c.subpixelCells[0].offsetX[0], -0.31);  // pixels, as written
  ASSERT_EQ(c.warnings.size(), 2u);
  EXPECT_NE(c.warnings[0].find("gen3.json: /newFirmwareKey: unknown key"), std::string::npos);
  EXPECT_NE(c.warnings[1].find("gen3.json: /invView: missing, taken as 1"), std::string::npos);
  // The subpixels land a fraction of a pixel from their pixel's centre, not across the screen.
  const LenticularDesign d = designLenticular(c);
  const Vec3d centre = subpixelPointMm(d, 100.5, 100.5, 1);
  const Vec3d red = subpixelPointMm(d, 100.5, 100.5, 0);
  EXPECT_LT(std::fabs(red.x - centre.x), d.pixelPitchMm);
  EXPECT_LT(std::fabs(red.y - centre.y), d.pixelPitchMm);
}

TEST(LenticularFile, ErrorsNameTheFileAndKey) {
  const std::string base =
      R"("pitch": 50, "center": 0.2, "viewCone": 40, "invView": 1, "DPI": 300,
         "screenW": 1500, "screenH": 2000)";
  EXPECT_NE(errorOf("{" + base + "}").find("visual.json: /slope: missing"), std::string::npos)
      << errorOf("{" + base + "}");
  const std::string withSlope = "{" + base + R"(, "slope": -5)";
  EXPECT_EQ(errorOf(withSlope + "}"), "no error");
  EXPECT_NE(errorOf(withSlope + R"(, "flipSubp": {"value": "yes"}})").find("/flipSubp/value"),
            std::string::npos);
  EXPECT_NE(errorOf(withSlope + R"(, "flipSubp": {"value": 2}})").find("/flipSubp/value"),
            std::string::npos);
  EXPECT_NE(errorOf(withSlope + R"(, "fringe": {"value": 0, "min": 0}})").find("/fringe/min"),
            std::string::npos);
  EXPECT_NE(errorOf(withSlope + R"(, "subpixelCells": [{"ROffsetX": 0}]})")
                .find("/subpixelCells/0/ROffsetY: missing"),
            std::string::npos);
  EXPECT_NE(errorOf(withSlope + R"(, "CellPatternMode": 5})").find("/CellPatternMode"),
            std::string::npos);
  EXPECT_NE(errorOf(withSlope + R"(, "CellPatternMode": 1.5})").find("/CellPatternMode"),
            std::string::npos);
  // Relations between fields are checked against the same file.
  EXPECT_NE(errorOf(R"({"pitch": 50, "slope": 0, "center": 0, "viewCone": 40, "invView": 1,
                        "DPI": 300, "screenW": 1500, "screenH": 2000})")
                .find("visual.json: /slope"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"pitch": 50, "slope": -5, "center": 0, "viewCone": 40, "invView": 1,
                        "DPI": 300, "screenW": 1500.5, "screenH": 2000})")
                .find("visual.json: /screenW: expected a whole number"),
            std::string::npos);
  try {
    loadLenticularCalibration("/nonexistent/visual.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/visual.json"), std::string::npos);
  }
}

TEST(LenticularFile, WrittenTextReadsBack) {
  const LenticularCalibration a = parseLenticularCalibration(kDeviceStyle, "a.json");
  const LenticularCalibration b = parseLenticularCalibration(lenticularCalibrationText(a), "b");
  EXPECT_DOUBLE_EQ(a.pitch, b.pitch);
  EXPECT_DOUBLE_EQ(a.slope, b.slope);
  EXPECT_DOUBLE_EQ(a.center, b.center);
  EXPECT_DOUBLE_EQ(a.viewConeDegrees, b.viewConeDegrees);
  EXPECT_DOUBLE_EQ(a.dpi, b.dpi);
  EXPECT_EQ(a.screenW, b.screenW);
  EXPECT_EQ(a.screenH, b.screenH);
  EXPECT_EQ(a.invView, b.invView);
  EXPECT_EQ(a.flipImageY, b.flipImageY);
  EXPECT_EQ(a.flipSubpixels, b.flipSubpixels);
  EXPECT_EQ(a.cellPatternMode, b.cellPatternMode);
  ASSERT_EQ(b.subpixelCells.size(), 2u);
  for (size_t i = 0; i < 2; ++i)
    for (size_t ch = 0; ch < 3; ++ch) {
      EXPECT_DOUBLE_EQ(a.subpixelCells[i].offsetX[ch], b.subpixelCells[i].offsetX[ch]);
      EXPECT_DOUBLE_EQ(a.subpixelCells[i].offsetY[ch], b.subpixelCells[i].offsetY[ch]);
    }
  EXPECT_NE(lenticularCalibrationText(a).find("\"value\""), std::string::npos);
  EXPECT_EQ(b.serial, "TEST-0001");  // kept: the copy beside the pictures is the same unit
}

// Each preset's visual.json, written and loaded back as a unit's own file, is that device, with
// its device's default quilt (a 16" Gen3's 7x7 on 5999 x 5999, not the Portrait's 8x6); with a
// serial of its line, by the serial.
TEST(LenticularFile, AUnitsFileGetsItsDevicesQuilt) {
  for (const LenticularPreset& p : lenticularPresets()) {
    for (const std::string& serial : {std::string(), p.serialPrefix + "00332"}) {
      LenticularCalibration written = p.calibration;
      written.serial = serial;
      const LenticularCalibration c =
          parseLenticularCalibration(lenticularCalibrationText(written), "visual.json");
      EXPECT_EQ(c.serial, serial);
      EXPECT_EQ(c.device, p.name) << serial;
      EXPECT_NE(c.deviceBasis.find(serial.empty() ? "pixels at" : "serial LKG-"), std::string::npos)
          << c.deviceBasis;
      EXPECT_EQ(c.quilt.columns, p.calibration.quilt.columns) << p.name;
      EXPECT_EQ(c.quilt.rows, p.calibration.quilt.rows) << p.name;
      EXPECT_EQ(c.quilt.width, p.calibration.quilt.width) << p.name;
      EXPECT_EQ(c.quilt.height, p.calibration.quilt.height) << p.name;
      EXPECT_EQ(designLenticular(c).quiltViews, p.calibration.quilt.views()) << p.name;
    }
  }
  const LenticularCalibration gen3 = parseLenticularCalibration(
      lenticularCalibrationText(*lenticularPreset("16-gen3")), "visual.json");
  EXPECT_EQ(gen3.quilt.columns, 7);
  EXPECT_EQ(gen3.quilt.rows, 7);
  // A panel no preset has: a quilt derived from it.
  LenticularCalibration odd = *lenticularPreset("portrait");
  odd.screenW = 1200, odd.screenH = 1920, odd.serial = "ACME-1";
  const LenticularCalibration c =
      parseLenticularCalibration(lenticularCalibrationText(odd), "visual.json");
  EXPECT_EQ(c.device, "");
  EXPECT_EQ(c.quilt.views(), derivedQuilt(1200, 1920).views());
  EXPECT_EQ(c.quilt.width, derivedQuilt(1200, 1920).width);
}

TEST(LenticularFile, EveryExampleLoads) {
  int count = 0;
  for (const auto& entry :
       fs::directory_iterator(fs::path(PARALLAX_SOURCE_DIR) / "displays" / "lenticular")) {
    const LenticularDesign d = designLenticular(loadLenticularCalibration(entry.path().string()));
    EXPECT_GT(d.subpixelsPerLens, 6.0) << entry.path();
    EXPECT_LT(d.subpixelsPerLens, 100.0) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 3);
}

}  // namespace
}  // namespace parallax
