// Cross-talk of the simulated display against the display's geometry: where the rays of one
// view meet (from the display's rays), and how much light the anti-aliased mask raster and the
// diffuser spread out of an aperture's own view (a model derived below, computed here apart
// from the simulator).
#include "parallax/sim/crosstalk.h"

#include <gtest/gtest.h>

#include <cmath>

#include "parallax/display/display_model.h"
#include "parallax/display/mask.h"
#include "parallax/sim/sim_test_support.h"

namespace parallax {
namespace {

DisplayDesign wideDisplay(LayerOrder order, double viewZoneCentre = 0.0) {
  DisplaySpec s = defaultDisplaySpec();
  s.order = order;
  s.viewZoneCenterXMm = viewZoneCentre;
  // 44 groups: Tv = 9.045 mask pixels walks the slits twice across the mask pixel grid.
  s.imagePanel.width = s.maskPanel.width = 400;
  s.imagePanel.height = s.maskPanel.height = 8;  // slits: every row alike
  return designDisplay(s);
}

SimulationOptions fineInX(const DisplayDesign& d) {
  SimulationOptions o;
  o.width = 8 * d.spec.imagePanel.width;  // 8 samples across each panel pixel
  return o;
}

TEST(Crosstalk, DesignEyeIsWhereTheRaysOfAViewMeet) {
  for (LayerOrder order : kLayerOrders)
    for (double centre : {0.0, 40.0}) {
      const DisplayDesign d = wideDisplay(order, centre);
      const std::unique_ptr<DisplayModel> rays = makeBarrierDisplay(d);
      for (int v = 0; v < pixelViewCount(d); ++v) {
        // Two pixels of view v far apart; their rays (lines in x, z) cross at the eye.
        int first = -1, last = -1;
        for (int x = 0; x < d.spec.imagePanel.width; ++x)
          if (rays->viewIndex(x, 4) == v) (first < 0 ? first : last) = x;
        ASSERT_GE(last, first + 350);
        const DisplayRay a = rays->ray(first + 0.5, 4.5, 0.5, 0.5);
        const DisplayRay b = rays->ray(last + 0.5, 4.5, 0.5, 0.5);
        // x(z) = origin.x + (origin.z - z) * direction.x, since direction.z = -1.
        const double t = (b.origin.x - a.origin.x) / (a.direction.x - b.direction.x);
        const double z = a.origin.z - t, x = a.origin.x + t * a.direction.x;
        const Vec3d eye = designEyePosition(d, v);
        EXPECT_NEAR(eye.x, x, 1e-6);
        EXPECT_NEAR(eye.z, z, 1e-6);
        EXPECT_EQ(eye.y, d.spec.viewZoneHeightMm);
        if (order == LayerOrder::BarrierBack && centre == 0.0) {
          const double dx = d.spec.imagePanel.pitchMm;
          EXPECT_NEAR(eye.x, (v - 4) * dx * (1 + d.viewDistanceMm / d.gapMm), 1e-9);
        }
      }
    }
}

TEST(Crosstalk, ViewCodedImagesLightEachPixelOnce) {
  const DisplayDesign d = wideDisplay(LayerOrder::BarrierFront);
  Image sum(400, 8);
  for (int v = 0; v < 9; ++v) {
    const Image coded = viewCodedImage(d, v);
    int lit = 0;
    for (size_t i = 0; i < coded.pixels().size(); ++i) {
      sum.pixels()[i] += coded.pixels()[i];
      lit += coded.pixels()[i].x > 0;
    }
    EXPECT_GE(lit, 44 * 8) << v;  // one pixel per group and row
    EXPECT_LE(lit, 45 * 8) << v;
  }
  for (const Vec3f& p : sum.pixels()) ASSERT_EQ(p, Vec3f(1.0f));
}

// The model. Work on the mask layer. From the design eye of view v, the pixels of view v are
// seen through (barrier-front) or against (barrier-back) the mask in windows of width
// 2h = dx (D - z_M) / (D - z_I) centred on the aperture centres a_k (the rays of view v pass
// the pixel centres and the aperture centres). A slit of width w = duty * Tv is rasterised by
// area: the light of each point of the slit is spread evenly over the mask pixel (pitch p)
// holding it, and the diffuser then moves a pixel's light m pixels over with the Gaussian's
// mass over [m - 1/2, m + 1/2] (sigma in pixels, the simulator's blur). Light outside the window
// reaches the eye through other views' pixels: that fraction is the aperture's leak, and the
// cross-talk is the leak averaged over the slits.
//
// Worst case (no diffuser, w <= p <= 2h): a slit centred on a pixel edge is spread evenly
// over two pixels, and the window keeps h/p of each:
//
//     crosstalk_0 <= 1 - h/p                                       (about 1/2 here)
//
// Average: the slit period, 9.045 p, walks the slits across the pixel grid, so over the screen
// the slit centre's phase in its pixel is close to uniform. Then the pixel edge to the right of
// a slit point u from the centre (|u| <= w/2) is uniform in [u, u + p] and the one to its left
// in [u - p, u], so (for w <= 2h <= 2p and h + w/2 <= p) that point's light leaves the window
// with probability ((p - h + u)^2 + (p - h - u)^2) / (2 p^2). Averaging over u:
//
//     crosstalk_0 ~ (1 - h/p)^2 + (w/p)^2 / 12                     (about 1/3 here)
//
// for the default display's one-pixel slit (w ~ 2h ~ p), anti-aliased over two pixels. The
// diffuser leaves a pixel's light in place with probability q0 = erf(1 / (2 sqrt(2) sigma_px)),
// and light that stays in place inside the window still reaches the own view, so
//
//     crosstalk_sigma <= 1 - q0 h/p.
//
// An eye moved by e along x moves each window by e (z_M - z_I) / (D - z_I) on the mask.
double apertureLeak(double centre, double windowShift, double gridOrigin, double width,
                    double pitch, double halfWindow, double sigmaPx) {
  const double lo = centre - 0.5 * width, hi = centre + 0.5 * width;
  const double windowLo = centre + windowShift - halfWindow;
  const double windowHi = centre + windowShift + halfWindow;
  const int radius = sigmaPx > 0 ? int(std::ceil(5 * sigmaPx + 1)) : 0;
  double own = 0;
  for (int p = int(std::floor((lo - gridOrigin) / pitch));
       p <= int(std::floor((hi - gridOrigin) / pitch)); ++p) {
    const double left = gridOrigin + p * pitch;
    const double light = std::max(0.0, std::min(hi, left + pitch) - std::max(lo, left));
    for (int m = -radius; m <= radius; ++m) {
      const double moved = sigmaPx > 0 ? 0.5 * (std::erf((m + 0.5) / (sigmaPx * std::sqrt(2.0))) -
                                                std::erf((m - 0.5) / (sigmaPx * std::sqrt(2.0))))
                                       : 1.0;
      const double l = left + m * pitch;
      const double inWindow = std::max(0.0, std::min(windowHi, l + pitch) - std::max(windowLo, l));
      own += light * moved * inWindow / pitch;
    }
  }
  return 1.0 - own / width;
}

struct Model {
  double halfWindow, slitWidth, pitch;
  // The leak averaged over this display's own slits (those centred on the mask panel) and over
  // the given eye offsets along x.
  double predicted(const DisplayDesign& d, double sigmaPx,
                   const std::vector<double>& eyeOffsets) const {
    const MaskGeometry mask(d);
    const double origin = -0.5 * d.spec.maskPanel.widthMm();
    const double D = d.viewDistanceMm;
    const double windowPerEye = (d.maskLayerZ() - d.imageLayerZ()) / (D - d.imageLayerZ());
    double sum = 0;
    int n = 0;
    for (int64_t k = -60; k <= 60; ++k) {
      const double c = mask.apertureCenterX(k, 0.0);
      if (std::abs(c) > -origin) continue;
      for (double e : eyeOffsets) {
        sum += apertureLeak(c, e * windowPerEye, origin, slitWidth, pitch, halfWindow, sigmaPx);
        ++n;
      }
    }
    return sum / n;
  }
  double worstCase() const { return 1 - halfWindow / pitch; }
  double phaseAverage() const {
    const double a = 1 - halfWindow / pitch, b = slitWidth / pitch;
    return a * a + b * b / 12;
  }
};

Model modelOf(const DisplayDesign& d) {
  const double D = d.viewDistanceMm;
  return {0.5 * d.spec.imagePanel.pitchMm * (D - d.maskLayerZ()) / (D - d.imageLayerZ()),
          d.spec.mask.dutyCycle * d.slitPeriodMm, d.spec.maskPanel.pitchMm};
}

int cyclicDistance(int a, int b, int n) {
  const int d = std::abs(a - b) % n;
  return std::min(d, n - d);
}

TEST(Crosstalk, ModelMatchesItsClosedForms) {
  // Where the closed forms' conditions hold, the numeric leak averaged over a uniform phase
  // agrees with the average, and its maximum is the worst case.
  const Model m{0.5, 0.8, 1.0};
  double sum = 0, worst = 0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const double leak = apertureLeak((i + 0.5) / n, 0.0, 0.0, 0.8, 1.0, 0.5, 0.0);
    sum += leak, worst = std::max(worst, leak);
  }
  EXPECT_NEAR(sum / n, m.phaseAverage(), 1e-4);
  EXPECT_NEAR(worst, m.worstCase(), 1e-3);
}

TEST(Crosstalk, EachDesignEyeSeesItsOwnViewWithTheDerivedCrosstalk) {
  for (LayerOrder order : kLayerOrders) {
    const DisplayDesign d = wideDisplay(order);
    const Model model = modelOf(d);
    const double expected = model.predicted(d, 0.0, {0.0});
    for (int v = 0; v < 9; ++v) {
      const CrosstalkResult r =
          measureCrosstalk(d, maskLayerImage(d), fineInX(d), designEyePosition(d, v));
      EXPECT_EQ(r.ownView, v);
      EXPECT_LT(r.crosstalk, model.worstCase());
      // 44 slits cover the pixel phases about twice: near the phase average.
      EXPECT_NEAR(r.crosstalk, model.phaseAverage(), 0.02) << v;
      // This display's own slits, sampled 8 times per pixel: close to the model.
      EXPECT_NEAR(r.crosstalk, expected, 0.01) << v;
      // The leak goes to the neighbouring views (cyclically: view 0's left neighbour is the
      // last view of the group before); views two apart get almost nothing.
      const double own = r.lightPerView[size_t(v)];
      for (int other = 0; other < 9; ++other)
        if (cyclicDistance(v, other, 9) >= 2) {
          EXPECT_LT(r.lightPerView[size_t(other)], 0.01 * own) << v << " " << other;
        }
    }
  }
}

TEST(Crosstalk, GrowsWithTheDiffuserWithinTheDerivedBound) {
  const DisplayDesign d = wideDisplay(LayerOrder::BarrierBack);  // the diffuser blurs the mask
  const Model model = modelOf(d);
  const double pitch = d.spec.maskPanel.pitchMm;
  double previous = 0;
  for (double sigma : {0.0, 0.1, 0.25, 0.5}) {
    SimulationOptions o = fineInX(d);
    o.diffuserSigmaMm = sigma;
    const CrosstalkResult r = measureCrosstalk(d, maskLayerImage(d), o, designEyePosition(d, 4));
    EXPECT_EQ(r.ownView, 4);
    EXPECT_GT(r.crosstalk, previous + 0.02) << sigma;
    previous = r.crosstalk;
    EXPECT_NEAR(r.crosstalk, model.predicted(d, sigma / pitch, {0.0}), 0.01) << sigma;
    const double q0 = sigma > 0 ? std::erf(1.0 / (2 * std::sqrt(2.0) * sigma / pitch)) : 1.0;
    EXPECT_LT(r.crosstalk, 1 - q0 * model.halfWindow / pitch) << sigma;
  }
}

TEST(Crosstalk, TheViewZoneWrapsOutsideItself) {
  for (LayerOrder order : kLayerOrders) {
    const DisplayDesign d = wideDisplay(order);
    const int n = pixelViewCount(d);
    const auto ownView = [&](const Vec3d& eye) {
      return measureCrosstalk(d, maskLayerImage(d), fineInX(d), eye).ownView;
    };
    // Just beyond either end of the zone the eye sees the view from the zone's other end...
    EXPECT_EQ(ownView(designEyePosition(d, n)), 0);
    EXPECT_EQ(ownView(designEyePosition(d, -1)), n - 1);
    // ...and one zone width S over, the same view as at its design eye: the rear layer is then
    // seen shifted by exactly one period (S g / D = Tr).
    for (int v : {1, 6}) {
      Vec3d eye = designEyePosition(d, v);
      eye.x += (v == 1 ? 1 : -1) * d.viewZoneWidthMm;
      const CrosstalkResult r = measureCrosstalk(d, maskLayerImage(d), fineInX(d), eye);
      EXPECT_EQ(r.ownView, v);
      EXPECT_LT(r.crosstalk, modelOf(d).worstCase());
    }
  }
}

TEST(Crosstalk, APupilAveragesTheWindowsItMoves) {
  // Each pupil point moves the windows by its x offset times g / D; the cross-talk is the
  // model's leak averaged over the points. A 4 mm pupil moves them by at most 0.01 mm (the
  // views are 55 mm wide): hardly any change; a pupil one view wide mixes neighbouring views.
  const DisplayDesign d = wideDisplay(LayerOrder::BarrierBack);
  const Model model = modelOf(d);
  SimulationOptions o = fineInX(d);
  const Vec3d eye = designEyePosition(d, 3);
  const double pinhole = measureCrosstalk(d, maskLayerImage(d), o, eye).crosstalk;
  for (double diameter : {4.0, d.viewWidthMm}) {
    o.pupilDiameterMm = diameter;
    std::vector<double> offsets;
    const DisplaySimulator sim(d, {viewCodedImage(d, 3), maskLayerImage(d)}, o);
    for (const Vec3d& p : sim.pupilPoints(eye)) offsets.push_back(p.x - eye.x);
    const CrosstalkResult r = measureCrosstalk(d, maskLayerImage(d), o, eye);
    EXPECT_EQ(r.ownView, 3);
    EXPECT_NEAR(r.crosstalk, model.predicted(d, 0.0, offsets), 0.01) << diameter;
    if (diameter < 5) {
      EXPECT_NEAR(r.crosstalk, pinhole, 0.005);
    } else {
      EXPECT_GT(r.crosstalk, pinhole + 0.03);
    }
  }
}

}  // namespace
}  // namespace parallax
