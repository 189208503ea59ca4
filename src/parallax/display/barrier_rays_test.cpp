// The display camera's rays against the geometry they must satisfy (docs/display-geometry.md).
#include "parallax/display/barrier_rays.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace parallax {
namespace {

DisplaySpec narrowDisplay(LayerOrder order = LayerOrder::BarrierBack) {
  DisplaySpec s = defaultDisplaySpec();
  s.order = order;
  s.imagePanel.width = s.maskPanel.width = 180;
  s.imagePanel.height = s.maskPanel.height = 40;
  s.viewZoneHeightMm = 30.0;
  return s;
}

// x and y where a ray crosses the plane z.
std::pair<double, double> at(const BarrierRay& r, double z) {
  const double t = (z - r.origin.z) / r.direction.z;
  return {r.origin.x + t * r.direction.x, r.origin.y + t * r.direction.y};
}

TEST(BarrierRays, CentralRayPassesPixelApertureAndViewLine) {
  for (LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
    const BarrierRayGenerator gen(designDisplay(narrowDisplay(order)));
    const DisplayDesign& d = gen.design();
    for (int y = 0; y < 40; y += 7)
      for (int x = 0; x < 180; ++x) {
        const BarrierRay r = gen.ray(x + 0.5, y + 0.5, 0.5, 0.5);
        const Vec3d pixel = gen.imagePoint(x + 0.5, y + 0.5);
        const auto [ix, iy] = at(r, d.imageLayerZ());
        EXPECT_NEAR(ix, pixel.x, 1e-9);
        EXPECT_NEAR(iy, pixel.y, 1e-9);
        const auto [mx, my] = at(r, d.maskLayerZ());
        EXPECT_NEAR(mx, gen.mask().apertureCenterX(r.aperture, my), 1e-9);
        const auto [vx, vy] = at(r, d.viewDistanceMm);
        EXPECT_NEAR(vy, d.spec.viewZoneHeightMm, 1e-9);
        // The serving aperture is the one whose group holds the pixel.
        EXPECT_LE(std::abs(vx - d.spec.viewZoneCenterXMm), 0.5 * d.viewZoneWidthMm + 1e-6);
      }
  }
}

TEST(BarrierRays, RaysOfOneViewMeetInOnePointAtTheDesignDistance) {
  for (LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
    const BarrierRayGenerator gen(designDisplay(narrowDisplay(order)));
    const DisplayDesign& d = gen.design();
    // Group boundaries fall on pixel boundaries: the view index is the offset in the group.
    std::map<int64_t, std::vector<double>> hitsByView;
    for (int x = 0; x < 180; ++x) {
      const BarrierRay r = gen.ray(x + 0.5, 20.5, 0.5, 0.5);
      const Vec3d pixel = gen.imagePoint(x + 0.5, 20.5);
      const double groupCentre =
          d.spec.viewZoneCenterXMm + (gen.mask().apertureCenterX(r.aperture, 0) - 0) *
                                         (d.viewDistanceMm - d.imageLayerZ()) /
                                         (d.viewDistanceMm - d.maskLayerZ());
      const double offset = (pixel.x - groupCentre) / d.spec.imagePanel.pitchMm;
      const int64_t view = std::llround(offset + 4.0);
      ASSERT_NEAR(offset + 4.0, double(view), 1e-6) << "pixel centres must sit on view slots";
      EXPECT_EQ(gen.viewIndex(x, 20), int(view)) << x;
      hitsByView[view].push_back(at(r, d.viewDistanceMm).first);
    }
    ASSERT_EQ(hitsByView.size(), 9u);
    double previous = NAN;
    for (const auto& [view, xs] : hitsByView) {
      for (double x : xs) EXPECT_NEAR(x, xs.front(), 1e-6) << "view " << view;
      EXPECT_NEAR(gen.viewPosition(int(view)).x, xs.front(), 1e-6) << "view " << view;
      // Neighbouring views are one view width S / N apart (G2).
      if (!std::isnan(previous)) {
        EXPECT_NEAR(std::abs(xs.front() - previous), d.viewWidthMm, 1e-6);
      }
      previous = xs.front();
    }
  }
}

TEST(BarrierRays, ViewIndexCountsPixelsAcrossTheGroup) {
  const BarrierRayGenerator gen(designDisplay(narrowDisplay()));
  // Every view index covers one pixel per group, and within a group the index rises by one
  // per pixel: the same pixels whose rays meet in one point at D (the test above).
  std::map<int, int> count;
  int previous = -1;
  for (int x = 0; x < 180; ++x) {
    const int view = gen.viewIndex(x, 20);
    ASSERT_GE(view, 0);
    ASSERT_LT(view, 9);
    if (previous >= 0 && view != 0) {
      EXPECT_EQ(view, previous + 1) << x;
    }
    previous = view;
    ++count[view];
  }
  ASSERT_EQ(count.size(), 9u);
  for (const auto& [view, n] : count) EXPECT_NEAR(n, 20, 1) << view;
}

TEST(BarrierRays, InfiniteVirtualDistanceGivesParallelViews) {
  BarrierCameraSettings camera;
  camera.virtualDistanceMm = kInfinity;
  const BarrierRayGenerator gen(designDisplay(narrowDisplay(), camera));
  std::map<int, std::pair<double, double>> slopes;
  for (int x = 0; x < 180; ++x) {
    const BarrierRay r = gen.ray(x + 0.5, 3.5, 0.5, 0.5);
    EXPECT_EQ(r.direction.y, 0.0);
    const auto [it, inserted] = slopes.emplace(x % 9, std::pair{r.direction.x, r.direction.y});
    if (!inserted) {
      EXPECT_NEAR(r.direction.x, it->second.first, 1e-12) << x;
    }
  }
}

TEST(BarrierRays, VirtualGapScalesTheAngularSpan) {
  const auto span = [](double virtualGap) {
    BarrierCameraSettings camera;
    camera.virtualGapMm = virtualGap;
    camera.virtualDistanceMm = kInfinity;  // parallel views: the span is a slope difference
    const BarrierRayGenerator gen(designDisplay(narrowDisplay(), camera));
    double lo = 1e9, hi = -1e9;
    for (int x = 81; x < 90; ++x) {  // one whole group
      const double slope = gen.ray(x + 0.5, 20.5, 0.5, 0.5).direction.x;
      lo = std::min(lo, slope), hi = std::max(hi, slope);
    }
    return hi - lo;
  };
  EXPECT_NEAR(span(6.0) / span(3.0), 3.0 / 6.0, 1e-9);
  EXPECT_NEAR(span(1.5) / span(3.0), 2.0, 1e-9);
}

TEST(BarrierRays, SubpixelsGetTheirOwnRays) {
  DisplaySpec s = narrowDisplay();
  s.imagePanel.subpixels = SubpixelOrder::BGR;
  BarrierCameraSettings camera;
  camera.subpixelRays = true;
  const BarrierRayGenerator gen(designDisplay(s, camera));
  EXPECT_EQ(gen.filmWidth(), 540);
  EXPECT_EQ(gen.channelOfColumn(0), 2);
  EXPECT_EQ(gen.channelOfColumn(4), 1);
  // Subpixels of one pixel sit dx/3 apart, so (within a group) their rays differ in slope by
  // (dx / 3) / g: three times the views.
  const double dx = s.imagePanel.pitchMm;
  const BarrierRay a = gen.ray(3 * 85 + 0.5, 10.5, 0.5, 0.5),
                   b = gen.ray(3 * 85 + 1.5, 10.5, 0.5, 0.5);
  ASSERT_EQ(a.aperture, b.aperture);
  EXPECT_NEAR(std::abs(a.direction.x - b.direction.x), dx / 3.0 / s.gapMm, 1e-12);
  EXPECT_NEAR(b.imagePoint.x - a.imagePoint.x, dx / 3.0, 1e-12);
}

TEST(BarrierRays, PeriodFilterSpansOnePixelAndOneApertureCell) {
  const BarrierRayGenerator gen(designDisplay(narrowDisplay()), {ViewFilterKind::Period, 1.0});
  const DisplayDesign& d = gen.design();
  const BarrierRay lo = gen.ray(85.0, 20.5, 0.0, 0.5), hi = gen.ray(85.999999, 20.5, 1.0, 0.5);
  EXPECT_EQ(lo.aperture, hi.aperture);
  EXPECT_NEAR(hi.imagePoint.x - lo.imagePoint.x, d.spec.imagePanel.pitchMm, 1e-5);
  EXPECT_NEAR(hi.aperturePoint.x - lo.aperturePoint.x, d.slitPeriodMm, 1e-5);
}

// The view filters' footprint (docs/display-geometry.md, "Super-sampling"): every sub-ray of a
// pixel passes through its sample point and, at the virtual distance D', through an eye inside
// the pixel's own view window: the window dx (D' - z_M') / g' wide around the central ray's
// eye (D' infinite: slopes within dx / (2 g') of the central slope). Checked for both layer
// orders, a virtual gap and distance, subpixel rays, pinholes (in y too) and slanted slits.
struct FootprintCase {
  const char* name;
  DisplaySpec spec;
  BarrierCameraSettings camera = {};
};

std::vector<FootprintCase> footprintCases() {
  std::vector<FootprintCase> cases;
  cases.push_back({"barrier-back", narrowDisplay()});
  cases.push_back({"barrier-front", narrowDisplay(LayerOrder::BarrierFront)});
  BarrierCameraSettings virtualGap;
  virtualGap.virtualGapMm = 5.0, virtualGap.virtualDistanceMm = 900.0;
  cases.push_back({"virtual g' and D'", narrowDisplay(), virtualGap});
  BarrierCameraSettings orthographic;
  orthographic.virtualDistanceMm = kInfinity;
  cases.push_back({"D' infinite", narrowDisplay(), orthographic});
  BarrierCameraSettings subpixels;
  subpixels.subpixelRays = true;
  cases.push_back({"subpixels", narrowDisplay(), subpixels});
  DisplaySpec pinholes = narrowDisplay();
  pinholes.mask.kind = MaskKind::Pinholes;
  pinholes.mask.verticalPeriodPx = 9.045;
  cases.push_back({"pinholes", pinholes});
  DisplaySpec slanted = narrowDisplay();
  slanted.mask.kind = MaskKind::Slanted;
  slanted.mask.slantDegrees = 12.0;
  cases.push_back({"slanted", slanted});
  return cases;
}

TEST(BarrierRays, ViewFilterRaysMeetAnEyeInsideThePixelsViewWindow) {
  for (const FootprintCase& c : footprintCases()) {
    const DisplayDesign d = designDisplay(c.spec, c.camera);
    for (const ViewFilter filter :
         {ViewFilter{ViewFilterKind::View, 1.0}, ViewFilter{ViewFilterKind::Tent, 1.0},
          ViewFilter{ViewFilterKind::Gaussian, 1.5}, ViewFilter{ViewFilterKind::View, 0.5}}) {
      const BarrierRayGenerator gen(d, filter);
      const double halfSupport = ViewFilterWarp(filter).halfSupport();
      const bool subpixel = c.camera.subpixelRays, pinhole = gen.mask().isPinholeGrid();
      const double dx = d.spec.imagePanel.pitchMm / (subpixel ? 3.0 : 1.0);
      const double dy = d.spec.imagePanel.pitchMm;
      const double g = d.virtualGapMm;
      const bool front = d.spec.order == LayerOrder::BarrierBack;  // image layer in front
      const double zI = front ? 0.0 : -g, zM = front ? -g : 0.0;
      const double D = d.virtualDistanceMm;
      for (int x = 40; x < gen.filmWidth() - 40; x += 13)
        for (int y : {3, 17, 31}) {
          const BarrierRay centre = gen.ray(x + 0.5, y + 0.5, 0.5, 0.5);
          double lo = 1e9, hi = -1e9, loY = 1e9, hiY = -1e9;
          for (double fx : {0.0, 0.3, 0.999})
            for (double fy : {0.0, 0.6, 0.999})
              for (double u : {0.0, 0.2, 0.5, 0.8, 0.9999}) {
                const double v = pinhole ? u : 0.5;
                const BarrierRay r = gen.ray(x + fx, y + fy, u, v);
                ASSERT_EQ(r.aperture, centre.aperture) << c.name;
                // A slanted slit lies elsewhere at another height: the central ray of the
                // sample's own height is the reference there.
                const BarrierRay central = gen.ray(x + 0.5, y + fy, 0.5, 0.5);
                // Through its sample point on the image layer.
                const Vec3d sample = gen.imagePoint(x + fx, y + fy);
                const auto [ix, iy] = at(r, zI);
                ASSERT_NEAR(ix, sample.x, 1e-9) << c.name;
                ASSERT_NEAR(iy, sample.y, 1e-9) << c.name;
                // Offset from the central ray, as an eye offset at D' (or a slope offset).
                double offset, offsetY = 0;
                if (std::isinf(D)) {
                  offset = (r.direction.x - central.direction.x) * g / dx;
                  offsetY = (r.direction.y - central.direction.y) * g / dy;
                } else {
                  const double window = dx * (D - zM) / g;  // one view's window at D'
                  offset = (at(r, D).first - at(central, D).first) / window;
                  offsetY = (at(r, D).second - at(central, D).second) / (dy * (D - zM) / g);
                }
                lo = std::min(lo, offset), hi = std::max(hi, offset);
                loY = std::min(loY, offsetY), hiY = std::max(hiY, offsetY);
              }
          const std::string where =
              std::string(c.name) + " " + viewFilterName(filter.kind) + " x " + std::to_string(x);
          EXPECT_LE(hi, halfSupport + 1e-6) << where;
          EXPECT_GE(lo, -halfSupport - 1e-6) << where;
          EXPECT_GT(hi - lo, 0.9 * halfSupport) << where;  // and it does spread
          if (pinhole) {
            EXPECT_LE(std::max(hiY, -loY), halfSupport + 1e-6) << where;
          }
        }
    }
  }
}

TEST(BarrierRays, NoneFilterTracesOnlyTheCentralRay) {
  const BarrierRayGenerator gen(designDisplay(narrowDisplay()), {ViewFilterKind::None, 1.0});
  const BarrierRay centre = gen.ray(85.5, 20.5, 0.5, 0.5);
  const BarrierRay other = gen.ray(85.1, 20.9, 0.05, 0.95);
  EXPECT_EQ(other.direction.x, centre.direction.x);
  EXPECT_EQ(other.origin.x, centre.origin.x);
  EXPECT_EQ(other.origin.y, centre.origin.y);
}

TEST(BarrierRays, PinholesGiveFullParallax) {
  DisplaySpec s = narrowDisplay();
  s.mask.kind = MaskKind::Pinholes;
  s.mask.verticalPeriodPx = 9.045;
  const BarrierRayGenerator gen(designDisplay(s));
  const DisplayDesign& d = gen.design();
  for (int y = 0; y < 40; y += 3)
    for (int x = 0; x < 180; x += 5) {
      const BarrierRay r = gen.ray(x + 0.5, y + 0.5, 0.5, 0.5);
      const auto [mx, my] = at(r, d.maskLayerZ());
      EXPECT_NEAR(mx, gen.mask().apertureCenterX(r.aperture, my), 1e-9);
      EXPECT_NEAR(my, gen.mask().rowCenterY(r.apertureRow), 1e-9);
    }
}

TEST(BarrierRays, SlantedSlitsAreFollowedAtTheCrossingHeight) {
  DisplaySpec s = narrowDisplay();
  s.mask.kind = MaskKind::Slanted;
  s.mask.slantDegrees = 18.0;
  const BarrierRayGenerator gen(designDisplay(s));
  for (double fy : {0.1, 0.5, 0.9})
    for (int x = 0; x < 180; x += 7) {
      const BarrierRay r = gen.ray(x + 0.5, 12 + fy, 0.5, 0.5);
      const auto [mx, my] = at(r, gen.design().maskLayerZ());
      EXPECT_NEAR(mx, gen.mask().apertureCenterX(r.aperture, my), 1e-9);
    }
}

}  // namespace
}  // namespace parallax

namespace parallax {
namespace {

TEST(BarrierRays, SixteenAtOnceMatchOneByOne) {
  for (MaskKind kind : {MaskKind::Slits, MaskKind::Slanted})
    for (ViewFilterKind filter : {ViewFilterKind::View, ViewFilterKind::Tent,
                                  ViewFilterKind::Period, ViewFilterKind::None}) {
      DisplaySpec s = defaultDisplaySpec();
      s.imagePanel.width = s.maskPanel.width = 180;
      s.imagePanel.height = s.maskPanel.height = 40;
      s.mask.kind = kind;
      s.mask.slantDegrees = 10;
      s.viewZoneHeightMm = 20;
      BarrierCameraSettings camera;
      camera.virtualGapMm = 4.0;
      const BarrierRayGenerator gen(designDisplay(s, camera), {filter, 1.0});
      alignas(64) float x[16], y[16], u[16], v[16];
      for (int i = 0; i < 16; ++i)
        x[i] = 11.3f * float(i) + 0.37f, y[i] = 2.1f * float(i) + 0.5f, u[i] = 0.06f * float(i),
        v[i] = 0.5f;
      alignas(64) double origin[3][16], direction[3][16];
      gen.rays16(x, y, u, v, origin, direction);
      for (int i = 0; i < 16; ++i) {
        const BarrierRay r = gen.ray(x[i], y[i], u[i], v[i]);
        EXPECT_NEAR(origin[0][i], r.origin.x, 1e-9);
        EXPECT_NEAR(origin[1][i], r.origin.y, 1e-9);
        EXPECT_NEAR(origin[2][i], r.origin.z, 1e-9);
        EXPECT_NEAR(direction[0][i], r.direction.x, 1e-12);
        EXPECT_NEAR(direction[1][i], r.direction.y, 1e-12);
      }
    }
}

}  // namespace
}  // namespace parallax
