// The depth budget on a lenticular panel (camera/framing.h, docs/lenticular.md "Depth of
// field"): the content of a bare box fitted into the lens's depth of field by a depth scale, a
// given focus and budget honoured, the window fit's warning, shallow content kept.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "parallax/camera/framing.h"
#include "parallax/display/depth_scaled_display.h"
#include "parallax/display/lenticular_presets.h"

namespace parallax {
namespace {

Scene boxScene(const Vec3f& half) {
  Scene scene;
  const Bounds3f b{-half, half};
  scene.display.fit = b;
  scene.display.content = b;
  scene.display.width = 2 * half.x;
  return scene;
}

LenticularDesign portrait() { return designLenticular(*lenticularPreset("portrait")); }

TEST(LenticularFraming, DepthFitScalesTheContentIntoTheLensDepthOfField) {
  const LenticularDesign d = portrait();
  const double dof = lensDepthOfFieldMm(d);
  const Framing f = frameForDisplay(boxScene({1, 1, 1}), d);
  ASSERT_EQ(f.fit, DisplayFit::Depth);
  EXPECT_TRUE(f.lenticular);
  EXPECT_DOUBLE_EQ(f.depthOfFieldMm, dof);
  EXPECT_DOUBLE_EQ(f.budgetMm, dof);
  // The cube fills the window (about 115 mm wide), so it is about as deep: far beyond +-13 mm.
  EXPECT_GT(f.nearMm - f.farMm, 80);
  EXPECT_NEAR(f.nearMm - f.farMm, 2 * f.scaleMmPerUnit, 1e-6);
  EXPECT_NEAR(harmonicFocusZ(f.nearMm, f.farMm, d.viewDistanceMm), 0.0, 1e-6);
  // The deeper (far) side lands exactly on the budget, the other inside it.
  EXPECT_NEAR(f.depthScale, dof / -f.farMm, 1e-12);
  EXPECT_NEAR(f.shownFarMm, -dof, 1e-9);
  EXPECT_NEAR(f.shownNearMm, f.nearMm * f.depthScale, 1e-12);
  EXPECT_LT(f.shownNearMm, dof);
  EXPECT_TRUE(f.withinBudget());
  EXPECT_EQ(depthWarning(f), "");
  EXPECT_NE(depthSummary(f).find("sharp within ±12.8 mm (lens)"), std::string::npos)
      << depthSummary(f);
}

TEST(LenticularFraming, AGivenFocusAndBudgetAreHonoured) {
  const LenticularDesign d = portrait();
  Scene scene = boxScene({1, 1, 1});
  applyFramingOptions(scene.display, "depth", "20", "30");
  const Framing f = frameForDisplay(scene, d);
  EXPECT_FALSE(f.focusAuto);
  EXPECT_FALSE(f.budgetAuto);
  EXPECT_DOUBLE_EQ(f.focusMm, 20);
  EXPECT_DOUBLE_EQ(f.budgetMm, 30);
  // The scene depth 20 mm in front of the placement's centre is now the panel's plane.
  EXPECT_NEAR((f.placement.center.z - scene.display.center.z) * f.scaleMmPerUnit, 20, 1e-4);
  EXPECT_NEAR(std::max(f.shownNearMm, -f.shownFarMm), 30, 1e-9);
  EXPECT_TRUE(f.withinBudget());
}

TEST(LenticularFraming, TheWindowFitKeepsTheDepthAndWarns) {
  const LenticularDesign d = portrait();
  Scene scene = boxScene({1, 1, 1});
  applyFramingOptions(scene.display, "window", "", "");
  const Framing f = frameForDisplay(scene, d);
  EXPECT_EQ(f.depthScale, 1);
  EXPECT_FALSE(f.withinBudget());
  char expected[160];
  std::snprintf(expected, sizeof expected,
                "the content spans %+.0f to %+.0f mm; the display is sharp within ±13 mm (the "
                "lens's depth of field); {fit} depth compresses it",
                f.farMm, f.nearMm);
  EXPECT_EQ(depthWarning(f), expected);
}

TEST(LenticularFraming, ShallowContentKeepsItsDepth) {
  Scene scene = boxScene({1, 1, 0.05f});  // 115 mm wide, about 6 mm deep
  const Framing f = frameForDisplay(scene, portrait());
  EXPECT_EQ(f.depthScale, 1);
  EXPECT_EQ(f.shownNearMm, f.nearMm);
  EXPECT_TRUE(f.withinBudget());
}

}  // namespace
}  // namespace parallax
