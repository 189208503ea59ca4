// Calibration patterns checked by independent readers (run centroids for periods and phases, a
// glyph reader for the labels), and the simulator-based prediction checked against displays
// whose gap and distance the routine is not told.
#include "parallax/sim/calibration.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "parallax/core/error.h"
#include "parallax/display/display_model.h"
#include "parallax/image/contact_sheet.h"
#include "parallax/image/metrics.h"
#include "parallax/sim/crosstalk.h"
#include "parallax/sim/sim_test_support.h"
#include "parallax/sim/simulator.h"

namespace parallax {
namespace {

DisplaySpec panels(LayerOrder order, int width, int height) {
  DisplaySpec s = defaultDisplaySpec();
  s.order = order;
  s.imagePanel.width = s.maskPanel.width = width;
  s.imagePanel.height = s.maskPanel.height = height;
  return s;
}

// Coverage-weighted centres of the maximal runs of lit pixels in one row. For a slit one
// pixel wide the centroid of its two anti-aliased pixels is exactly the slit's centre.
std::vector<double> runCentres(const Image& image, int row) {
  std::vector<double> centres;
  double weight = 0, moment = 0;
  for (int x = 0; x <= image.width(); ++x) {
    const double v = x < image.width() ? luminance(image.at(x, row)) : 0.0;
    if (v > 1e-6) {
      weight += v, moment += v * (x + 0.5);
    } else if (weight > 0) {
      centres.push_back(moment / weight);
      weight = moment = 0;
    }
  }
  return centres;
}

// Least-squares line through (k, centre_k): slope = period, intercept = first centre. The
// runs at the panel's ends may be clipped and are left out.
struct Line {
  double period = 0, first = 0;
};
Line fitRuns(const std::vector<double>& centres) {
  const size_t n = centres.size() - 2;
  double sk = 0, sc = 0, skk = 0, skc = 0;
  for (size_t k = 0; k < n; ++k) {
    const double c = centres[k + 1];
    sk += double(k), sc += c, skk += double(k) * double(k), skc += double(k) * c;
  }
  const double period = (n * skc - sk * sc) / (n * skk - sk * sk);
  return {period, (sc - period * sk) / n};
}

// The glyph of the built-in font drawn at (x0, y0), scaled by `scale`: a font pixel is lit
// when its scale x scale cell averages above one half; '?' if it matches no glyph.
char readGlyph(const Image& image, int x0, int y0, int scale) {
  unsigned char rows[kGlyphHeight] = {};
  for (int r = 0; r < kGlyphHeight; ++r)
    for (int c = 0; c < kGlyphWidth; ++c) {
      double sum = 0;
      for (int dy = 0; dy < scale; ++dy)
        for (int dx = 0; dx < scale; ++dx) {
          const int x = x0 + c * scale + dx, y = y0 + r * scale + dy;
          if (x >= 0 && y >= 0 && x < image.width() && y < image.height())
            sum += luminance(image.at(x, y));
        }
      if (sum > 0.5 * scale * scale)
        rows[r] = static_cast<unsigned char>(rows[r] | (1u << (kGlyphWidth - 1 - c)));
    }
  for (char candidate : std::string(" 0123456789.-ABCDEFGHIJKLMNOPQRSTUVWXYZ"))
    if (std::equal(rows, rows + kGlyphHeight, glyphRows(candidate))) return candidate;
  return '?';
}

// Reads `chars` glyphs from (x0, y0) as a reader would: a label seen across the gap may sit
// a pixel or two off its place, more toward the panel's sides.
std::string readLabel(const Image& image, int x0, int y0, int scale, int chars) {
  std::string text;
  for (int i = 0; i < chars; ++i) {
    // A glyph half a cell off reads as blank: prefer a shift that reads as a character.
    char found = '?';
    for (int shift : {0, -1, 1, -2, 2}) {
      const char c = readGlyph(image, x0 + i * kGlyphAdvance * scale + shift, y0, scale);
      if (c != '?' && c != ' ') {
        found = c;
        break;
      }
      if (c == ' ') found = ' ';
    }
    text += found;
  }
  return text.substr(0, text.find_last_not_of(' ') + 1);
}

// "TV 9.0450 PH 0.50" -> (9.045, 0.5).
bool parseMaskLabel(const std::string& label, double& period, double& phase) {
  return std::sscanf(label.c_str(), "TV %lf PH %lf", &period, &phase) == 2;
}

double circularDistance(double a, double b, double period) {
  const double d = std::fmod(std::abs(a - b), period);
  return std::min(d, period - d);
}

TEST(CalibrationPatterns, MaskPeriodsAndPhasesAreWhatTheirLabelsSay) {
  for (LayerOrder order : kLayerOrders) {
    const DisplaySpec display = panels(order, 480, 60);
    const std::vector<PatternDescription> set = calibrationPatternSet(display, {});
    const LabelLayout layout = labelLayout(480, 60, set.front().labelScale);
    ASSERT_TRUE(layout.shown);
    int masks = 0;
    Line phaseZero;
    for (const PatternDescription& p : set) {
      if (p.kind != PatternKind::MaskSlits) continue;
      ++masks;
      const Image image = drawPattern(display, p);
      ASSERT_EQ(image.width(), display.maskPanel.width);
      ASSERT_EQ(image.height(), display.maskPanel.height);
      double labelPeriod = 0, labelPhase = 0;
      const std::string label =
          readLabel(image, layout.maskTextX, layout.maskTextY, layout.scale, kMaxLabelChars);
      ASSERT_TRUE(parseMaskLabel(label, labelPeriod, labelPhase)) << p.file << ": " << label;
      const Line line = fitRuns(runCentres(image, image.height() - 1));
      // The label has 4 decimals (5e-5); the fit over ~50 exact centres is far finer.
      EXPECT_NEAR(line.period, labelPeriod, 1e-4) << p.file;
      // Phase: the slits move by the phase difference against the phase sweep's first.
      if (p.file == "mask-phase-01.png") phaseZero = line;
      if (p.file.rfind("mask-phase-", 0) == 0) {  // phases are labelled with 2 decimals
        EXPECT_LT(circularDistance(line.first - phaseZero.first, labelPhase - set[10].phasePx,
                                   line.period),
                  0.006)
            << p.file;
      }
    }
    // Phases 0, 0.5, ... below Tv = 9.045 (barrier-back) or 8.955 (barrier-front).
    EXPECT_EQ(masks, 9 + (order == LayerOrder::BarrierBack ? 19 : 18) + 1);
  }
}

TEST(CalibrationPatterns, PeriodSweepBracketsTheDesignAndImageSlitsSitAtTheScreenPeriod) {
  for (LayerOrder order : kLayerOrders) {
    const DisplaySpec display = panels(order, 480, 60);
    const DisplayDesign design = designDisplay(display);
    const std::vector<PatternDescription> set = calibrationPatternSet(display, {});
    EXPECT_LT(set[1].slitPeriodPx, design.slitPeriodPx);
    EXPECT_GT(set[9].slitPeriodPx, design.slitPeriodPx);
    EXPECT_NEAR(set[5].slitPeriodPx, design.slitPeriodPx, 1e-9);  // the middle of nine
    const Image slits = drawPattern(display, set.front());
    const std::vector<double> centres = runCentres(slits, slits.height() - 1);
    for (size_t k = 1; k < centres.size(); ++k) EXPECT_DOUBLE_EQ(centres[k] - centres[k - 1], 9);
    EXPECT_DOUBLE_EQ(centres.front(), 4.5);  // the central pixel of the first group
    const LabelLayout layout = labelLayout(480, 60, set.front().labelScale);
    EXPECT_EQ(readLabel(slits, layout.imageTextX, layout.imageTextY, layout.scale, 8), "TX 9");
  }
}

TEST(CalibrationPatterns, RefusesPeriodsThatBreakG1) {
  PatternSettings s;
  s.fromPx = 8.8, s.toPx = 9.1;  // barrier-back needs Tv > Tx = 9
  try {
    calibrationPatternSet(defaultDisplaySpec(), s);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), kCalibrationSettings);
    EXPECT_EQ(e.path(), "/from_px");  // a field, not an option: the front end names those
  }
  EXPECT_THROW(measuredDisplaySpec(defaultDisplaySpec(), 9, 8.9, 0), InputError);
}

// Both labels are seen on the panel: the simulated view from the design eye reads back as the
// labels of the image layer's and the mask layer's patterns.
TEST(CalibrationPatterns, LabelsAreReadableThroughTheOtherPanel) {
  for (LayerOrder order : kLayerOrders) {
    const DisplaySpec display = panels(order, 720, 180);
    PatternSettings settings;
    settings.labelScale = 3;
    const std::vector<PatternDescription> set = calibrationPatternSet(display, settings);
    const LabelLayout layout = labelLayout(720, 180, 3);
    ASSERT_TRUE(layout.shown);
    const DisplayDesign design = designDisplay(display);
    SimulationOptions raw;
    raw.normalise = false;  // transmittance as it is: a label is white (1) or not
    const DisplaySimulator sim(design, {drawPattern(display, set[0]), drawPattern(display, set[3])},
                               raw);
    const Image seen = sim.view({0, 0, design.viewDistanceMm});
    EXPECT_EQ(readLabel(seen, layout.imageTextX, layout.imageTextY, 3, 8), "TX 9");
    EXPECT_EQ(readLabel(seen, layout.maskTextX, layout.maskTextY, 3, kMaxLabelChars), set[3].label);
  }
}

TEST(CalibrationPatterns, EachViewShowsItsNumberInItsColour) {
  for (LayerOrder order : kLayerOrders) {
    const DisplaySpec display = panels(order, 240, 60);
    const DisplayDesign design = designDisplay(display);
    const Image views = numberedViewImage(display, 9, design.slitPeriodPx, 0.0);
    const Image mask = maskSlitImage(display, 9, design.slitPeriodPx, 0.0, 0.0);
    SimulationOptions options;
    options.width = 4 * 240;
    const DisplaySimulator sim(design, {views, mask}, options);
    const std::unique_ptr<DisplayModel> rays = makeBarrierDisplay(design);
    for (int v = 0; v < 9; ++v) {
      // The eye of view v sees mostly view v's hue: the nearest of the nine.
      const Image seen = sim.view(designEyePosition(design, v));
      Vec3f mean(0.0f);
      for (const Vec3f& p : seen.pixels()) mean += p;
      const auto cosine = [&mean](const Vec3f& c) {
        return dot(mean, c) / (length(mean) * length(c));
      };
      int nearest = 0;
      for (int u = 1; u < 9; ++u)
        if (cosine(viewColour(u, 9)) > cosine(viewColour(nearest, 9))) nearest = u;
      EXPECT_EQ(nearest, v) << "order " << int(order);
      // The picture of view v, one cell per group and row, lit where the group's pixel of
      // view v is bright, draws the digit v: read it within the bounds of its lit cells.
      std::vector<std::vector<bool>> lit(240 / 9 + 1, std::vector<bool>(60, false));
      int left = 1 << 20, right = -1, top = 1 << 20, bottom = -1;
      for (int x = 0; x < 240; ++x)
        for (int y = 0; y < 60; ++y)
          if (rays->viewIndex(x, y) == v && maxComponent(views.at(x, y)) > 0.5f) {
            lit[size_t(x / 9)][size_t(y)] = true;
            left = std::min(left, x / 9), right = std::max(right, x / 9);
            top = std::min(top, y), bottom = std::max(bottom, y);
          }
      ASSERT_GE(right, left) << "view " << v;
      const unsigned char* digit = glyphRows(char('0' + v));
      int first = kGlyphWidth, last = -1;  // the glyph's own columns
      for (int r = 0; r < kGlyphHeight; ++r)
        for (int c = 0; c < kGlyphWidth; ++c)
          if ((digit[r] >> (kGlyphWidth - 1 - c)) & 1u)
            first = std::min(first, c), last = std::max(last, c);
      const int sx = (right - left + 1) / (last - first + 1),
                sy = (bottom - top + 1) / kGlyphHeight;
      ASSERT_GE(sx, 1);
      ASSERT_GE(sy, 1);
      for (int r = 0; r < kGlyphHeight; ++r)
        for (int c = first; c <= last; ++c)
          EXPECT_EQ(lit[size_t(left + (c - first) * sx + sx / 2)][size_t(top + r * sy + sy / 2)],
                    bool((digit[r] >> (kGlyphWidth - 1 - c)) & 1u))
              << "view " << v << " font pixel " << c << "," << r;
    }
  }
}

TEST(CalibrationPatterns, ColourTestHasWhiteRedGreenBlueBands) {
  const Image image = colourTestImage(defaultDisplaySpec().imagePanel, 9, 0.0);
  const Vec3f expected[4] = {Vec3f(1.0f), {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int band = 0; band < 4; ++band) {
    const int y = (2 * band + 1) * image.height() / 8;
    EXPECT_EQ(image.at(4, y), expected[band]);
    EXPECT_EQ(image.at(5, y), Vec3f(0.0f));
    EXPECT_EQ(image.at(13, y), expected[band]);
  }
}

// ---- Prediction ----------------------------------------------------------------------------
//
// Tolerance. Take the slit centred on the panel as the phase reference (the aperture origin
// is the group nearest x = 0). A slit period error dTv (mask pixels) then displaces aperture k
// from the projection of its lit pixel by k dTv, up to N/2 dTv at the panel's edges (N groups
// across). The view from the eye stays that of one view (the one the lit pixel serves) while
// the displacement stays within a quarter of the view spacing on the mask, which is
// Tv / (Tx / dx) ~ 1 mask pixel: N/2 |dTv| <= 1/4, so |dTv| <= 1 / (2N). The search adds at
// most half its finest step. For 1920-pixel panels, N = 213: 0.0023 + 0.00006 mask pixels.
// A 240-pixel panel (N = 26) would allow 0.019 pixels, more than the 0.010 between the true
// and the assumed display below: it could not tell them apart. The simulation runs on one-row
// strips, so the full width costs little.
//
// A phase error dphi moves every aperture by dphi: the same quarter of a view gives 1/4 pixel.

struct Truth {
  LayerOrder order;
  double gap, distance, eyeX;
};

double trueSlitPeriod(const Truth& t) {  // G1 with the true g and D, Tx = 9, equal pitches
  const double r = t.order == LayerOrder::BarrierBack ? (t.distance + t.gap) / t.distance
                                                      : t.distance / (t.distance + t.gap);
  return 9.0 * r;
}

// The line from the eye through the lit (central) pixel of group k meets the mask plane at
// e + (c_k - e) r; the pattern puts aperture k at c_0 Tv/Tx + k Tv + phase (its origin is the
// projection of the central group with the ratio of the periods): phase = e (1 - r).
double truePhase(const Truth& t) {
  const double r = trueSlitPeriod(t) / 9.0;
  return t.eyeX * (1.0 - r) / defaultDisplaySpec().maskPanel.pitchMm;
}

TEST(CalibrationPrediction, FindsTheTruePeriodsOfADisplayItIsNotToldAbout) {
  const Truth truths[] = {{LayerOrder::BarrierBack, 2.7, 700, 0},
                          {LayerOrder::BarrierFront, 2.7, 700, 0},
                          {LayerOrder::BarrierBack, 2.7, 700, 100},
                          {LayerOrder::BarrierFront, 3.6, 500, -60}};
  for (const Truth& t : truths) {
    const DisplaySpec assumed = panels(t.order, 1920, 8);  // g = 3, D = 600
    DisplaySpec trueSpec = assumed;
    trueSpec.gapMm = t.gap;
    trueSpec.viewDistanceMm = t.distance;
    const DisplayDesign physics = designDisplay(trueSpec);
    const CalibrationPrediction p =
        predictCalibration(assumed, physics, {t.eyeX, 0, t.distance}, {});
    const double groups = 1920 / 9;
    const double tolerance = 1.0 / (2.0 * groups) + 0.5 * p.stepPx;
    const double truth = trueSlitPeriod(t);
    // The test has power: the assumed display's period is outside the tolerance.
    ASSERT_GT(std::abs(designDisplay(assumed).slitPeriodPx - truth), 2 * tolerance);
    EXPECT_EQ(p.screenPeriodPx, 9);
    EXPECT_NEAR(p.slitPeriodPx, truth, tolerance);
    EXPECT_LT(circularDistance(p.phasePx, truePhase(t), p.slitPeriodPx), 0.25);
    const double dOverG = t.distance / t.gap;
    std::printf(
        "[ order %s g %.1f D %.0f eye x %.0f ] Tv %.5f (true %.5f, error %+.5f, "
        "tolerance %.5f); phase %.3f (true %.3f); D/g %.1f (true %.1f); score %.3f\n",
        t.order == LayerOrder::BarrierBack ? "back" : "front", t.gap, t.distance, t.eyeX,
        p.slitPeriodPx, truth, p.slitPeriodPx - truth, tolerance, p.phasePx, truePhase(t),
        p.distanceOverGap, dOverG, p.score.score);
  }
}

// The premise of the tolerance: the contrast curve is about 1/N wide. At a drift of two
// pixels across the panel (dTv = 2/N) every position sees a mix of views, and the best phase
// recovers less than half of the calibrated score; within the tolerance it keeps most of it.
TEST(CalibrationPrediction, ContrastCurveIsAboutOneOverNWide) {
  const Truth t{LayerOrder::BarrierBack, 2.7, 700, 0};
  const DisplaySpec assumed = panels(t.order, 1920, 8);
  DisplaySpec trueSpec = assumed;
  trueSpec.gapMm = t.gap;
  trueSpec.viewDistanceMm = t.distance;
  const CalibrationScorer scorer(assumed, designDisplay(trueSpec), {0, 0, t.distance}, 9);
  try {
    const CalibrationScorer behind(assumed, designDisplay(trueSpec), {0, 0, -1}, 9);
    ADD_FAILURE() << "an eye behind the display was accepted";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.field(), "eye");
    EXPECT_EQ(e.message(), "must be in front (z > 0)");
  }
  const double truth = trueSlitPeriod(t), n = scorer.groupsAcross();
  const auto bestOverPhases = [&scorer](double period) {
    double best = 0;
    for (int j = -8; j <= 8; ++j) best = std::max(best, scorer.score(period, j / 16.0).score);
    return best;
  };
  const double peak = bestOverPhases(truth);
  for (double sign : {-1.0, 1.0}) {
    const double near = bestOverPhases(truth + sign / (2 * n));
    const double far = bestOverPhases(truth + sign * 2 / n);
    EXPECT_GT(near, 0.6 * peak);
    EXPECT_LT(far, 0.5 * peak);
    std::printf("[ curve ] dTv = %+.1f/N: %.2f of the peak; dTv = %+.0f/N: %.2f\n", sign / 2,
                near / peak, 2 * sign, far / peak);
  }
}

// End to end: the predicted periods with the true gap make a display file whose distance is
// the true one within the tolerance carried through G1, and whose rendered views reach the
// eye as well as the true design's do.
TEST(CalibrationPrediction, AppliedPeriodsGiveTheTrueDistanceAndViews) {
  const Truth t{LayerOrder::BarrierBack, 2.7, 700, 0};
  const DisplaySpec assumed = panels(t.order, 1920, 8);
  DisplaySpec trueSpec = assumed;
  trueSpec.gapMm = t.gap;
  trueSpec.viewDistanceMm = t.distance;
  const DisplayDesign truth = designDisplay(trueSpec);
  const Vec3d eye{0, 0, t.distance};
  const CalibrationPrediction p = predictCalibration(assumed, truth, eye, {});
  DisplaySpec base = assumed;
  base.gapMm = t.gap;  // the user measures the gap roughly, or keeps the default
  const DisplayDesign applied =
      designDisplay(measuredDisplaySpec(base, p.screenPeriodPx, p.slitPeriodPx, p.phasePx));
  const double tolerance = 1.0 / (2.0 * (1920 / 9)) + 0.5 * p.stepPx;
  const auto distance = [&t](double slit) { return t.gap / (slit / 9.0 - 1.0); };  // G1
  const double tv = trueSlitPeriod(t);
  EXPECT_GT(applied.viewDistanceMm, distance(tv + tolerance));
  EXPECT_LT(applied.viewDistanceMm, distance(tv - tolerance));
  std::printf("[ applied ] D %.1f mm (true %.0f)\n", applied.viewDistanceMm, t.distance);

  SimulationOptions options;
  options.width = 8 * 1920;
  options.normalise = false;
  const CrosstalkResult own = measureCrosstalk(applied, maskLayerImage(applied), options, eye);
  const CrosstalkResult ideal = measureCrosstalk(truth, maskLayerImage(truth), options, eye);
  EXPECT_EQ(own.ownView, 4);  // the central view, whose pixels the calibration lit
  EXPECT_LT(own.crosstalk, ideal.crosstalk + 0.05);
  std::printf("[ applied ] crosstalk %.3f (true design %.3f)\n", own.crosstalk, ideal.crosstalk);
}

}  // namespace
}  // namespace parallax
