#include "parallax/sim/calibration.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "parallax/core/error.h"
#include "parallax/display/display_model.h"
#include "parallax/image/contact_sheet.h"
#include "parallax/image/metrics.h"
#include "parallax/sim/simulator.h"

namespace parallax {

namespace {

// A setting out of range, named by its field (calibration.h, kCalibrationSettings); the command
// line maps fields to its own option names.
InputError optionError(const std::string& field, const std::string& message) {
  return InputError(kCalibrationSettings, "/" + field, message);
}

std::string fixed(double value, int decimals) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

// G1 with D > 0: the rear period exceeds the front one (the slit period is the rear one
// behind the image, barrier-back, and the front one in front of it, barrier-front).
bool rearExceedsFront(const DisplaySpec& d, double screenPeriodPx, double slitPeriodPx) {
  const double screen = screenPeriodPx * d.imagePanel.pitchMm;
  const double slit = slitPeriodPx * d.maskPanel.pitchMm;
  return d.order == LayerOrder::BarrierBack ? slit > screen : screen > slit;
}

// A slit period asked for (or its default): at least 2 pixels, and G1.
void checkSlitPeriod(const DisplaySpec& d, int screenPeriodPx, double slitPeriodPx,
                     const std::string& option) {
  if (!(slitPeriodPx >= 2.0) || !std::isfinite(slitPeriodPx))
    throw optionError(option, "the slit period must be at least 2 mask pixels (got " +
                                  fixed(slitPeriodPx, 4) + ")");
  if (rearExceedsFront(d, screenPeriodPx, slitPeriodPx)) return;
  const double screenInMaskPx = screenPeriodPx * d.imagePanel.pitchMm / d.maskPanel.pitchMm;
  const std::string relation = d.order == LayerOrder::BarrierBack
                                   ? "barrier-back: the slit period must exceed"
                                   : "barrier-front: the slit period must be shorter than";
  throw optionError(option, "G1 needs the rear period to exceed the front period; " + relation +
                                " the screen period, " + fixed(screenInMaskPx, 4) +
                                " mask px (got " + fixed(slitPeriodPx, 4) + ")");
}

// A one-row strip of the display: vertical slits look the same in every row.
DisplaySpec strip(DisplaySpec spec) {
  spec.imagePanel.height = spec.maskPanel.height = 1;
  spec.viewZoneHeightMm = 0.0;
  return spec;
}

bool samePanel(const Panel& a, const Panel& b) {
  return a.width == b.width && a.pitchMm == b.pitchMm && a.subpixels == b.subpixels;
}

int slitWidthPx(int screenPeriodPx, double duty) {
  return duty > 0 ? std::clamp(int(std::lround(duty * screenPeriodPx)), 1, screenPeriodPx) : 1;
}

// Fills [x0, x1) x [y0, y1), clipped to the image.
void fillRect(Image& image, int x0, int y0, int x1, int y1, Vec3f colour) {
  for (int y = std::max(0, y0); y < std::min(image.height(), y1); ++y)
    for (int x = std::max(0, x0); x < std::min(image.width(), x1); ++x) image.at(x, y) = colour;
}

void drawText(Image& image, int x0, int y0, int scale, const std::string& text, Vec3f colour) {
  for (size_t i = 0; i < text.size(); ++i) {
    const unsigned char* rows = glyphRows(text[i]);
    const int left = x0 + int(i) * kGlyphAdvance * scale;
    for (int r = 0; r < kGlyphHeight; ++r)
      for (int c = 0; c < kGlyphWidth; ++c)
        if (rows[r] & (1u << (kGlyphWidth - 1 - c)))
          fillRect(image, left + c * scale, y0 + r * scale, left + (c + 1) * scale,
                   y0 + (r + 1) * scale, colour);
  }
}

// Fully saturated hue h in [0, 1) as linear RGB.
Vec3f hue(double h) {
  const double x = 6.0 * (h - std::floor(h));
  const auto ramp = [x](double centre) {
    double d = std::abs(x - centre);
    d = std::min(d, 6.0 - d);
    return float(std::clamp(2.0 - d, 0.0, 1.0));
  };
  return {ramp(0.0), ramp(2.0), ramp(4.0)};
}

// Whether the number `text`, centred in a picture of groups x rows cells with font pixels sx
// cells wide and sy rows high, covers cell (group, row).
bool numberCovers(const std::string& text, int groups, int rows, int sx, int sy, int group,
                  int row) {
  const int advance = kGlyphAdvance * int(text.size());
  const int gx = group - (groups - (advance - 1) * sx) / 2;
  const int gy = row - (rows - kGlyphHeight * sy) / 2;
  if (gx < 0 || gy < 0 || gy >= kGlyphHeight * sy) return false;
  const int cell = gx / sx, character = cell / kGlyphAdvance, column = cell % kGlyphAdvance;
  if (character >= int(text.size()) || column >= kGlyphWidth) return false;
  return (glyphRows(text[size_t(character)])[gy / sy] >> (kGlyphWidth - 1 - column)) & 1u;
}

// Peak position by a parabola through three equally spaced samples, as an offset in steps.
double parabolicOffset(double left, double centre, double right) {
  const double curvature = left - 2.0 * centre + right;
  if (!(curvature < 0)) return 0.0;
  return std::clamp(0.5 * (left - right) / curvature, -0.5, 0.5);
}

}  // namespace

DisplaySpec measuredDisplaySpec(const DisplaySpec& base, double screenPeriodPx, double slitPeriodPx,
                                double phasePx) {
  DisplaySpec spec = base;
  spec.views.reset();
  spec.viewZoneWidthMm.reset();
  spec.viewDistanceMm.reset();
  spec.screenPeriodPx = screenPeriodPx;
  spec.slitPeriodPx = slitPeriodPx;
  spec.mask.phasePx = phasePx;
  designDisplay(spec);  // throws for impossible input
  return spec;
}

double expectedSlitPeriodPx(const DisplaySpec& base, int screenPeriodPx) {
  DisplaySpec spec = base;
  spec.viewDistanceMm = designDisplay(base).viewDistanceMm;
  spec.views = double(screenPeriodPx);
  spec.viewZoneWidthMm.reset();
  spec.screenPeriodPx.reset();
  spec.slitPeriodPx.reset();
  return designDisplay(spec).slitPeriodPx;
}

// ---- Patterns ----------------------------------------------------------------------------

PatternSettings resolvePatternSettings(const DisplaySpec& display, PatternSettings s) {
  const DisplayDesign design = designDisplay(display);
  if (s.screenPeriodPx < 0 || s.screenPeriodPx == 1)
    throw optionError("screen_period_px", "must be at least 2 pixels");
  if (s.screenPeriodPx == 0)
    s.screenPeriodPx = std::max(2, int(std::lround(design.screenPeriodPx)));
  const int tx = s.screenPeriodPx;
  const double expected = expectedSlitPeriodPx(display, tx);
  if (s.slitPeriodPx == 0) s.slitPeriodPx = expected;
  checkSlitPeriod(display, tx, s.slitPeriodPx, "slit_period_px");
  if ((s.fromPx == 0) != (s.toPx == 0))
    throw optionError("from_px", "give both ends of the period range (from_px and to_px)");
  if (s.fromPx == 0) {
    // g/D from half to 1.5 times the design's: the gap is rarely known better than that.
    const double screenInMaskPx = tx * display.imagePanel.pitchMm / display.maskPanel.pitchMm;
    const double half = 0.5 * std::abs(expected - screenInMaskPx);
    s.fromPx = s.slitPeriodPx - half;
    s.toPx = s.slitPeriodPx + half;
  }
  checkSlitPeriod(display, tx, s.fromPx, "from_px");
  checkSlitPeriod(display, tx, s.toPx, "to_px");
  if (!(s.fromPx <= s.toPx)) throw optionError("to_px", "must not be below from_px");
  if (s.periodSteps < 1) throw optionError("period_steps", "must be at least 1");
  if (s.phaseStepPx == 0) s.phaseStepPx = 0.5;
  if (!(s.phaseStepPx > 0 && s.phaseStepPx <= s.slitPeriodPx))
    throw optionError("phase_step_px", "must be positive and at most one slit period");
  if (!(s.duty >= 0 && s.duty <= 1)) throw optionError("duty", "must be in (0, 1]");
  if (!std::isfinite(s.phasePx)) throw optionError("phase_px", "must be a number");
  if (s.labelScale < 0) throw optionError("label_scale", "must be at least 1");
  if (s.labelScale == 0) s.labelScale = std::max(1, display.imagePanel.height / 180);
  return s;
}

std::vector<PatternDescription> calibrationPatternSet(const DisplaySpec& display,
                                                      const PatternSettings& settings) {
  const PatternSettings s = resolvePatternSettings(display, settings);
  const std::string tx = "TX " + std::to_string(s.screenPeriodPx);
  const auto number = [](int i, int count) {  // zero-padded to at least two digits
    const std::string text = std::to_string(i);
    const size_t digits = std::max<size_t>(2, std::to_string(count).size());
    return std::string(digits - std::min(digits, text.size()), '0') + text;
  };
  const auto pattern = [&s](std::string file, PatternKind kind, std::string purpose, double period,
                            double phase, std::string label = "") {
    PatternDescription p;
    p.file = std::move(file);
    p.kind = kind;
    p.maskLayer = kind == PatternKind::MaskSlits;
    p.purpose = std::move(purpose);
    p.screenPeriodPx = s.screenPeriodPx;
    p.slitPeriodPx = period;
    p.phasePx = phase;
    p.duty = s.duty;
    p.labelScale = s.labelScale;
    p.label = p.maskLayer ? "TV " + fixed(period, 4) + " PH " + fixed(phase, 2) : std::move(label);
    return p;
  };
  const auto mask = PatternKind::MaskSlits;
  std::vector<PatternDescription> set;
  set.push_back(pattern("image-slits.png", PatternKind::ScreenSlits,
                        "image layer: white slits at the screen period; show it with every mask "
                        "pattern",
                        s.slitPeriodPx, s.phasePx, tx));
  for (int i = 0; i < s.periodSteps; ++i) {
    const double t = s.periodSteps == 1 ? 0.5 : double(i) / double(s.periodSteps - 1);
    set.push_back(pattern("mask-period-" + number(i + 1, s.periodSteps) + ".png", mask,
                          "period sweep: the one that looks uniformly white from one place",
                          s.fromPx + t * (s.toPx - s.fromPx), s.phasePx));
  }
  const int phases = int(std::ceil(s.slitPeriodPx / s.phaseStepPx - 1e-9));
  for (int j = 0; j < phases; ++j)
    set.push_back(pattern("mask-phase-" + number(j + 1, phases) + ".png", mask,
                          "phase sweep: the one that is white from where you sit", s.slitPeriodPx,
                          s.phasePx + j * s.phaseStepPx));
  set.push_back(pattern("mask-slits.png", mask,
                        "the mask for image-views.png and image-colours.png", s.slitPeriodPx,
                        s.phasePx));
  set.push_back(pattern("image-views.png", PatternKind::NumberedViews,
                        "image layer: each view shows its number in its own colour (with "
                        "mask-slits)",
                        s.slitPeriodPx, s.phasePx, "VIEWS " + tx));
  set.push_back(pattern("image-colours.png", PatternKind::ColourTest,
                        "image layer: white, red, green and blue slits in bands (with "
                        "mask-slits)",
                        s.slitPeriodPx, s.phasePx, "WRGB " + tx));
  return set;
}

Image drawPattern(const DisplaySpec& display, const PatternDescription& p) {
  Image image;
  switch (p.kind) {
    case PatternKind::ScreenSlits:
      image = screenSlitImage(display.imagePanel, p.screenPeriodPx, p.duty, Vec3f(1.0f));
      break;
    case PatternKind::MaskSlits:
      image = maskSlitImage(display, p.screenPeriodPx, p.slitPeriodPx, p.phasePx, p.duty);
      break;
    case PatternKind::NumberedViews:
      image = numberedViewImage(display, p.screenPeriodPx, p.slitPeriodPx, p.phasePx);
      break;
    case PatternKind::ColourTest:
      image = colourTestImage(display.imagePanel, p.screenPeriodPx, p.duty);
      break;
  }
  drawLabel(image, labelLayout(image.width(), image.height(), p.labelScale), p.maskLayer, p.label);
  return image;
}

Image screenSlitImage(const Panel& panel, int screenPeriodPx, double duty, Vec3f colour) {
  Image image(panel.width, panel.height);
  const int width = slitWidthPx(screenPeriodPx, duty);
  const int first = (screenPeriodPx - width) / 2;  // centred in its group
  for (int x = 0; x < panel.width; ++x) {
    const int inGroup = x % screenPeriodPx;
    if (inGroup < first || inGroup >= first + width) continue;
    for (int y = 0; y < panel.height; ++y) image.at(x, y) = colour;
  }
  return image;
}

Image maskSlitImage(const DisplaySpec& display, int screenPeriodPx, double slitPeriodPx,
                    double phasePx, double duty) {
  DisplaySpec spec = measuredDisplaySpec(display, screenPeriodPx, slitPeriodPx, phasePx);
  spec.mask = MaskSpec{};
  spec.mask.phasePx = phasePx;
  spec.mask.dutyCycle = duty > 0 ? duty : 1.0 / slitPeriodPx;  // one mask pixel wide
  return maskLayerImage(designDisplay(spec));
}

Vec3f viewColour(int view, int views) {
  return hue(double(view) / double(std::max(1, views)));
}

Image numberedViewImage(const DisplaySpec& display, int screenPeriodPx, double slitPeriodPx,
                        double phasePx) {
  // The panel's pixel views (the default camera: one ray per pixel).
  const std::unique_ptr<DisplayModel> rays = makeBarrierDisplay(
      designDisplay(measuredDisplaySpec(display, screenPeriodPx, slitPeriodPx, phasePx)));
  const Panel& panel = display.imagePanel;
  // Each view is a picture of one column per group by the panel's rows. A font pixel is sy
  // rows high and sx groups wide, about square on the panel, and the widest number fits.
  const int groups = (panel.width + screenPeriodPx - 1) / screenPeriodPx;
  const int digits = int(std::to_string(screenPeriodPx - 1).size());
  const int sy = std::max(1, int(0.6 * panel.height / kGlyphHeight));
  const int sx = std::max(1, std::min(int(0.8 * groups / (digits * kGlyphAdvance)),
                                      int(std::lround(double(sy) / screenPeriodPx))));
  Image image(panel.width, panel.height);
  for (int x = 0; x < panel.width; ++x)
    for (int y = 0; y < panel.height; ++y) {
      const int view = rays->viewIndex(x, y);
      const Vec3f colour = viewColour(view, screenPeriodPx);
      const bool lit =
          numberCovers(std::to_string(view), groups, panel.height, sx, sy, x / screenPeriodPx, y);
      image.at(x, y) = lit ? colour : colour * 0.15f;
    }
  return image;
}

Image colourTestImage(const Panel& panel, int screenPeriodPx, double duty) {
  const Vec3f colours[4] = {Vec3f(1.0f), {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  Image image = screenSlitImage(panel, screenPeriodPx, duty, Vec3f(1.0f));
  for (int y = 0; y < panel.height; ++y)
    for (int x = 0; x < panel.width; ++x)
      image.at(x, y) = image.at(x, y) * colours[std::min(3, 4 * y / panel.height)];
  return image;
}

LabelLayout labelLayout(int width, int height, int scale) {
  LabelLayout l;
  l.scale = std::max(1, scale);
  const int s = l.scale, pad = s, margin = 2 * s;
  l.windowMargin = 2 * s + 2;  // the other layer's window: parallax across the gap
  l.boxWidth = kMaxLabelChars * kGlyphAdvance * s - s + 2 * pad;
  l.boxHeight = kGlyphHeight * s + 2 * pad;
  const int boxStride = l.boxHeight + 2 * l.windowMargin;
  l.imageTextX = l.maskTextX = margin + pad;
  l.imageTextY = l.maskTextY = margin + pad;
  int used = margin + boxStride;
  if (2 * (l.boxWidth + 2 * l.windowMargin) + 2 * margin <= width) {
    l.maskTextX = width - margin - l.boxWidth + pad;
  } else {
    l.maskTextY += boxStride;
    used += boxStride;
  }
  l.shown = l.boxWidth + 2 * margin + l.windowMargin <= width && 2 * used <= height;
  return l;
}

void drawLabel(Image& image, const LabelLayout& l, bool maskLayer, const std::string& text) {
  if (!l.shown) return;
  const int pad = l.scale;
  const int ownX = (maskLayer ? l.maskTextX : l.imageTextX) - pad;
  const int ownY = (maskLayer ? l.maskTextY : l.imageTextY) - pad;
  const int otherX = (maskLayer ? l.imageTextX : l.maskTextX) - pad - l.windowMargin;
  const int otherY = (maskLayer ? l.imageTextY : l.maskTextY) - pad - l.windowMargin;
  const int m2 = 2 * l.windowMargin;
  fillRect(image, otherX, otherY, otherX + l.boxWidth + m2, otherY + l.boxHeight + m2, Vec3f(1.0f));
  fillRect(image, ownX, ownY, ownX + l.boxWidth, ownY + l.boxHeight, Vec3f(0.0f));
  drawText(image, ownX + pad, ownY + pad, l.scale, text.substr(0, kMaxLabelChars), Vec3f(1.0f));
}

// ---- Prediction --------------------------------------------------------------------------

CalibrationScorer::CalibrationScorer(const DisplaySpec& assumed, const DisplayDesign& physics,
                                     const Vec3d& eye, int screenPeriodPx, double duty,
                                     int samplesPerPixel)
    : assumed_(strip(assumed)),
      physics_(physics),
      eye_{eye.x, 0.0, eye.z},
      screenPeriod_(screenPeriodPx),
      samples_(std::max(1, samplesPerPixel)),
      duty_(duty) {
  const DisplaySpec& p = physics.spec;
  if (!samePanel(assumed.imagePanel, p.imagePanel) || !samePanel(assumed.maskPanel, p.maskPanel) ||
      assumed.order != p.order)
    throw std::invalid_argument("CalibrationScorer: the displays' panels or order differ");
  if (!(eye.z > 0)) throw RequestError("eye", "must be in front (z > 0)");
  physics_.spec = strip(p);
  // One image pixel, seen through an aperture across the gap, spans dx (D - z_M) / g at the
  // eye's distance D (z_M = -g behind, 0 in front).
  const double g = assumed.gapMm;
  const double maskZ = assumed.order == LayerOrder::BarrierBack ? -g : 0.0;
  viewWidthMm_ = assumed.imagePanel.pitchMm * (eye.z - maskZ) / g;
  groups_ = assumed.imagePanel.width / screenPeriodPx;
  imageLayer_ = screenSlitImage(assumed_.imagePanel, screenPeriodPx, duty, Vec3f(1.0f));
}

CalibrationScore CalibrationScorer::score(double slitPeriodPx, double phasePx,
                                          bool uniformity) const {
  const Image mask = maskSlitImage(assumed_, screenPeriod_, slitPeriodPx, phasePx, duty_);
  const bool imageInFront = assumed_.order == LayerOrder::BarrierBack;
  const Panel& front = imageInFront ? assumed_.imagePanel : assumed_.maskPanel;
  SimulationOptions options;
  options.width = front.width * samples_;
  options.height = 1;
  options.normalise = false;
  options.threads = 1;
  const DisplaySimulator simulator(physics_, {imageLayer_, mask}, options);
  const int width = options.width;
  // The central 90% of the view: the rear layer's edge shows at the panel's sides.
  const int lo = width / 20, hi = width - width / 20;
  const auto mean = [lo, hi](const Image& row) {
    double sum = 0;
    for (int x = lo; x < hi; ++x) sum += luminance(row.at(x, 0));
    return sum / double(hi - lo);
  };
  const Image seen = simulator.view(eye_);
  const double b0 = mean(seen);
  const double left = mean(simulator.view({eye_.x - viewWidthMm_, 0.0, eye_.z}));
  const double right = mean(simulator.view({eye_.x + viewWidthMm_, 0.0, eye_.z}));
  const double bn = 0.5 * (left + right);

  CalibrationScore s;
  s.brightness = b0;
  s.contrast = b0 + bn > 0 ? (b0 - bn) / (b0 + bn) : 0.0;
  const double openMean = double(slitWidthPx(screenPeriod_, duty_)) / screenPeriod_;
  s.score = std::max(0.0, b0 - bn) / openMean;
  if (!uniformity) return s;
  // Uniformity across the view: the light of each front period (a box one period wide), so
  // that a periodic view is constant and moire shows as variation.
  const double frontPeriodPx = imageInFront ? screenPeriod_ : slitPeriodPx;
  const Image periods = boxFilterX(seen, frontPeriodPx * samples_);
  double sum = 0, sumSquares = 0;
  for (int x = lo; x < hi; ++x) {
    const double v = luminance(periods.at(x, 0));
    sum += v, sumSquares += v * v;
  }
  const double n = double(hi - lo), average = sum / n;
  const double variation =
      average > 0 ? std::sqrt(std::max(0.0, sumSquares / n - average * average)) / average : 1.0;
  s.uniformity = std::max(0.0, 1.0 - variation);
  return s;
}

CalibrationPrediction predictCalibration(const DisplaySpec& assumed, const DisplayDesign& physics,
                                         const Vec3d& eye, const PredictionSettings& settings) {
  CalibrationPrediction p;
  const DisplayDesign design = designDisplay(assumed);
  if (settings.screenPeriodPx < 0 || settings.screenPeriodPx == 1)
    throw optionError("screen_period_px", "must be at least 2 pixels");
  const int tx = settings.screenPeriodPx > 0 ? settings.screenPeriodPx
                                             : std::max(2, int(std::lround(design.screenPeriodPx)));
  p.screenPeriodPx = tx;
  const double txMask = tx * assumed.imagePanel.pitchMm / assumed.maskPanel.pitchMm;
  const double delta = expectedSlitPeriodPx(assumed, tx) - txMask;
  if ((settings.fromPx == 0) != (settings.toPx == 0))
    throw optionError("from_px", "give both ends of the period range (from_px and to_px)");
  p.fromPx = settings.fromPx != 0 ? settings.fromPx : txMask + 0.25 * delta;
  p.toPx = settings.toPx != 0 ? settings.toPx : txMask + 2.0 * delta;
  // A range given reversed is refused, as the patterns' sweep refuses it; the default one
  // runs from a quarter to twice the design's offset, which is negative for a barrier in front.
  if (settings.fromPx != 0 && !(settings.fromPx <= settings.toPx))
    throw optionError("to_px", "must not be below from_px");
  if (p.fromPx > p.toPx) std::swap(p.fromPx, p.toPx);
  checkSlitPeriod(assumed, tx, p.fromPx, "from_px");
  checkSlitPeriod(assumed, tx, p.toPx, "to_px");
  if (!(settings.duty >= 0 && settings.duty <= 1)) throw optionError("duty", "must be in (0, 1]");

  const CalibrationScorer scorer(assumed, physics, eye, tx, settings.duty,
                                 settings.samplesPerPixel);
  const auto score = [&scorer](double period, double phase) {
    return scorer.score(period, phase, false).score;
  };
  // Coarse: a period error dTv drifts the slits by N dTv across N groups, so steps of 1/(4N)
  // pixels keep the drift between neighbouring candidates at a quarter pixel.
  const double coarse = 1.0 / (4.0 * std::max(1, scorer.groupsAcross()));
  const int count = std::max(2, int(std::ceil((p.toPx - p.fromPx) / coarse)) + 1);
  // Phases one pixel apart: the best is within half a pixel of the optimum at every period,
  // which keeps the shape of the curve over the periods.
  const int phases = int(std::lround(0.5 * (p.fromPx + p.toPx)));
  std::vector<double> bestPhase(size_t(count), 0.0);
  for (int i = 0; i < count; ++i) {
    const double period = p.fromPx + (p.toPx - p.fromPx) * i / (count - 1);
    double best = -1;
    for (int j = 0; j < phases; ++j) {
      const double phase = period * j / phases, value = score(period, phase);
      if (value > best) best = value, bestPhase[size_t(i)] = phase;
    }
    p.periods.push_back(period);
    p.periodScores.push_back(best);
  }
  const size_t top = size_t(std::max_element(p.periodScores.begin(), p.periodScores.end()) -
                            p.periodScores.begin());

  // The phase at a period: 1/32-pixel steps over +-1 pixel around a guess, interpolated.
  const auto refinePhase = [&score](double period, double guess) {
    constexpr int kSteps = 32;
    std::vector<double> values;
    for (int k = -kSteps; k <= kSteps; ++k) values.push_back(score(period, guess + k / 32.0));
    const size_t m =
        size_t(std::max_element(values.begin() + 1, values.end() - 1) - values.begin());
    return guess +
           (double(m) - kSteps + parabolicOffset(values[m - 1], values[m], values[m + 1])) / kSteps;
  };
  double phase = refinePhase(p.periods[top], bestPhase[top]);
  // Fine periods: ten times finer over +-2 coarse steps at that phase, interpolated.
  const double step = (p.toPx - p.fromPx) / (count - 1), fine = step / 10;
  std::vector<double> periods, values;
  for (int k = -20; k <= 20; ++k) {
    const double period = p.periods[top] + k * fine;
    if (period < p.fromPx - 1e-12 || period > p.toPx + 1e-12) continue;
    periods.push_back(period);
    values.push_back(score(period, phase));
  }
  size_t m = size_t(std::max_element(values.begin(), values.end()) - values.begin());
  p.slitPeriodPx = periods[m];
  if (m > 0 && m + 1 < values.size())
    p.slitPeriodPx += fine * parabolicOffset(values[m - 1], values[m], values[m + 1]);
  phase = refinePhase(p.slitPeriodPx, phase);
  p.phasePx = phase - p.slitPeriodPx * std::ceil(phase / p.slitPeriodPx - 0.5);
  p.stepPx = fine;
  p.atRangeEdge = std::min(p.slitPeriodPx - p.fromPx, p.toPx - p.slitPeriodPx) < step;
  p.score = scorer.score(p.slitPeriodPx, p.phasePx);
  const double slitMm = p.slitPeriodPx * assumed.maskPanel.pitchMm;
  const double screenMm = tx * assumed.imagePanel.pitchMm;
  const double rearOverFront =
      assumed.order == LayerOrder::BarrierBack ? slitMm / screenMm : screenMm / slitMm;
  p.distanceOverGap = 1.0 / (rearOverFront - 1.0);  // G1
  return p;
}

}  // namespace parallax
