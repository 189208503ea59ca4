// The ray-space plot against the display geometry it draws (docs/display-geometry.md): pixel
// centres and aperture centres computed here from the panel and the mask, the G1/G2 relations,
// and a small tag scanner for the SVG text.
#include "parallax/sim/lightfield.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/display/mask.h"

namespace parallax {
namespace {

DisplayDesign design(LayerOrder order = LayerOrder::BarrierBack) {
  DisplaySpec spec = defaultDisplaySpec();
  spec.order = order;
  spec.viewZoneCenterXMm = 40.0;  // off-centre, so e_c is not silently 0
  return designDisplay(spec);
}

// Centres of the image pixels in [from, to], from the panel alone.
std::vector<double> pixelCentres(const DisplayDesign& d, double from, double to) {
  std::vector<double> centres;
  const Panel& p = d.spec.imagePanel;
  for (int i = 0; i < p.width; ++i) {
    const double x = -0.5 * p.widthMm() + (i + 0.5) * p.pitchMm;
    if (x >= from && x <= to) centres.push_back(x);
  }
  return centres;
}

// Eye-to-mask projection scale (D - zM) / (D - zI).
double slope(const DisplayDesign& d) {
  return (d.viewDistanceMm - d.maskLayerZ()) / (d.viewDistanceMm - d.imageLayerZ());
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Scans every <...> tag: opening tags must be closed in order, <.../> closes itself.
bool tagsBalanced(const std::string& svg) {
  std::vector<std::string> open;
  for (size_t at = svg.find('<'); at != std::string::npos; at = svg.find('<', at + 1)) {
    const size_t end = svg.find('>', at);
    if (end == std::string::npos) return false;
    const std::string tag = svg.substr(at + 1, end - at - 1);
    const bool closing = tag.front() == '/';
    const std::string name = tag.substr(closing, tag.find_first_of(" /", closing) - closing);
    if (closing) {
      if (open.empty() || open.back() != name) return false;
      open.pop_back();
    } else if (tag.back() != '/') {
      open.push_back(name);
    }
  }
  return open.empty();
}

TEST(LightField, SvgIsAStandaloneDocumentWithOneDotPerPixel) {
  for (LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
    const DisplayDesign d = design(order);
    LightFieldOptions o;
    o.fromMm = -7.3;
    o.toMm = 4.1;
    const std::string svg = lightFieldSvg(d, o);
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_EQ(svg.substr(svg.find_last_not_of(" \n") - 5, 6), "</svg>");
    EXPECT_NE(svg.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
    EXPECT_NE(svg.find("viewBox=\"0 0 900.00 600.00\""), std::string::npos);
    EXPECT_TRUE(tagsBalanced(svg));
    EXPECT_EQ(count(svg, "class=\"ray\""), pixelCentres(d, o.fromMm, o.toMm).size());
    EXPECT_EQ(count(svg, "class=\"cell\""), pixelCentres(d, o.fromMm, o.toMm).size());
    EXPECT_EQ(count(svg, "class=\"sample\""), 0u);
    EXPECT_EQ(count(svg, "class=\"band\""), 1u);
    EXPECT_NE(svg.find("9-view"), std::string::npos);
  }
  EXPECT_FALSE(tagsBalanced("<svg><g></svg></g>"));  // the scanner can fail
}

TEST(LightField, SubpixelRaysPlotOneDotPerSubpixelColumn) {
  BarrierCameraSettings camera;
  camera.subpixelRays = true;
  const DisplayDesign d = designDisplay(defaultDisplaySpec(), camera);
  const std::vector<LightFieldRay> rays = lightFieldRays(d, {});
  // Centres of the R, G, B thirds of each pixel, in [-5, 5] (the default stretch).
  std::vector<double> thirds;
  for (double pixel : pixelCentres(d, -6, 6))
    for (int c = -1; c <= 1; ++c) {
      const double x = pixel + c * d.spec.imagePanel.pitchMm / 3;
      if (x >= -5 && x <= 5) thirds.push_back(x);
    }
  ASSERT_EQ(rays.size(), thirds.size());
  for (size_t i = 0; i < rays.size(); ++i) EXPECT_NEAR(rays[i].x, thirds[i], 1e-9);
  EXPECT_TRUE(tagsBalanced(lightFieldSvg(d, {})));
}

TEST(LightField, AxisLabelsAreInMillimetres) {
  const std::string svg = lightFieldSvg(design(), {});
  ASSERT_EQ(count(svg, "class=\"axis-label\""), 2u);
  for (size_t at = svg.find("class=\"axis-label\""); at != std::string::npos;
       at = svg.find("class=\"axis-label\"", at + 1)) {
    const size_t textStart = svg.find('>', at) + 1;
    EXPECT_NE(svg.substr(textStart, svg.find("</text>", at) - textStart).find("(mm)"),
              std::string::npos);
  }
}

TEST(LightField, SubRayCountIsPixelsTimesSamples) {
  LightFieldOptions o;
  o.samplesPerPixel = 9;
  const DisplayDesign d = design();
  const std::string svg = lightFieldSvg(d, o);
  EXPECT_EQ(count(svg, "class=\"sample\""), 9 * pixelCentres(d, o.fromMm, o.toMm).size());
  EXPECT_TRUE(tagsBalanced(svg));
}

TEST(LightField, CentralRaysJoinPixelCentreAndServingApertureCentre) {
  for (LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
    const DisplayDesign d = design(order);
    const MaskGeometry mask(d);
    LightFieldOptions o;
    o.fromMm = -12;
    o.toMm = 15;
    o.row = 100;
    const std::vector<LightFieldRay> rays = lightFieldRays(d, o);
    const std::vector<double> centres = pixelCentres(d, o.fromMm, o.toMm);
    ASSERT_EQ(rays.size(), centres.size());
    const double s = slope(d), ec = d.spec.viewZoneCenterXMm, ye = d.spec.viewZoneHeightMm;
    const double y = 0.5 * d.spec.imagePanel.heightMm() - 100.5 * d.spec.imagePanel.pitchMm;
    const double maskY = ye + (y - ye) * s;
    for (size_t i = 0; i < rays.size(); ++i) {
      EXPECT_NEAR(rays[i].x, centres[i], 1e-9);
      // The serving aperture is the one nearest the pixel seen from the view-zone centre ...
      const double seen = ec + (centres[i] - ec) * s;
      EXPECT_EQ(rays[i].aperture, mask.nearestAperture(seen, maskY));
      EXPECT_NEAR(rays[i].v, mask.apertureCenterX(rays[i].aperture, maskY), 1e-9);
      // ... so the ray lies in the band between the lines of rays through the view-zone
      // edges, v = e + (x - e) s for e = e_c -/+ S/2.
      const double halfS = 0.5 * d.viewZoneWidthMm;
      const double a = ec - halfS + (centres[i] - ec + halfS) * s;
      const double b = ec + halfS + (centres[i] - ec - halfS) * s;
      EXPECT_GE(rays[i].v, std::min(a, b) - 1e-9);
      EXPECT_LE(rays[i].v, std::max(a, b) + 1e-9);
      // The band is one slit period tall: S |1 - s| is S g / D = Tr (G2) for barrier-back and
      // S g / (D + g) = Tr D / (D + g) = Tf (G1) for barrier-front; either way Tv.
      EXPECT_NEAR(std::abs(a - b), d.slitPeriodMm, 1e-9);
    }
  }
}

TEST(LightField, RaysOfOneSlitShareVAndRaysOfOneViewMeetAtOneEyePoint) {
  for (LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
    const DisplayDesign d = design(order);
    LightFieldOptions o;
    o.fromMm = -30;
    o.toMm = 30;
    const std::vector<LightFieldRay> rays = lightFieldRays(d, o);
    std::map<int64_t, std::vector<LightFieldRay>> bySlit;
    std::map<int, std::vector<LightFieldRay>> byView;
    for (const LightFieldRay& r : rays) {
      bySlit[r.aperture].push_back(r);
      byView[r.view].push_back(r);
    }
    EXPECT_GE(bySlit.size(), 20u);
    EXPECT_EQ(byView.size(), 9u);
    for (const auto& [slit, group] : bySlit)
      for (const LightFieldRay& r : group) EXPECT_NEAR(r.v, group.front().v, 1e-12);  // slits
    const double s = slope(d);
    for (const auto& [view, line] : byView) {
      ASSERT_GE(line.size(), 20u);
      // Collinear with slope (D - zM) / (D - zI), and that line's fixed point v = x is the
      // eye point at z = D where all the view's rays meet.
      for (const LightFieldRay& r : line)
        EXPECT_NEAR((r.v - line.front().v) - s * (r.x - line.front().x), 0.0, 1e-9);
      const double eye = (line.front().v - s * line.front().x) / (1 - s);
      // The doc's design eye point of view j: e_c + delta (z_M - D) / (z_M - z_I), delta the
      // column's offset (j + 1/2 - views/2) dx from its group centre.
      const double delta = (view + 0.5 - 0.5 * d.views) * d.spec.imagePanel.pitchMm;
      EXPECT_NEAR(eye,
                  d.spec.viewZoneCenterXMm + delta * (d.maskLayerZ() - d.viewDistanceMm) /
                                                 (d.maskLayerZ() - d.imageLayerZ()),
                  1e-6);
      EXPECT_LE(std::abs(eye - d.spec.viewZoneCenterXMm), 0.5 * d.viewZoneWidthMm);
    }
  }
}

TEST(LightField, SamplesAreStratifiedJitteredInTheirCell) {
  const DisplayDesign d = design();
  LightFieldOptions o;
  o.samplesPerPixel = 16;
  o.filter.kind = ViewFilterKind::Period;  // the whole-period cell: strata of Tv in v
  const std::vector<LightFieldRay> rays = lightFieldRays(d, o);
  const std::vector<LightFieldRay> samples = lightFieldSamples(d, o);
  ASSERT_EQ(samples.size(), 16 * rays.size());
  const double dx = d.spec.imagePanel.pitchMm, Tv = d.slitPeriodMm;
  double offCentre = 0;
  for (size_t k = 0; k < samples.size(); ++k) {
    const LightFieldRay& cell = rays[k / 16];
    const int i = int(k % 16);
    EXPECT_EQ(samples[k].aperture, cell.aperture);
    const double xIn = (samples[k].x - (cell.x - 0.5 * dx)) / dx * 4;  // in x strata
    const double vIn = (samples[k].v - (cell.v - 0.5 * Tv)) / Tv * 4;  // in aperture strata
    EXPECT_GE(xIn, i % 4 - 1e-9);
    EXPECT_LE(xIn, i % 4 + 1 + 1e-9);
    EXPECT_GE(vIn, i / 4 - 1e-9);
    EXPECT_LE(vIn, i / 4 + 1 + 1e-9);
    offCentre += std::abs(xIn - std::floor(xIn) - 0.5);
  }
  EXPECT_GT(offCentre / samples.size(), 0.1);  // jittered, not at the stratum centres
  // The one-view box: v within a quarter of s' dx of its stratum, around the aperture centre
  // shifted with the sample (v = v_c + s' ((x - x_c) + f dx), f in [-1/2, 1/2]).
  o.filter.kind = ViewFilterKind::View;
  const std::vector<LightFieldRay> view = lightFieldSamples(d, o);
  const double s = (d.viewDistanceMm - d.maskLayerZ()) / (d.viewDistanceMm - d.imageLayerZ());
  for (size_t k = 0; k < view.size(); ++k) {
    const LightFieldRay& cell = rays[k / 16];
    const int i = int(k % 16);
    const double f = (view[k].v - cell.v) / (s * dx) - (view[k].x - cell.x) / dx;
    EXPECT_GE(f, -0.5 + 0.25 * (i / 4) - 1e-9);
    EXPECT_LE(f, -0.25 + 0.25 * (i / 4) + 1e-9);
  }
  const std::vector<LightFieldRay> again = lightFieldSamples(d, o);
  for (size_t k = 0; k < samples.size(); ++k) EXPECT_EQ(samples[k].x, again[k].x);
}

TEST(LightField, RejectsBadOptions) {
  const DisplayDesign d = design();
  LightFieldOptions o;
  o.samplesPerPixel = 8;
  EXPECT_THROW(lightFieldRays(d, o), InputError);
  o = {};
  o.fromMm = 400;  // off the 527 mm wide panel's right half
  o.toMm = 500;
  EXPECT_THROW(lightFieldRays(d, o), InputError);
  o = {};
  o.row = 1080;
  EXPECT_THROW(lightFieldSvg(d, o), InputError);
  o = {};
  o.widthPx = 200;
  EXPECT_THROW(lightFieldSvg(d, o), InputError);
}

}  // namespace
}  // namespace parallax
