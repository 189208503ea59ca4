// Calibrating a real two-LCD display (the paper's section 3.1; docs/calibration.md). Both
// layers show white-on-black slits; the user varies the slit period until, from one position,
// the view is uniformly white, and black from the others. That pins down the ratio of the
// periods, Tr/Tf = (D + g)/D (G1), without measuring the gap or the pitch.
//
// Patterns are drawn at the layers' native resolutions. The image layer shows slits at an
// integer screen period Tx: in every group of Tx pixels, laid from the panel's left edge,
// the w pixels starting at floor((Tx - w) / 2) are lit (the central view for odd Tx, w = 1).
// The mask layer shows slits at a fractional period Tv and phase, rasterised by MaskGeometry
// exactly as `render` draws a display file with these measured periods, so the phase found
// here is the display file's mask.phase_px (docs/calibration.md, "The phase", says what that
// can and cannot compensate on a real display).
#pragma once

#include <string>
#include <vector>

#include "parallax/display/display.h"
#include "parallax/image/image.h"

namespace parallax {

// The display with measured periods (Tx image pixels, Tv mask pixels) in place of views and
// distance, so that D follows from G1 and `base`'s gap. The mask keeps base's type and duty
// cycle; the phase is set. Throws designDisplay's InputError for impossible input.
DisplaySpec measuredDisplaySpec(const DisplaySpec& base, double screenPeriodPx, double slitPeriodPx,
                                double phasePx);

// The slit period (mask pixels) that G1 gives for an integer screen period at base's gap and
// view distance.
double expectedSlitPeriodPx(const DisplaySpec& base, int screenPeriodPx);

// ---- Patterns ----------------------------------------------------------------------------

// Zero means "the default" for every field (see calibrationPatternSet).
// The `file` of an InputError about a pattern or prediction setting; its path names the field
// ("/screen_period_px", "/slit_period_px", "/from_px", "/to_px", "/period_steps",
// "/phase_step_px", "/duty", "/phase_px", "/label_scale"), for a front end to map to its own
// names.
inline constexpr const char* kCalibrationSettings = "calibration settings";

struct PatternSettings {
  int screenPeriodPx = 0;       // Tx; default round(design's)
  double slitPeriodPx = 0;      // Tv of the phase sweep and the tests; default G1's for Tx
  double phasePx = 0;           // mask phase of the period sweep and the tests
  double fromPx = 0, toPx = 0;  // period sweep; default Tv -+ |Tv - Tx| / 2 (g/D x 0.5 .. 1.5)
  int periodSteps = 9;
  double phaseStepPx = 0;  // phase sweep over one period; default 0.5 mask pixels
  double duty = 0;         // slit width / period on both layers; default one pixel on each
  int labelScale = 0;      // glyph pixels per font pixel; default max(1, panel height / 180)
};

enum class PatternKind { ScreenSlits, MaskSlits, NumberedViews, ColourTest };

struct PatternDescription {
  std::string file;  // "mask-period-03.png"
  PatternKind kind = PatternKind::ScreenSlits;
  bool maskLayer = false;  // which panel shows it
  std::string purpose;
  int screenPeriodPx = 0;
  double slitPeriodPx = 0, phasePx = 0;  // of the mask it is (or is meant to be seen with)
  double duty = 0;
  int labelScale = 1;
  std::string label;  // drawn into the pattern's corner
};

// The settings with defaults filled in, checked: throws InputError(kCalibrationSettings,
// "/field", ...) for periods that break G1 in the display's layer order, steps < 1, a duty cycle
// outside (0, 1].
PatternSettings resolvePatternSettings(const DisplaySpec& display, PatternSettings settings);

// The whole set: image-slits, mask-period-NN (the period sweep), mask-phase-NN (the phase
// sweep), mask-slits (Tv and phase of the settings), image-views (numbered views) and
// image-colours (R, G, B fringes). Drawn one at a time by drawPattern (a full-HD image is
// 25 MB).
std::vector<PatternDescription> calibrationPatternSet(const DisplaySpec& display,
                                                      const PatternSettings& settings);
Image drawPattern(const DisplaySpec& display, const PatternDescription& pattern);

// The building blocks, unlabelled. Image layer: slits of `colour`, w = max(1, round(duty Tx))
// pixels wide (duty 0: one pixel).
Image screenSlitImage(const Panel& imagePanel, int screenPeriodPx, double duty, Vec3f colour);
// Mask layer: slits at Tv and phase, duty * Tv wide (duty 0: one mask pixel), anti-aliased.
Image maskSlitImage(const DisplaySpec& display, int screenPeriodPx, double slitPeriodPx,
                    double phasePx, double duty);
// Image layer in which view v (the display's viewIndex) shows the number v, large, in
// its own hue (viewColour) on a dim background of that hue.
Image numberedViewImage(const DisplaySpec& display, int screenPeriodPx, double slitPeriodPx,
                        double phasePx);
Vec3f viewColour(int view, int views);
// Image layer: four horizontal bands of slits, top to bottom white, red, green, blue.
Image colourTestImage(const Panel& imagePanel, int screenPeriodPx, double duty);

// Where the labels go: the image layer's label at the top left, the mask layer's at the top
// right (or below the first on a narrow panel). Each layer draws its own text white on black
// and leaves the other layer's box white (with a margin for parallax), so either label is
// seen through the other panel. Text origins are the top-left corners of the first glyph.
struct LabelLayout {
  bool shown = false;  // false when the panel is too small for the boxes
  int scale = 1;
  int imageTextX = 0, imageTextY = 0, maskTextX = 0, maskTextY = 0;
  int boxWidth = 0, boxHeight = 0, windowMargin = 0;
};
inline constexpr int kMaxLabelChars = 18;  // "TV 9.0450 PH -0.50"
LabelLayout labelLayout(int width, int height, int scale);
void drawLabel(Image& image, const LabelLayout& layout, bool maskLayer, const std::string& text);

// ---- Prediction with the simulator -------------------------------------------------------

struct CalibrationScore {
  double brightness = 0;  // B0: mean light reaching the eye (raw transmittance)
  double contrast = 0;    // (B0 - Bn) / (B0 + Bn), Bn the mean at eyes one view to each side
  double uniformity = 0;  // 1 - std/mean across the view (one period box filter), at least 0
  // What the search maximises: (B0 - Bn) / the image layer's mean, the light that reaches this
  // eye and not its neighbours. Uniformity is reported, not optimised: with anti-aliased slits
  // it is dominated by the moire of the slits against the mask's pixel grid, and weighting by
  // it doubled the search's error, to 0.0005 pixels (docs/calibration.md).
  double score = 0;
};

// The display of `physics` looking at calibration patterns made for `assumed` (the display as
// the user believes it is: panels, layer order, gap, distance). Vertical slits look the same
// in every row, so both are simulated as one-row strips of the panels (the x mapping of the
// simulator does not depend on y), with the eye moved to y = 0.
class CalibrationScorer {
 public:
  // eye: display mm. samplesPerPixel: samples across each front-layer pixel. Throws
  // std::invalid_argument if the two displays' panels differ in size, pitch or order.
  CalibrationScorer(const DisplaySpec& assumed, const DisplayDesign& physics, const Vec3d& eye,
                    int screenPeriodPx, double duty = 0, int samplesPerPixel = 8);
  // Uniformity costs a box filter; the search does without it (see score's comment).
  CalibrationScore score(double slitPeriodPx, double phasePx, bool uniformity = true) const;
  // Eyes one view to each side: one image pixel seen across the assumed gap,
  // dx (D - z_M) / g at the eye's distance D (docs/display-geometry.md).
  double viewWidthMm() const { return viewWidthMm_; }
  int groupsAcross() const { return groups_; }

 private:
  DisplaySpec assumed_;
  DisplayDesign physics_;
  Vec3d eye_;
  int screenPeriod_, samples_;
  double duty_, viewWidthMm_;
  int groups_;
  Image imageLayer_;
};

struct PredictionSettings {
  int screenPeriodPx = 0;       // default round(design's)
  double fromPx = 0, toPx = 0;  // default Tx + (1/4 .. 2) (Tv - Tx): g/D from 1/4 to twice
  double duty = 0;
  int samplesPerPixel = 8;
};

struct CalibrationPrediction {
  int screenPeriodPx = 0;
  double slitPeriodPx = 0, phasePx = 0;  // phase in (-Tv/2, Tv/2]
  double distanceOverGap = 0;            // D / g = 1 / (Tr/Tf - 1), G1
  CalibrationScore score;
  double fromPx = 0, toPx = 0, stepPx = 0;  // searched range and the finest period step
  bool atRangeEdge = false;                 // within one coarse step of either end: widen the range
  std::vector<double> periods, periodScores;  // coarse pass: best score over phases
};

// Searches the slit period for the integer screen period in coarse steps of 1/(4N) mask pixels
// (N groups across), each at the best of phases one pixel apart; then the phase at the best
// period in 1/32 pixel steps; then the period ten times finer around it; then the phase again.
// Peaks are interpolated with a parabola. `physics` must have `assumed`'s panels and order.
// This is the contrast optimum; it follows G1 within 1/(2N) pixels when N is 50 groups or
// more. On narrower panels anti-aliasing, which blurs slits that straddle two mask pixels,
// pulls it toward periods whose slits stay on whole pixels (docs/calibration.md).
CalibrationPrediction predictCalibration(const DisplaySpec& assumed, const DisplayDesign& physics,
                                         const Vec3d& eye, const PredictionSettings& settings);

}  // namespace parallax
