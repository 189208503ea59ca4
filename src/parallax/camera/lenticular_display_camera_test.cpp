// The display camera over a lenticular display model (display/display_model.h).
#include <gtest/gtest.h>

#include <cmath>

#include "parallax/camera/display_camera.h"
#include "parallax/display/lenticular_test_support.h"

namespace parallax {
namespace {

LenticularDesign smallDesign() {
  return smallLenticularDesign();
}

DisplayPlacement obliquePlacement() {
  DisplayPlacement p;
  p.center = {1, 2, -3};
  p.normal = normalize(Vec3f{0.3f, 0.1f, 1.0f});
  p.up = {0, 1, 0};
  p.width = 2.5f;
  return p;
}

TEST(LenticularDisplayCamera, OneColumnPerSubpixel) {
  const DisplayCamera camera(makeLenticularDisplay(smallDesign()), DisplayPlacement{});
  EXPECT_EQ(camera.width(), 540);
  EXPECT_EQ(camera.height(), 120);
  EXPECT_EQ(camera.display().channelOfColumn(3 * 17 + 2), 2);
  EXPECT_EQ(camera.packetShape().columns, 4);  // no shared aperture: neighbouring pixels
}

TEST(LenticularDisplayCamera, RayPassesThroughItsSubpixelInItsViewDirection) {
  const LenticularDesign d = smallDesign();
  const DisplayPlacement placement = obliquePlacement();
  // The central ray (filter none): from the subpixel itself.
  const DisplayCamera camera(makeLenticularDisplay(d, {ViewFilterKind::None, 1.0}), placement);
  const Transform world = worldFromDisplay(placement, displayWindow(d));
  const Transform display = world.inverse();
  for (const auto& [x, y, channel] : {std::array<int, 3>{0, 0, 0}, std::array<int, 3>{90, 60, 1},
                                      std::array<int, 3>{179, 119, 2}}) {
    const Ray ray = camera.generateRay({3.0f * x + channel + 0.5f, y + 0.5f, 0.5f, 0.5f});
    // In display mm the ray starts on the eye line (y = 0, z = D) and meets the panel (z = 0)
    // at the subpixel's point.
    const Vec3f o = display.point(ray.origin), dir = display.vector(ray.direction);
    EXPECT_NEAR(o.z, d.viewDistanceMm, 1e-3);
    EXPECT_NEAR(o.y, 0.0, 1e-3);
    const float t = -o.z / dir.z;
    const Vec3d p = subpixelPointMm(d, x + 0.5, y + 0.5, channel);
    EXPECT_NEAR(o.x + t * dir.x, p.x, 1e-3);
    EXPECT_NEAR(o.y + t * dir.y, p.y, 1e-3);
    // Horizontally it heads for its view's eye point on the design line (converging bundles).
    EXPECT_NEAR(o.x, d.viewDistanceMm * std::tan(viewAngle(d, viewFraction(d, x, y, channel))),
                1e-3);
  }
}

TEST(LenticularDisplayCamera, SamplesSpreadOverTheSubpixel) {
  const LenticularDesign d = smallDesign();
  const DisplayCamera camera(makeLenticularDisplay(d), DisplayPlacement{});
  const Transform display = worldFromDisplay(DisplayPlacement{}, displayWindow(d)).inverse();
  const Vec3d centre = subpixelPointMm(d, 40.5, 30.5, 1);
  // The second angular sample at the subpixel's own view: no move across its lens.
  const float own = float(viewFraction(d, 40, 30, 1));
  for (const float within : {0.01f, 0.99f}) {
    const Ray ray = camera.generateRay({3 * 40 + 1 + within, 30.5f, 0.5f, own});
    const Vec3f o = display.point(ray.origin), dir = display.vector(ray.direction);
    const float hitX = o.x - o.z / dir.z * dir.x;
    // Within a third of a pixel (the subpixel's width) of its centre, on the sample's side.
    EXPECT_LT(std::fabs(hitX - centre.x), d.pixelPitchMm / 6 + 1e-4);
    EXPECT_GT(std::fabs(hitX - centre.x), d.pixelPitchMm / 7);
    EXPECT_EQ(hitX > centre.x, within > 0.5f);
  }
}

// The prefilter's footprint: a sub-ray's view is the subpixel's own, plus its position across
// the subpixel (shaped by the filter, scaled by its width) times the part (1 - W) of the
// subpixel's span delta (a third of the channel view step) that a spot W subpixels wide leaves
// unblended: none for the default W = 1. The angular sample u moves the ray across its lens,
// never its view; none is the central ray for any sample, and period spreads over the whole
// lens period.
TEST(LenticularDisplayCamera, FilterFootprintMatchesItsFormula) {
  const LenticularDesign base = smallDesign();
  const Transform display = worldFromDisplay(DisplayPlacement{}, displayWindow(base)).inverse();
  const double step = channelViewStep(base);
  EXPECT_NEAR(step, base.pitchPx / 180.0, 1e-12);
  EXPECT_NEAR(step, 1.0 / base.pixelsPerLens, 1e-12);
  const int x = 70, y = 40, channel = 2;
  const double own = viewFraction(base, x, y, channel);
  const double delta = step / 3;
  // viewFractionOfAngle is not wrapped: compare with the own view modulo whole lens periods.
  const auto offset = [&](double view) { return view - own - std::round(view - own); };
  for (const double spot : {0.0, 0.25, 1.0, 3.0}) {
    LensOptics optics = base.optics;
    optics.spotWidthSubpixels = spot;
    const LenticularDesign d = withOptics(base, optics);
    // The view a ray carries: where it crosses the design line (bundles converging at D), as a
    // view fraction (not wrapped).
    const auto viewOf = [&](const DisplayCamera& camera, float within, float u) {
      const Ray ray = camera.generateRay({3.0f * x + channel + within, y + 0.3f, u, 0.5f});
      const Vec3f o = display.point(ray.origin), dir = display.vector(ray.direction);
      const double t = (d.viewDistanceMm - o.z) / dir.z;
      return viewFractionOfAngle(d, std::atan((o.x + t * dir.x) / d.viewDistanceMm));
    };
    const DisplayCamera box(makeLenticularDisplay(d, {ViewFilterKind::View, 1.0}), {});
    const DisplayCamera wideBox(makeLenticularDisplay(d, {ViewFilterKind::View, 2.5}), {});
    const DisplayCamera tent(makeLenticularDisplay(d, {ViewFilterKind::Tent, 1.0}), {});
    const DisplayCamera none(makeLenticularDisplay(d, {ViewFilterKind::None, 1.0}), {});
    const DisplayCamera period(makeLenticularDisplay(d, {ViewFilterKind::Period, 1.0}), {});
    const double unblended = std::max(0.0, 1 - spot) * delta;
    for (const float within : {0.05f, 0.25f, 0.5f, 0.95f})
      for (const float u : {0.0f, 0.25f, 0.5f, 0.75f, 0.999f}) {
        const double across = within - 0.5;
        EXPECT_NEAR(offset(viewOf(box, within, u)), across * unblended, 1e-5) << spot;
        EXPECT_NEAR(offset(viewOf(wideBox, within, u)), 2.5 * across * unblended, 1e-5) << spot;
        // The tent's inverse CDF: half of its rays within 1 - sqrt(1/2) of a width of the centre.
        const double t =
            within < 0.5 ? std::sqrt(2.0 * within) - 1 : 1 - std::sqrt(2.0 * (1 - within));
        EXPECT_NEAR(offset(viewOf(tent, within, u)), t * unblended, 1e-5) << spot;
        EXPECT_NEAR(offset(viewOf(none, within, u)), 0.0, 1e-5) << spot;
        // (+-1/2 are the same place in the period.)
        EXPECT_NEAR(std::remainder(offset(viewOf(period, within, u)) - (u - 0.5), 1.0), 0.0, 1e-5)
            << spot;
      }
  }
  const LenticularDesign d = base;
  const DisplayCamera box(makeLenticularDisplay(d, {ViewFilterKind::View, 1.0}), {});
  const DisplayCamera none(makeLenticularDisplay(d, {ViewFilterKind::None, 1.0}), {});
  // The position still moves over the subpixel's area.
  const auto hitX = [&](const DisplayCamera& camera, float within) {
    const Ray ray = camera.generateRay({3.0f * x + channel + within, y + 0.5f, 0.9f, 0.5f});
    const Vec3f o = display.point(ray.origin), dir = display.vector(ray.direction);
    return o.x - o.z / dir.z * dir.x;
  };
  EXPECT_NEAR(hitX(box, 0.99f) - hitX(box, 0.01f), 0.98 * d.pixelPitchMm / 3, 1e-3);
  EXPECT_NEAR(hitX(none, 0.99f) - hitX(none, 0.01f), 0.0, 1e-6);
}

// A second code path: the one-axis window camera placed where a subpixel's ray starts casts the
// same ray through that subpixel's point.
TEST(LenticularDisplayCamera, AgreesWithTheWindowCameraAtTheRaysEye) {
  const LenticularDesign d = smallDesign();
  const DisplayPlacement placement = obliquePlacement();
  const DisplayCamera camera(makeLenticularDisplay(d), placement);
  const std::unique_ptr<DisplayModel> window = makeLenticularDisplay(d);
  EXPECT_NEAR(window->window().widthMm, d.widthMm, 1e-9);
  EXPECT_NEAR(window->window().heightMm, d.heightMm, 1e-9);
  const int x = 37, y = 81, channel = 2;
  const LenticularRay r = lenticularRay(d, x + 0.5, y + 0.5, channel);
  const WindowCamera eye(r.origin, *window, placement, d.calibration.screenW, d.calibration.screenH,
                         true);
  const float filmX = float((r.panelPoint.x + 0.5 * d.widthMm) / d.pixelPitchMm);
  const float filmY = float((0.5 * d.heightMm - r.panelPoint.y) / d.pixelPitchMm);
  const Ray expected = eye.generateRay({filmX, filmY, 0.5f, 0.5f});
  // The second angular sample at the subpixel's own view: from the subpixel's point.
  const Ray got =
      camera.generateRay({3.0f * x + channel + 0.5f, y + 0.5f, 0.5f, float(r.viewFraction)});
  const Vec3f gotDirection = normalize(got.direction),
              expectedDirection = normalize(expected.direction);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(got.origin[k], expected.origin[k], 1e-4);
    EXPECT_NEAR(gotDirection[k], expectedDirection[k], 1e-6);  // both run origin -> panel
  }
}

}  // namespace
}  // namespace parallax
