// The lenticular panel as a DisplayModel: its central rays are the published formula's, its views
// the quilt's slices of the view fraction, its eyes evenly in angle across the cone.
#include <gtest/gtest.h>

#include <cmath>

#include "parallax/display/display_model.h"
#include "parallax/display/lenticular_test_support.h"

namespace parallax {
namespace {

TEST(LenticularDisplay, CentralRaysAreTheFormulasAndViewsSliceTheFraction) {
  const LenticularDesign d = smallLenticularDesign();
  const std::unique_ptr<DisplayModel> display = makeLenticularDisplay(d, {ViewFilterKind::None, 1});
  EXPECT_EQ(display->viewCount(), d.quiltViews);
  for (int x = 0; x < 180; x += 13)
    for (int c = 0; c < 3; ++c) {
      const int column = 3 * x + c, row = 37;
      const LenticularRay expected = lenticularRay(d, x + 0.5, row + 0.5, c);
      const DisplayRay got = display->ray(column + 0.9, row + 0.2, 0.1, 0.7);  // none: central
      EXPECT_NEAR(got.origin.x, expected.origin.x, 1e-9);
      EXPECT_NEAR(got.direction.x, expected.direction.x, 1e-12);
      const double f = viewFraction(d, x, row, c);
      EXPECT_EQ(display->viewIndex(column, row), int(std::floor(f * d.quiltViews)));
    }
  // Eyes evenly in angle: the view's eye sits at the angle of its fraction's centre.
  for (int v : {0, 10, 47}) {
    const Vec3d eye = display->viewPosition(v);
    EXPECT_NEAR(std::atan2(eye.x, eye.z), viewAngle(d, (v + 0.5) / d.quiltViews), 1e-12);
  }
  EXPECT_FALSE(display->hasMaskLayer());
  EXPECT_TRUE(display->maskLayer().empty());
}

}  // namespace
}  // namespace parallax
