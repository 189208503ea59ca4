#include "parallax/display/lenticular_presets.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace parallax
