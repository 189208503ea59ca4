// The simulator against the seeing model's geometry (../shared/reference/geometry.md, "Seeing
// the display") and against what a barrier display must look like: small panels for speed.
#include "parallax/sim/simulator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "parallax/core/error.h"
#include "parallax/core/random.h"
#include "parallax/display/barrier_rays.h"
#include "parallax/display/display_model.h"
#include "parallax/display/mask.h"
#include "parallax/image/metrics.h"
#include "parallax/sim/crosstalk.h"
#include "parallax/sim/sim_test_support.h"

namespace parallax {
namespace {

Image constantImage(const Panel& panel, float value) {
  return Image(panel.width, panel.height, Vec3f(value));
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / double(v.size());
}

double standardDeviation(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / double(v.size()));
}

TEST(Simulator, OneOpenRearPixelAppearsWhereTheEyesLineThroughItCrossesTheFront) {
  // Independent truth: project the rear pixel's centre from the eye onto z = 0,
  // F = E + (R - E) E.z / (E.z + g), and compare with the centroid of the lit output.
  for (LayerOrder order : kLayerOrders) {
    const DisplayDesign d = smallDisplay(order, 60, 40);
    const bool imageInFront = order == LayerOrder::BarrierBack;
    const Panel& rearPanel = imageInFront ? d.spec.maskPanel : d.spec.imagePanel;
    Image rear(rearPanel.width, rearPanel.height);
    const int column = 41, row = 9;
    rear.at(column, row) = Vec3f(1.0f);
    Image front = constantImage(imageInFront ? d.spec.imagePanel : d.spec.maskPanel, 1.0f);
    SimulationOptions o;
    o.width = 600, o.height = 400;  // ten output pixels per panel pixel
    o.normalise = false;
    const DisplaySimulator sim(
        d, imageInFront ? LayerImages{front, rear} : LayerImages{rear, front}, o);
    for (const Vec3d eye : {Vec3d{0, 0, 600}, Vec3d{-150, 40, 450}, Vec3d{90, -20, 900}}) {
      const Image v = sim.view(eye);
      double sx = 0, sy = 0, n = 0;
      for (int j = 0; j < v.height(); ++j)
        for (int i = 0; i < v.width(); ++i)
          if (v.at(i, j).x > 0.5f) sx += i + 0.5, sy += j + 0.5, n += 1;
      ASSERT_GT(n, 0);
      const double rx = -0.5 * rearPanel.widthMm() + (column + 0.5) * rearPanel.pitchMm;
      const double ry = 0.5 * rearPanel.heightMm() - (row + 0.5) * rearPanel.pitchMm;
      const double t = eye.z / (eye.z + d.gapMm);
      const double fx = eye.x + (rx - eye.x) * t, fy = eye.y + (ry - eye.y) * t;
      const double outPitch = 0.1 * d.spec.imagePanel.pitchMm;
      EXPECT_NEAR(-0.5 * d.frontWidthMm() + sx / n * outPitch, fx, outPitch);
      EXPECT_NEAR(0.5 * d.frontHeightMm() - sy / n * outPitch, fy, outPitch);
      // Its area is the rear pixel shrunk by E.z / (E.z + g), to within one output pixel.
      EXPECT_NEAR(std::sqrt(n) * outPitch, rearPanel.pitchMm * t, outPitch);
    }
  }
}

TEST(Simulator, WhiteImageBehindSlitsLooksUniformAtTheApertureRatio) {
  // From any eye, the front layer's width W maps to a rear interval W (E.z + g) / E.z; with a
  // white image every mask aperture in that interval passes its whole area (duty * Tv) of
  // light, so mean = duty up to the apertures the interval's two ends cut or that fall off
  // the rear panel: at most one aperture's light per end, so |mean / duty - 1| <= 2 / N for N
  // groups across the screen.
  for (LayerOrder order : kLayerOrders) {
    const DisplayDesign d = smallDisplay(order);
    const double duty = d.spec.mask.dutyCycle, groups = d.aperturesAcross;
    SimulationOptions o;
    o.normalise = false;
    // 8 x 4 output pixels of 4 x 4 samples per panel pixel: 32 samples across each pixel,
    // against the aliasing of nearest lookups (1 sample per pixel misses or hits a one-pixel
    // slit depending on where the eye is).
    o.width = 8 * d.spec.imagePanel.width;
    o.height = 4 * d.spec.imagePanel.height;
    o.samplesPerPixel = 16;
    const DisplaySimulator sim(d, {constantImage(d.spec.imagePanel, 1.0f), maskLayerImage(d)}, o);
    const double S = d.viewZoneWidthMm, D = d.viewDistanceMm;
    for (const Vec3d eye : {Vec3d{0, 0, D}, Vec3d{-0.45 * S, 0, D}, Vec3d{0.3 * S, 25, D},
                            Vec3d{60, -10, 0.8 * D}, Vec3d{-60, 10, 1.25 * D}}) {
      const Image v = sim.view(eye);
      EXPECT_NEAR(meanLuminance(v) / duty, 1.0, 2.0 / groups) << eye.x << " " << eye.z;
      // Uniform at the display's resolution: a box one seen slit period wide (Tv on the front
      // layer, or Tv E.z / (E.z + g) when the mask is behind) holds the light of exactly one
      // period of the mask, w = duty * Tv, if the raster were periodic. It is not quite: Tv is
      // 9.045 mask pixels (8.955 barrier-front), so each slit is anti-aliased 0.045 pixels
      // further along than the one before, which moves the light on either side of any cut by
      // at most 2 * 0.045 p (p the mask pitch ~ w): the boxed view stays within 9 % of duty,
      // plus the sampling (32 per pixel): 10 %.
      const double seenPeriodMm = order == LayerOrder::BarrierBack
                                      ? d.slitPeriodMm * eye.z / (eye.z + d.gapMm)
                                      : d.slitPeriodMm;
      const double outputPitch = d.frontWidthMm() / v.width();
      const Image boxed = boxFilterX(v, seenPeriodMm / outputPitch);
      std::vector<double> values;
      const int margin = int(std::ceil(2 * seenPeriodMm / outputPitch));
      for (int j = 4; j < v.height() - 4; ++j)  // one panel row from the top and bottom
        for (int i = margin; i < v.width() - margin; ++i)
          values.push_back(luminance(boxed.at(i, j)));
      EXPECT_LT(standardDeviation(values) / duty, 0.03) << eye.x << " " << eye.z;
      for (double x : values) ASSERT_NEAR(x / duty, 1.0, 0.1) << eye.x << " " << eye.z;
    }
  }
}

// Two code paths: the exact integral over each output pixel (the default) is the limit of
// point sampling. Random layers (every cell its own value), both layer orders, eyes off the
// axis, above, nearer and farther, a pupil, and an output size that does not divide the panel:
// 64 x 64 point samples per output pixel agree with the exact pieces to within what 64 samples
// across can resolve.
TEST(Simulator, ExactIntegralIsTheLimitOfPointSampling) {
  for (LayerOrder order : kLayerOrders) {
    const DisplayDesign d = smallDisplay(order, 60, 20);
    Image image(60, 20), mask(60, 20);
    Rng rng(11, 3);
    for (Vec3f& p : image.pixels()) p = Vec3f(rng.uniform(), rng.uniform(), rng.uniform());
    for (Vec3f& p : mask.pixels()) p = Vec3f(rng.uniform());
    SimulationOptions exact, sampled;
    exact.width = sampled.width = 45;
    exact.height = sampled.height = 17;
    sampled.samplesPerPixel = 64 * 64;
    for (const double pupil : {0.0, 4.0}) {
      exact.pupilDiameterMm = sampled.pupilDiameterMm = pupil;
      const DisplaySimulator a(d, {image, mask}, exact), b(d, {image, mask}, sampled);
      const double D = d.viewDistanceMm;
      for (const Vec3d eye : {Vec3d{0, 0, D}, Vec3d{-37.3, 12, D}, Vec3d{80, -20, 0.7 * D},
                              Vec3d{-150, 0, 1.6 * D}}) {
        const Image va = a.view(eye), vb = b.view(eye);
        double worst = 0, sum = 0;
        for (size_t i = 0; i < va.pixels().size(); ++i) {
          const double diff = std::fabs(va.pixels()[i].y - vb.pixels()[i].y);
          worst = std::max(worst, diff), sum += diff;
        }
        const double scale = meanLuminance(va);
        EXPECT_LT(worst, 0.05 * scale)
            << (order == LayerOrder::BarrierBack ? "barrier-back" : "barrier-front") << " eye "
            << eye.x;
        EXPECT_LT(sum / double(va.pixels().size()), 0.01 * scale)
            << (order == LayerOrder::BarrierBack ? "barrier-back" : "barrier-front");
      }
    }
  }
}

// An eye a nanometre from the display spreads each output pixel over millions of rear cells:
// the exact pieces give way to 64 x 64 point samples there (the same picture), not a hang.
TEST(Simulator, AnEyeTouchingTheDisplayIsPointSampled) {
  const DisplayDesign d = smallDisplay(LayerOrder::BarrierBack, 60, 20);
  Image image(60, 20, Vec3f(0.5f));
  SimulationOptions exact, sampled;
  sampled.samplesPerPixel = 64 * 64;
  const Vec3d eye{3, 1, 1e-6};
  const Image a = DisplaySimulator(d, {image, maskLayerImage(d)}, exact).view(eye);
  const Image b = DisplaySimulator(d, {image, maskLayerImage(d)}, sampled).view(eye);
  EXPECT_EQ(a.pixels(), b.pixels());
}

TEST(Simulator, NormalisedWhiteLooksWhite) {
  const DisplayDesign d = smallDisplay(LayerOrder::BarrierBack);
  SimulationOptions o;
  o.samplesPerPixel = 16;
  const DisplaySimulator sim(d, {constantImage(d.spec.imagePanel, 1.0f), maskLayerImage(d)}, o);
  EXPECT_NEAR(sim.maskMeanTransmittance(), d.spec.mask.dutyCycle, 0.01 * d.spec.mask.dutyCycle);
  EXPECT_NEAR(meanLuminance(sim.view({0, 0, d.viewDistanceMm})), 1.0, 2.0 / d.aperturesAcross);
}

TEST(Simulator, ContentInTheAperturePlaneLooksTheSameFromEveryEye) {
  // A texture lying in the aperture plane is seen through aperture k in the same colour from
  // every eye: every pixel of group k shows it. Build that image layer directly, one random
  // colour per group, and check that from every eye in the inner view zone the light that
  // reaches the eye near aperture k (the span of one seen period around it) has that colour:
  // the view divided by the view of a white image, integrated over the span, is the texture
  // sampled at the group. The eyes stay within S/4 of the zone's centre so that no aperture's
  // anti-aliased light (about 2 mask pixels of 9) crosses into the neighbouring group.
  for (LayerOrder order : kLayerOrders) {
    const DisplayDesign d = smallDisplay(order);
    const auto rays = physicalBarrierRays(d);  // the design has no virtual gap
    const Panel& panel = d.spec.imagePanel;
    std::map<int64_t, Vec3f> texture;
    Image image(panel.width, panel.height);
    for (int y = 0; y < panel.height; ++y)
      for (int x = 0; x < panel.width; ++x) {
        const int64_t group = rays.ray(x + 0.5, y + 0.5, 0.5, 0.5).aperture;
        if (!texture.count(group)) {
          Rng rng(uint64_t(group + 1000), 7);
          texture[group] = Vec3f(rng.uniform(), rng.uniform(), rng.uniform());
        }
        image.at(x, y) = texture[group];
      }
    SimulationOptions o;
    o.width = 4 * panel.width;
    o.samplesPerPixel = 4;
    const DisplaySimulator textured(d, {image, maskLayerImage(d)}, o);
    const DisplaySimulator white(d, {constantImage(panel, 1.0f), maskLayerImage(d)}, o);
    const MaskGeometry mask(d);
    const double S = d.viewZoneWidthMm, D = d.viewDistanceMm;
    for (const Vec3d eye :
         {Vec3d{0, 0, D}, Vec3d{-0.25 * S, 10, D}, Vec3d{0.2 * S, -10, D}, Vec3d{30, 0, 0.9 * D}}) {
      const Image seen = textured.view(eye), lit = white.view(eye);
      // Group of each output column: the aperture whose light it carries, found from the eye:
      // the nearest aperture to the column's line from the eye, on the mask layer.
      std::map<int64_t, std::pair<Vec3f, Vec3f>> sums;
      const double pitch = d.frontWidthMm() / seen.width();
      for (int i = 0; i < seen.width(); ++i) {
        const double fx = -0.5 * d.frontWidthMm() + (i + 0.5) * pitch;
        const double mx = eye.x + (fx - eye.x) * (eye.z - d.maskLayerZ()) / eye.z;
        const int64_t k = mask.nearestAperture(mx, 0.0);
        for (int j = 0; j < seen.height(); ++j) {
          sums[k].first += seen.at(i, j);
          sums[k].second += lit.at(i, j);
        }
      }
      float fullest = 0;
      for (const auto& entry : sums) fullest = std::max(fullest, entry.second.second.x);
      int checked = 0;
      for (const auto& [k, sum] : sums) {
        if (!texture.count(k) || sum.second.x < 0.5f * fullest) continue;  // cut by an edge
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(sum.first[c] / sum.second[c], texture[k][c], 1e-4) << k << " " << eye.x;
        ++checked;
      }
      EXPECT_GE(checked, int(d.aperturesAcross) - 2);
    }
  }
}

TEST(Simulator, ColourFiltersMakeFringesButKeepTheMean) {
  // Through both layers' R, G, B stripes a sample passes light only where the front stripe and
  // the rear stripe it is seen through carry the same channel. Across the screen the two stripe
  // grids slide past each other (the rear one is seen magnified by (D + g) / D, and the slit
  // period 9.045 mask pixels walks each aperture across the stripes by 0.135 stripes per
  // period), so each channel passes 1/9 of the unfiltered light on average (1/3 per layer,
  // which `normalise` divides out); each aperture's light, though, has its own colour.
  const DisplayDesign d = smallDisplay(LayerOrder::BarrierBack, 396, 12);  // ~2 moire cycles
  SimulationOptions o;
  o.width = 6 * d.spec.imagePanel.width;  // two output pixels per stripe
  const auto viewWith = [&](bool filters) {
    o.colourFilters = filters;
    const DisplaySimulator sim(d, {constantImage(d.spec.imagePanel, 1.0f), maskLayerImage(d)}, o);
    return sim.view({0, 0, d.viewDistanceMm});
  };
  const Image plain = viewWith(false), filtered = viewWith(true);
  for (const Vec3f& p : plain.pixels()) ASSERT_TRUE(p.x == p.y && p.y == p.z);
  Vec3f total(0.0f);
  for (const Vec3f& p : filtered.pixels()) total += p / float(filtered.pixels().size());
  // Over two whole moire cycles (22.2 slits each: 44 slits here) each channel's share averages
  // to 1/3 per layer, up to the screen's ends (2 slits of 44, as in the test above: 4.5 %) and
  // the unfinished 1 % of a cycle.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(total[c], 1.0, 0.06) << c;
  // Box-filtered over one group (9 pixels = 54 output pixels), the unfiltered view is grey and
  // the filtered one shows hues: its chroma spread (max - min channel over the mean) varies
  // along the screen.
  const Image groups = boxFilterX(filtered, 54.0);
  double lowest = 1e9, highest = 0;
  for (int i = 60; i < groups.width() - 60; ++i) {
    const Vec3f p = groups.at(i, 6);
    const double chroma =
        (maxComponent(p) - std::min(p.x, std::min(p.y, p.z))) / ((p.x + p.y + p.z) / 3.0);
    lowest = std::min(lowest, chroma), highest = std::max(highest, chroma);
  }
  EXPECT_GT(highest, 0.5);
  EXPECT_LT(lowest, 0.5 * highest);
}

TEST(Simulator, PupilAveragesThePinholeViewsAtItsSamplePoints) {
  const DisplayDesign d = smallDisplay(LayerOrder::BarrierBack);
  SimulationOptions o;
  o.samplesPerPixel = 4;
  o.pupilDiameterMm = 5.0;
  o.pupilSamples = 12;
  const LayerImages layers{viewCodedImage(d, 4), maskLayerImage(d)};
  const DisplaySimulator pupil(d, layers, o);
  o.pupilDiameterMm = 0.0;
  const DisplaySimulator pinhole(d, layers, o);
  const Vec3d eye{20, 5, 620};
  const std::vector<Vec3d> points = pupil.pupilPoints(eye);
  ASSERT_EQ(points.size(), 12u);
  Image expected(pupil.outputWidth(), pupil.outputHeight());
  for (const Vec3d& p : points) {
    // The points fill a disk of the pupil's radius in the plane of the eye.
    EXPECT_EQ(p.z, eye.z);
    EXPECT_LE(std::hypot(p.x - eye.x, p.y - eye.y), 2.5);
    const Image v = pinhole.view(p);
    for (size_t i = 0; i < v.pixels().size(); ++i)
      expected.pixels()[i] += v.pixels()[i] / float(points.size());
  }
  const Image averaged = pupil.view(eye);
  for (size_t i = 0; i < averaged.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(averaged.pixels()[i][c], expected.pixels()[i][c], 1e-5) << i;
}

TEST(Simulator, ThreadCountDoesNotChangeTheView) {
  const DisplayDesign d = smallDisplay(LayerOrder::BarrierFront, 180, 37);
  SimulationOptions o;
  o.samplesPerPixel = 4;
  o.pupilDiameterMm = 3.0;
  o.pupilSamples = 5;
  o.diffuserSigmaMm = 0.2;
  o.colourFilters = true;
  Image image(180, 37);
  Rng rng(3);
  for (Vec3f& p : image.pixels()) p = Vec3f(rng.uniform(), rng.uniform(), rng.uniform());
  std::vector<Image> views;
  for (int threads : {1, 2, 3, 7}) {
    o.threads = threads;
    views.push_back(DisplaySimulator(d, {image, maskLayerImage(d)}, o).view({-40, 12, 580}));
  }
  for (const Image& v : views) EXPECT_EQ(v.pixels(), views.front().pixels());
}

TEST(Simulator, RejectsLayersOfTheWrongSize) {
  const DisplayDesign d = smallDisplay(LayerOrder::BarrierBack);
  const auto message = [&](const Image& image, const Image& mask) {
    try {
      DisplaySimulator(d, {image, mask}, {});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const Image good(180, 24), wrong(179, 24);
  EXPECT_NE(message(wrong, good).find("/image_layer"), std::string::npos);
  EXPECT_NE(message(wrong, good).find("179x24"), std::string::npos);
  EXPECT_NE(message(good, wrong).find("/mask_layer"), std::string::npos);
  SimulationOptions o;
  o.samplesPerPixel = 3;
  EXPECT_THROW(DisplaySimulator(d, {good, good}, o), InputError);
  const DisplaySimulator sim(d, {good, good}, {});
  EXPECT_THROW(sim.view({0, 0, -10}), InputError);
}

}  // namespace
}  // namespace parallax
