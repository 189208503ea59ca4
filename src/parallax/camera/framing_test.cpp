// The depth budget: the framing's width fit, zero-parallax plane and virtual gap on an analytic
// box (docs/display-geometry.md, "Depth budget"), and on a lenticular panel its depth scale.
#include "parallax/camera/framing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "parallax/camera/display_camera.h"
#include "parallax/core/error.h"
#include "parallax/display/depth_scaled_display.h"
#include "parallax/display/lenticular_presets.h"

namespace parallax {
namespace {

// A bare box as a bare mesh is placed: the display at its centre, width to be fitted.
Scene boxScene(const Vec3f& half) {
  Scene scene;
  const Bounds3f b{-half, half};
  scene.display.fit = b;
  scene.display.content = b;
  scene.display.width = 2 * half.x;
  return scene;
}

TEST(Framing, HarmonicFocusEqualisesTheVergenceErrors) {
  const double eye = 600, nearZ = 50, farZ = -100;
  const double z = harmonicFocusZ(nearZ, farZ, eye);
  const double focus = eye - z;
  EXPECT_NEAR(1 / (eye - nearZ) - 1 / focus, 1 / focus - 1 / (eye - farZ), 1e-15);
  EXPECT_NEAR(harmonicFocusZ(10, 10, eye), 10, 1e-12);
}

TEST(Framing, DepthFitPutsTheFocusAtTheHarmonicMeanAndTheDepthIntoTheBudget) {
  const DisplayDesign d = designDisplay(defaultDisplaySpec());
  const Scene scene = boxScene({1, 1, 1});  // a cube: deep once it fills the window
  const Framing f = frameForDisplay(scene, d);
  ASSERT_EQ(f.fit, DisplayFit::Depth);  // Auto without a given width
  ASSERT_TRUE(f.hasContent);
  EXPECT_TRUE(f.focusAuto);
  EXPECT_TRUE(f.budgetAuto);
  EXPECT_DOUBLE_EQ(f.budgetMm, d.depthOfFieldMm);
  // The cube, 2 units deep, spans 2 * scale mm, and z = 0 lies at the harmonic mean of the
  // distances of its near and far faces from the view-zone centre.
  const double D = d.viewDistanceMm;
  EXPECT_NEAR(f.nearMm - f.farMm, 2 * f.scaleMmPerUnit, 1e-6);
  EXPECT_NEAR(harmonicFocusZ(f.nearMm, f.farMm, D), 0.0, 1e-6);
  EXPECT_NEAR(2 / (1 / (D - f.nearMm) + 1 / (D - f.farMm)), D, 1e-6);
  // The far face is the deeper one, and lands exactly at -budget once flattened by g / g'.
  EXPECT_GT(-f.farMm, f.nearMm);
  EXPECT_NEAR(f.virtualGapMm, d.gapMm * -f.farMm / d.depthOfFieldMm, 1e-9);
  EXPECT_NEAR(f.shownFarMm, -d.depthOfFieldMm, 1e-9);
  EXPECT_NEAR(f.shownNearMm, f.nearMm * d.gapMm / f.virtualGapMm, 1e-12);
  EXPECT_LT(f.shownNearMm, d.depthOfFieldMm);
  EXPECT_TRUE(f.withinBudget());
  EXPECT_NEAR(f.design.virtualGapMm, f.virtualGapMm, 1e-12);
  EXPECT_NEAR(f.design.gapMm, d.gapMm, 1e-12);  // the physical display is unchanged
  // The content fills the window: its widest corner, seen from the eye, sits on the margin.
  const double halfWindow = 0.45 * std::min(d.frontWidthMm(), d.frontHeightMm());
  const double nearCorner = f.scaleMmPerUnit * 1 * D / (D - f.nearMm);
  EXPECT_NEAR(nearCorner, halfWindow, 1e-3 * halfWindow);
  // The placement moved the display plane onto the focus, toward the viewer by focus mm.
  EXPECT_NEAR(f.placement.center.z, f.focusMm / f.scaleMmPerUnit, 1e-5);
  EXPECT_NEAR(f.placement.width, d.frontWidthMm() / f.scaleMmPerUnit, 1e-4);
  EXPECT_FALSE(f.placement.fit);
  EXPECT_TRUE(depthWarning(f).empty());
  // Framing the framed scene again changes nothing.
  Scene again = scene;
  again.display = f.placement;
  const Framing g = frameForDisplay(again, f.design);
  EXPECT_NEAR(g.nearMm, f.nearMm, 1e-3);
  EXPECT_NEAR(g.placement.width, f.placement.width, 1e-5);
}

// A frustum (an RGB-D photo's mesh) is fitted by its corners, not by its box: the box's near
// corners, as wide as the far end, would limit the scale.
TEST(Framing, AContentHullIsFittedInsteadOfTheBoxCorners) {
  const DisplayDesign d = designDisplay(defaultDisplaySpec());
  Scene scene = boxScene({1, 1, 1});
  const Framing byBox = frameForDisplay(scene, d);
  // The frustum inside the cube: its far face (z = -1) is the cube's, its near face (z = 1) a
  // third as wide.
  for (float z : {-1.0f, 1.0f})
    for (float x : {-1.0f, 1.0f})
      for (float y : {-1.0f, 1.0f}) {
        const float s = z < 0 ? 1.0f : 1.0f / 3.0f;
        scene.display.contentHull.push_back({x * s, y * s, z});
      }
  const Framing byHull = frameForDisplay(scene, d);
  // Larger on the display (more mm per scene unit), the depth range still the box's.
  EXPECT_GT(byHull.scaleMmPerUnit, 1.1 * byBox.scaleMmPerUnit);
  EXPECT_NEAR((byHull.nearMm - byHull.farMm) / byHull.scaleMmPerUnit, 2.0, 1e-6);
  // The hull's widest corner seen from the eye still sits inside the window's margin.
  const double D = d.viewDistanceMm;
  const double halfWindow = 0.45 * std::min(d.frontWidthMm(), d.frontHeightMm());
  const double farCorner = byHull.scaleMmPerUnit * D / (D - byHull.farMm);
  const double nearCorner = byHull.scaleMmPerUnit / 3.0 * D / (D - byHull.nearMm);
  EXPECT_LE(std::max(farCorner, nearCorner), halfWindow * (1 + 1e-6));
}

TEST(Framing, AGivenBudgetAndFocusAreHonoured) {
  const DisplayDesign d = designDisplay(defaultDisplaySpec());
  Scene scene = boxScene({1, 1, 1});
  applyFramingOptions(scene.display, "depth", "0", "10");
  const Framing f = frameForDisplay(scene, d);
  EXPECT_FALSE(f.focusAuto);
  EXPECT_DOUBLE_EQ(f.focusMm, 0.0);
  EXPECT_DOUBLE_EQ(f.budgetMm, 10.0);
  // Focus 0 on a centred cube: near and far are equal and opposite, both land at +-10 mm.
  EXPECT_NEAR(f.nearMm, -f.farMm, 1e-9);
  EXPECT_NEAR(f.shownNearMm, 10.0, 1e-9);
  EXPECT_NEAR(f.shownFarMm, -10.0, 1e-9);
  EXPECT_NEAR(f.virtualGapMm, d.gapMm * f.nearMm / 10.0, 1e-9);
}

TEST(Framing, WindowFitIsTodaysFitAndWarns) {
  const DisplayDesign d = designDisplay(defaultDisplaySpec());
  Scene scene = boxScene({1, 1, 1});
  scene.display.fitMode = DisplayFit::Window;
  const Framing f = frameForDisplay(scene, d);
  EXPECT_FLOAT_EQ(f.placement.width, fitDisplayWidth(scene.display, displayWindow(d)));
  EXPECT_DOUBLE_EQ(f.virtualGapMm, d.gapMm);
  EXPECT_NEAR(f.nearMm, -f.farMm, 1e-9);
  const std::string warning = depthWarning(f);
  EXPECT_NE(warning.find("the display is sharp within ±27 mm (G4); {fit} depth compresses it"),
            std::string::npos)
      << warning;
}

TEST(Framing, ShallowContentKeepsItsDepthAndAGivenWidthIsKept) {
  const DisplayDesign d = designDisplay(defaultDisplaySpec());
  const Framing flat = frameForDisplay(boxScene({1, 1, 0.01f}), d);
  EXPECT_EQ(flat.fit, DisplayFit::Depth);
  EXPECT_DOUBLE_EQ(flat.virtualGapMm, d.gapMm);  // never below g
  EXPECT_FALSE(flat.design.camera.virtualGapMm);
  Scene given = boxScene({1, 1, 1});
  given.display.fit.reset();
  given.display.width = 5;
  const Framing asIs = frameForDisplay(given, d);
  EXPECT_EQ(asIs.fit, DisplayFit::None);
  EXPECT_FLOAT_EQ(asIs.placement.width, 5.0f);
  EXPECT_DOUBLE_EQ(asIs.focusMm, 0.0);
}

TEST(Framing, AVirtualGapFromTheDisplayFileIsKept) {
  BarrierCameraSettings camera;
  camera.virtualGapMm = 6.0;
  const DisplayDesign d = designDisplay(defaultDisplaySpec(), camera);
  const Framing f = frameForDisplay(boxScene({1, 1, 1}), d);
  EXPECT_TRUE(f.virtualGapFixed);
  EXPECT_DOUBLE_EQ(f.virtualGapMm, 6.0);
  EXPECT_NE(depthWarning(f).find("virtual/gap_mm"), std::string::npos);
}

TEST(Framing, OptionsAreChecked) {
  DisplayPlacement p;
  const auto refused = [&p](const std::string& fit, const std::string& focus,
                            const std::string& budget, const std::string& field,
                            const std::string& message) {
    try {
      applyFramingOptions(p, fit, focus, budget);
      ADD_FAILURE() << field << ": accepted";
    } catch (const RequestError& e) {
      EXPECT_EQ(e.field(), field);
      EXPECT_EQ(e.message(), message);
      EXPECT_EQ(std::string(e.what()), "request: " + field + ": " + message);
    }
  };
  refused("wide", "", "", "fit", "expected window, depth, camera, none or auto, got 'wide'");
  refused("", "near", "", "focus", "expected a number of millimetres or auto, got 'near'");
  refused("", "", "0", "depth_budget", "expected above 0 up to 1000 mm, got 0");
  refused("", "", "1e9", "depth_budget", "expected above 0 up to 1000 mm, got 1e9");
  refused("", "2e4", "", "focus", "expected from -10000 up to 10000 mm, got 2e4");
  applyFramingOptions(p, "none", "-12.5", "auto");
  EXPECT_EQ(p.fitMode, DisplayFit::None);
  EXPECT_DOUBLE_EQ(*p.focusMm, -12.5);
  EXPECT_FALSE(p.depthBudgetMm);
  applyFramingOptions(p, "", "auto", "");
  EXPECT_FALSE(p.focusMm);
}

TEST(VirtualEye, TheCentreIsItsOwnVirtualEyeAndOthersMoveInward) {
  DisplaySpec spec = defaultDisplaySpec();
  const DisplayDesign plain = designDisplay(spec);
  const Vec3d eye{200, 10, 600};
  const Vec3d same = virtualEye(plain, eye);
  EXPECT_DOUBLE_EQ(same.x, 200);
  BarrierCameraSettings camera;
  camera.virtualGapMm = 12.0;
  const DisplayDesign d = designDisplay(spec, camera);
  const Vec3d centre = virtualEye(d, {0, 0, 600});
  EXPECT_NEAR(centre.x, 0, 1e-12);
  EXPECT_NEAR(centre.z, 600, 1e-9);
  const double g = 3, gv = 12, D = 600;
  const Vec3d moved = virtualEye(d, eye);
  EXPECT_NEAR(moved.x, 200 * g * (gv + D) / (gv * (g + D)), 1e-9);
  EXPECT_NEAR(moved.z, 600, 1e-9);
  EXPECT_DOUBLE_EQ(moved.y, 10);
}

// The depth budget on a lenticular panel (docs/lenticular.md "Depth of field"): the content
// fitted into the lens's depth of field by a depth scale, a given focus and budget honoured, the
// window fit's warning, shallow content kept.
LenticularDesign portrait() {
  return designLenticular(*lenticularPreset("portrait"));
}

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
