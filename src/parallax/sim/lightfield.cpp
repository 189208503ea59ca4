#include "parallax/sim/lightfield.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "parallax/core/error.h"
#include "parallax/core/random.h"
#include "parallax/display/barrier_rays.h"

namespace parallax {
namespace {

constexpr uint64_t kSampleSeed = 0x5eedf1e1dull;  // fixed, so the plot is reproducible
const char* const kSource = "<light field>";
const char* const kBandFill = "#f5b041";
const char* const kEdgeStroke = "#c0392b";

// The film as the display's physical rays see it (display/barrier_rays.h, physicalBarrierRays):
// its size, and where its columns lie on the image layer.
struct Film {
  int width = 0, height = 0;
  double left = 0, columnWidth = 0;  // column c spans left + [c, c + 1) columnWidth (mm)
};

template <class Rays>
Film filmOf(const Rays& rays) {
  const double left = rays.imagePoint(0, 0).x;
  return {rays.filmWidth(), rays.filmHeight(), left, rays.imagePoint(1, 0).x - left};
}

// The film columns whose centres lie in [fromMm, toMm], of one row; n x n samples each.
struct Stretch {
  int row = 0, first = 0, last = -1, n = 0;
};

Stretch stretchOf(const Film& film, const LightFieldOptions& o) {
  Stretch s;
  s.row = o.row < 0 ? film.height / 2 : o.row;
  if (s.row >= film.height) throw InputError(kSource, "/row", "is off the panel");
  s.n = int(std::lround(std::sqrt(double(std::max(0, o.samplesPerPixel)))));
  if (o.samplesPerPixel < 0 || s.n * s.n != o.samplesPerPixel)
    throw InputError(kSource, "/samples_per_pixel", "must be a square n * n (or 0)");
  const double left = film.left, width = film.columnWidth;
  s.first = std::max(0, int(std::ceil((o.fromMm - left) / width - 0.5)));
  s.last = std::min(film.width - 1, int(std::floor((o.toMm - left) / width - 0.5)));
  if (!(o.fromMm < o.toMm) || s.first > s.last)
    throw InputError(kSource, "/from_mm", "the stretch holds no pixel centre of the panel");
  return s;
}

LightFieldRay toPoint(const BarrierRay& r, int column, int view) {
  return {r.imagePoint.x, r.aperturePoint.x, r.aperture, column, view};
}

std::string num(double value, int digits = 2) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

// A round tick step (1, 2 or 5 times a power of ten) giving at most maxTicks ticks.
double tickStep(double range, double maxTicks) {
  const double raw = range / std::max(1.0, maxTicks);
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * decade >= raw) return m * decade;
  return 10.0 * decade;
}

// Data (x, v) in mm to SVG pixels inside the plot rectangle; v grows upward.
struct Frame {
  double left, top, width, height, xMin, xMax, vMin, vMax;
  double px(double x) const { return left + (x - xMin) / (xMax - xMin) * width; }
  double py(double v) const { return top + (vMax - v) / (vMax - vMin) * height; }
};

std::string viewColour(int view, int views) {
  // Hues from red (view 0) to violet (the last view), distinct at both ends.
  return "hsl(" + num(280.0 * view / std::max(1, views - 1), 0) + ",75%,42%)";
}

// Tick marks and numbers along both axes (round steps at least ~60 px apart in x and ~40 px
// in v), and the axis titles.
void writeAxes(std::ostream& svg, const Frame& f, double heightPx) {
  const double bottom = f.top + f.height;
  const double xStep = tickStep(f.xMax - f.xMin, f.width / 60);
  const int xDigits = std::max(0, int(-std::floor(std::log10(xStep))));
  for (double k = std::ceil(f.xMin / xStep); k * xStep <= f.xMax; ++k)
    svg << "<line x1=\"" << num(f.px(k * xStep)) << "\" y1=\"" << num(bottom) << "\" x2=\""
        << num(f.px(k * xStep)) << "\" y2=\"" << num(bottom + 5) << "\" stroke=\"black\"/>\n"
        << "<text x=\"" << num(f.px(k * xStep)) << "\" y=\"" << num(bottom + 19)
        << "\" font-size=\"12\" text-anchor=\"middle\">" << num(k * xStep + 0.0, xDigits)
        << "</text>\n";
  const double vStep = tickStep(f.vMax - f.vMin, f.height / 40);
  const int vDigits = std::max(0, int(-std::floor(std::log10(vStep))));
  for (double k = std::ceil(f.vMin / vStep); k * vStep <= f.vMax; ++k)
    svg << "<line x1=\"" << num(f.left - 5) << "\" y1=\"" << num(f.py(k * vStep)) << "\" x2=\""
        << num(f.left) << "\" y2=\"" << num(f.py(k * vStep)) << "\" stroke=\"black\"/>\n"
        << "<text x=\"" << num(f.left - 8) << "\" y=\"" << num(f.py(k * vStep) + 4)
        << "\" font-size=\"12\" text-anchor=\"end\">" << num(k * vStep + 0.0, vDigits)
        << "</text>\n";
  svg << "<text class=\"axis-label\" x=\"" << num(f.left + 0.5 * f.width) << "\" y=\""
      << num(heightPx - 12) << "\" font-size=\"13\" text-anchor=\"middle\">"
      << "x: where the ray crosses the image layer (mm)</text>\n"
      << "<text class=\"axis-label\" transform=\"translate(16 " << num(f.top + 0.5 * f.height)
      << ") rotate(-90)\" font-size=\"13\" text-anchor=\"middle\">"
      << "v: where it crosses the mask layer (mm)</text>\n";
}

void writeLegend(std::ostream& svg, double x, double y, int views, int samplesPerPixel) {
  auto entry = [&](const std::string& swatch, const std::string& label) {
    svg << "<g transform=\"translate(" << num(x) << ' ' << num(y) << ")\">" << swatch
        << "<text x=\"30\" y=\"4\" font-size=\"12\">" << label << "</text></g>\n";
    y += 24;
  };
  entry("<rect x=\"0\" y=\"-6\" width=\"22\" height=\"12\" fill=\"" + std::string(kBandFill) +
            "\" fill-opacity=\"0.28\"/>",
        "rays reaching view zone");
  entry("<line x1=\"0\" y1=\"0\" x2=\"22\" y2=\"0\" stroke=\"" + std::string(kEdgeStroke) +
            "\" stroke-width=\"1.2\" stroke-dasharray=\"6 4\"/>",
        "ray through zone edge");
  entry("<rect x=\"0\" y=\"-6\" width=\"22\" height=\"12\" fill=\"#e9edf2\" stroke=\"#a9b4c0\"/>",
        "cell: pixel x slit period");
  std::string dots;
  for (int i = 0; i < 3; ++i)
    dots += "<circle cx=\"" + num(3 + 8 * i) + "\" cy=\"0\" r=\"3.5\" fill=\"" +
            viewColour(i * (views - 1) / 2, views) + "\"/>";
  entry(dots, "central ray, hue = view");
  if (samplesPerPixel > 0)
    entry("<circle cx=\"11\" cy=\"0\" r=\"1.6\" fill=\"#2c3e50\"/>",
          "sub-ray (" + std::to_string(samplesPerPixel) + " per cell)");
}

}  // namespace

std::vector<LightFieldRay> lightFieldRays(const DisplayDesign& design,
                                          const LightFieldOptions& options) {
  const auto gen = physicalBarrierRays(design);
  const Stretch s = stretchOf(filmOf(gen), options);
  std::vector<LightFieldRay> rays;
  for (int c = s.first; c <= s.last; ++c)
    rays.push_back(toPoint(gen.ray(c + 0.5, s.row + 0.5, 0.5, 0.5), c, gen.viewIndex(c, s.row)));
  return rays;
}

std::vector<LightFieldRay> lightFieldSamples(const DisplayDesign& design,
                                             const LightFieldOptions& options) {
  const auto gen = physicalBarrierRays(design, options.filter);
  const Stretch s = stretchOf(filmOf(gen), options);
  std::vector<LightFieldRay> samples;
  // Stratified jitter (docs/display-geometry.md, "Super-sampling"): the (x, f) cell in n x n
  // strata, x stratum i mod n, angular stratum i div n, spread by the filter. The row stays at its
  // centre: the plot is one row's slice.
  for (int c = s.first; c <= s.last; ++c)
    for (int i = 0; i < s.n * s.n; ++i) {
      Rng rng = Rng::forSample(uint32_t(c), uint32_t(s.row), uint32_t(i), kSampleSeed);
      const double filmX = c + ((i % s.n) + rng.uniform()) / s.n;
      const double u = ((i / s.n) + rng.uniform()) / s.n;
      samples.push_back(toPoint(gen.ray(filmX, s.row + 0.5, u, 0.5), c, gen.viewIndex(c, s.row)));
    }
  return samples;
}

std::string lightFieldSvg(const DisplayDesign& design, const LightFieldOptions& options) {
  const double W = options.widthPx, H = options.heightPx;
  const double marginLeft = 72, marginRight = 230, marginTop = 64, marginBottom = 56;
  if (!(W >= marginLeft + marginRight + 120) || !(H >= marginTop + marginBottom + 120))
    throw InputError(kSource, "/width_px", "the plot needs at least 422 x 360 pixels");
  const std::vector<LightFieldRay> rays = lightFieldRays(design, options);
  const std::vector<LightFieldRay> samples = lightFieldSamples(design, options);
  const auto gen = physicalBarrierRays(design);
  const Film film = filmOf(gen);
  const double pitch = film.columnWidth;
  const double Tv = design.slitPeriodMm, D = design.viewDistanceMm;

  // The band of rays reaching the view zone: for an eye point e at z = D the rays form the
  // line v = e + (x - e)(D - zM)/(D - zI); its edges are the lines of e = e_c -/+ S/2.
  const double slope = (D - design.maskLayerZ()) / (D - design.imageLayerZ());
  const double ec = design.spec.viewZoneCenterXMm, halfS = 0.5 * design.viewZoneWidthMm;
  const double edges[2] = {ec - halfS, ec + halfS};
  auto edge = [&](double e, double x) { return e + (x - e) * slope; };

  // Data range: the stretch and every cell, and the band across it.
  Frame f{marginLeft,
          marginTop,
          W - marginLeft - marginRight,
          H - marginTop - marginBottom,
          std::min(options.fromMm, rays.front().x - 0.5 * pitch),
          std::max(options.toMm, rays.back().x + 0.5 * pitch),
          1e300,
          -1e300};
  for (const LightFieldRay& r : rays) {
    f.vMin = std::min(f.vMin, r.v - 0.5 * Tv);
    f.vMax = std::max(f.vMax, r.v + 0.5 * Tv);
  }
  for (double e : edges)
    for (double x : {f.xMin, f.xMax}) {
      f.vMin = std::min(f.vMin, edge(e, x));
      f.vMax = std::max(f.vMax, edge(e, x));
    }
  const double pad = 0.03 * (f.vMax - f.vMin);
  f.vMin -= pad;
  f.vMax += pad;

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(W) << "\" height=\"" << num(H)
      << "\" viewBox=\"0 0 " << num(W) << ' ' << num(H)
      << "\" font-family=\"Helvetica, Arial, sans-serif\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<defs><clipPath id=\"plot\"><rect x=\"" << num(f.left) << "\" y=\"" << num(f.top)
      << "\" width=\"" << num(f.width) << "\" height=\"" << num(f.height)
      << "\"/></clipPath></defs>\n<g clip-path=\"url(#plot)\">\n";
  // Cells (one column wide in x, one slit period in v) under the translucent band.
  for (const LightFieldRay& r : rays)
    svg << "<rect class=\"cell\" x=\"" << num(f.px(r.x - 0.5 * pitch)) << "\" y=\""
        << num(f.py(r.v + 0.5 * Tv)) << "\" width=\"" << num(f.px(pitch) - f.px(0))
        << "\" height=\"" << num(f.py(r.v - 0.5 * Tv) - f.py(r.v + 0.5 * Tv))
        << "\" fill=\"#e9edf2\" stroke=\"#a9b4c0\" stroke-width=\"0.7\"/>\n";
  svg << "<polygon class=\"band\" points=\"";
  for (double x : {f.xMin, f.xMax})
    svg << num(f.px(x)) << ',' << num(f.py(edge(edges[0], x))) << ' ';
  for (double x : {f.xMax, f.xMin})
    svg << num(f.px(x)) << ',' << num(f.py(edge(edges[1], x))) << ' ';
  svg << "\" fill=\"" << kBandFill << "\" fill-opacity=\"0.28\"/>\n";
  for (double e : edges)
    svg << "<line class=\"edge\" x1=\"" << num(f.px(f.xMin)) << "\" y1=\""
        << num(f.py(edge(e, f.xMin))) << "\" x2=\"" << num(f.px(f.xMax)) << "\" y2=\""
        << num(f.py(edge(e, f.xMax))) << "\" stroke=\"" << kEdgeStroke
        << "\" stroke-width=\"1.2\" stroke-dasharray=\"6 4\"/>\n";
  for (const LightFieldRay& s : samples)
    svg << "<circle class=\"sample\" cx=\"" << num(f.px(s.x)) << "\" cy=\"" << num(f.py(s.v))
        << "\" r=\"1.3\" fill=\"#2c3e50\" fill-opacity=\"0.75\"/>\n";
  const int views = interleavedViewCount(design);
  const std::string dotRadius = num(std::clamp(0.3 * (f.px(pitch) - f.px(0)), 1.5, 4.5));
  for (const LightFieldRay& r : rays)
    svg << "<circle class=\"ray\" cx=\"" << num(f.px(r.x)) << "\" cy=\"" << num(f.py(r.v))
        << "\" r=\"" << dotRadius << "\" fill=\"" << viewColour(r.view, views)
        << "\" stroke=\"white\" stroke-width=\"0.8\"/>\n";
  svg << "</g>\n<rect x=\"" << num(f.left) << "\" y=\"" << num(f.top) << "\" width=\""
      << num(f.width) << "\" height=\"" << num(f.height) << "\" fill=\"none\" stroke=\"black\"/>\n";

  writeAxes(svg, f, H);
  // Title naming the display.
  char viewsText[32];
  std::snprintf(viewsText, sizeof viewsText, "%g", design.views);
  const bool back = design.spec.order == LayerOrder::BarrierBack;
  svg << "<text x=\"" << num(f.left) << "\" y=\"24\" font-size=\"16\" font-weight=\"bold\">"
      << "Ray space of a " << viewsText << "-view " << (back ? "barrier-back" : "barrier-front")
      << " display" << (gen.subpixelMode() ? " (subpixel rays)" : "") << "</text>\n"
      << "<text x=\"" << num(f.left) << "\" y=\"44\" font-size=\"12.5\" fill=\"#444\">Tx "
      << num(design.screenPeriodMm, 4) << " mm, Tv " << num(Tv, 4) << " mm, gap "
      << num(design.gapMm, 2) << " mm, D " << num(D, 0) << " mm; image row "
      << stretchOf(film, options).row << "</text>\n";
  writeLegend(svg, f.left + f.width + 18, f.top + 8, views, int(samples.size() / rays.size()));
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace parallax
