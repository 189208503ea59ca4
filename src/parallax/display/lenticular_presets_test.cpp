#include "parallax/display/lenticular_presets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <string>

namespace parallax {
namespace {

// Every preset is a valid calibration with its device's quilt.
TEST(LenticularPresets, EveryPresetDesigns) {
  ASSERT_GE(lenticularPresets().size(), 9u);
  for (const LenticularPreset& p : lenticularPresets()) {
    const LenticularDesign d = designLenticular(p.calibration);
    EXPECT_EQ(d.calibration.source, "lkg:" + p.name);
    EXPECT_GT(d.pixelsPerLens, 2) << p.name;
    EXPECT_EQ(d.quiltViews, p.calibration.quilt.columns * p.calibration.quilt.rows);
    // The default quilt's tiles have (about) the panel's aspect or are squeezed on purpose; the
    // quilt is never smaller than 3000 pixels a side for these devices.
    EXPECT_GE(p.calibration.quilt.width, 3000) << p.name;
    EXPECT_TRUE(d.calibration.invView);
  }
  ASSERT_TRUE(lenticularPreset("portrait"));
  EXPECT_EQ(lenticularPreset("portrait")->screenW, 1536);
  EXPECT_EQ(lenticularPreset("16-gen3")->cellPatternMode, 2);
  EXPECT_FALSE(lenticularPreset("nonesuch"));
  EXPECT_NE(lenticularPresetNames().find("portrait, go"), std::string::npos);
}

// The Gen3 panels' cell layouts: the landscape's second cell mirrors the first in y (pattern 2,
// alternate columns), the portrait's in x (pattern 4, alternate rows): the same OLED turned.
TEST(LenticularPresets, Gen3CellsMirrorAsTheirPatternsAlternate) {
  const LenticularCalibration landscape = *lenticularPreset("16-gen3");
  const LenticularCalibration portrait = *lenticularPreset("16-gen3-portrait");
  ASSERT_EQ(landscape.subpixelCells.size(), 2u);
  ASSERT_EQ(portrait.subpixelCells.size(), 2u);
  for (size_t c = 0; c < 3; ++c) {
    EXPECT_EQ(landscape.subpixelCells[1].offsetX[c], landscape.subpixelCells[0].offsetX[c]);
    EXPECT_EQ(landscape.subpixelCells[1].offsetY[c], -landscape.subpixelCells[0].offsetY[c]);
    EXPECT_EQ(portrait.subpixelCells[1].offsetX[c], -portrait.subpixelCells[0].offsetX[c]);
    EXPECT_EQ(portrait.subpixelCells[1].offsetY[c], portrait.subpixelCells[0].offsetY[c]);
    // Turned a quarter, (x, y) -> (-y, x): the same subpixels seen on the panel stood upright.
    EXPECT_EQ(portrait.subpixelCells[0].offsetX[c], -landscape.subpixelCells[0].offsetY[c]);
    EXPECT_EQ(portrait.subpixelCells[0].offsetY[c], landscape.subpixelCells[0].offsetX[c]);
  }
  EXPECT_EQ(cellIndex(landscape, 0, 5), 0);
  EXPECT_EQ(cellIndex(landscape, 1, 5), 1);
  EXPECT_EQ(cellIndex(portrait, 5, 0), 0);
  EXPECT_EQ(cellIndex(portrait, 5, 1), 1);
}

// A unit's calibration is recognised as its preset's device by its serial's prefix, and without
// a serial by its resolution and DPI, the nearest pitch deciding between devices of one panel
// (a real unit's pitch is within a few percent of its template's).
TEST(LenticularDevice, EveryPresetIsRecognisedBySerialAndByPanel) {
  for (const LenticularPreset& p : lenticularPresets()) {
    LenticularCalibration unit = p.calibration;
    unit.device.clear();
    unit.pitch *= 1.02;  // measured, not the template's
    unit.serial = p.serialPrefix + "01234";
    RecognisedDevice d = recogniseLenticularDevice(unit);
    ASSERT_TRUE(d.preset) << p.name;
    EXPECT_EQ(d.preset->name, p.name);
    EXPECT_EQ(d.basis, "serial " + unit.serial);
    unit.serial.clear();
    d = recogniseLenticularDevice(unit);
    ASSERT_TRUE(d.preset) << p.name;
    EXPECT_EQ(d.preset->name, p.name) << d.basis;
    EXPECT_NE(d.basis.find(std::to_string(unit.screenW) + "x"), std::string::npos) << d.basis;
    applyDeviceConventions(unit);
    EXPECT_EQ(unit.device, p.name);
    EXPECT_EQ(unit.quilt.columns, p.calibration.quilt.columns);
    EXPECT_EQ(unit.quilt.rows, p.calibration.quilt.rows);
    EXPECT_EQ(unit.quilt.width, p.calibration.quilt.width);
    EXPECT_EQ(unit.quilt.height, p.calibration.quilt.height);
  }
  // The prefixes are told apart (the serial wins over a nearer pitch): a 16" Gen2 unit whose
  // pitch happens to be the Gen3's is still a Gen2 by its serial.
  LenticularCalibration gen2 = *lenticularPreset("16-gen2");
  gen2.pitch = lenticularPreset("16-gen3")->pitch;
  gen2.serial = "LKG-A00001";
  EXPECT_EQ(recogniseLenticularDevice(gen2).preset->name, "16-gen2");
  gen2.serial = "";
  EXPECT_EQ(recogniseLenticularDevice(gen2).preset->name, "16-gen3");
}

// A serial of a known line on a panel that is not its preset's (a Go turned landscape), or a
// panel no preset has, is no preset's device.
TEST(LenticularDevice, OtherPanelsAreNoPresets) {
  LenticularCalibration turned = *lenticularPreset("go");
  std::swap(turned.screenW, turned.screenH);
  turned.serial = "LKG-E01234";
  EXPECT_FALSE(recogniseLenticularDevice(turned).preset);
  LenticularCalibration other = *lenticularPreset("portrait");
  other.dpi = 300;  // 1536 x 2048 at 300 DPI: another screen
  EXPECT_FALSE(recogniseLenticularDevice(other).preset);
  applyDeviceConventions(other);
  EXPECT_EQ(other.device, "");
  const QuiltFormat derived = derivedQuilt(1536, 2048);
  EXPECT_EQ(other.quilt.columns, derived.columns);
  EXPECT_EQ(other.quilt.width, derived.width);
}

// The derived quilt: about 48 views, tiles of about the panel's aspect on a square quilt, as
// Looking Glass's own (5x9 for 16:9 and 8x6 for 3:4 are its choices too).
TEST(LenticularDevice, DerivedQuiltsFollowThePanelsAspect) {
  QuiltFormat q = derivedQuilt(3840, 2160);
  EXPECT_EQ(q.columns, 5);
  EXPECT_EQ(q.rows, 9);
  q = derivedQuilt(1536, 2048);
  EXPECT_EQ(q.columns, 8);
  EXPECT_EQ(q.rows, 6);
  for (const auto& [w, h] : {std::pair{3840, 2160},
                             {1536, 2048},
                             {1440, 2560},
                             {2000, 2000},
                             {5120, 1440},
                             {800, 1280},
                             {7680, 4320}}) {
    q = derivedQuilt(w, h);
    EXPECT_GE(q.views(), 40) << w << "x" << h;
    EXPECT_LE(q.views(), 66) << w << "x" << h;
    EXPECT_EQ(q.width, q.height);
    EXPECT_GE(q.width, 2048);
    EXPECT_LE(q.width, 8192);
    const double tileAspect = double(q.width / q.columns) / (q.height / q.rows);
    EXPECT_LT(std::abs(std::log(tileAspect / (double(w) / h))), 0.12) << w << "x" << h;
    EXPECT_EQ(q.width % std::lcm(q.columns, q.rows), 0) << w << "x" << h;
  }
}

}  // namespace
}  // namespace parallax
