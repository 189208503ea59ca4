// Slanted lenticular displays (the Looking Glass family): an LCD or OLED panel under a sheet of
// slanted cylindrical lenses at their focal distance, described by a per-device calibration
// (visual.json). Each subpixel gets a fractional view in [0, 1) from the published formula of the
// Looking Glass shaders (docs/lenticular.md):
//
//   pitch_px = pitch * (screenW / DPI) * cos(atan(1 / slope))   lenses across the width, along x
//   tilt     = screenH / (screenW * slope)
//   view     = fract((u + i / (3 screenW) + v * tilt) * pitch_px - center)
//
// for subpixel slot i of the pixel at screen coordinates (u, v) in [0, 1]^2, v up, with invView
// replacing view by 1 - view. Where the light of view f goes, and what an eye sees of it, is the
// lens optics (LensOptics below, docs/lenticular.md "The optics"): every renderer, interlacer and
// simulator asks these functions. Frame as in docs/display-geometry.md: millimetres, the panel at
// z = 0 with its centre at the origin, x right, y up, z toward the viewer.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "parallax/core/math.h"

namespace parallax {

// Where the R, G and B subpixels of one kind of pixel sit (OLED panels whose subpixels are not
// three vertical stripes), as offsets from the pixel's centre in pixels (x right, y up), as
// visual.json writes them; Looking Glass's readers divide x by screenW and y by screenH before
// the shader adds them to the screen coordinates (u, v).
struct SubpixelCell {
  std::array<double, 3> offsetX{}, offsetY{};  // R, G, B
};

// The quilt a device's content comes in (Looking Glass's tiled views): columns x rows views,
// tiled into a width x height picture. Not in visual.json; presets know their device's.
struct QuiltFormat {
  int columns = 8, rows = 6;
  int width = 3360, height = 3360;
  int views() const { return columns * rows; }
  // One view's tile: the quilt's size over its columns and rows (leftover pixels are padding).
  int tileWidth() const { return width / columns; }
  int tileHeight() const { return height / rows; }
};

// The calibration fields as the device writes them (visual.json).
struct LenticularCalibration {
  std::string source = "<built-in>";            // file name for error messages
  double pitch = 0;                             // lenticules per inch, across the lenticules
  double slope = 0;                             // lens slant: screen pixels down per pixel across
  double center = 0;                            // phase of view 0, in lens periods
  double viewConeDegrees = 0;                   // angle the views of one lens period fan over
  double dpi = 0;                               // panel pixels per inch
  int screenW = 0, screenH = 0;                 // panel pixels
  bool invView = false;                         // view -> 1 - view (the lens inverts; most devices)
  bool flipImageX = false, flipImageY = false;  // the panel is mirrored as the viewer sees it
  bool flipSubpixels = false;                   // BGR instead of RGB stripes
  // Which cell pixel (x, y) uses, y counted from the bottom row (cellIndex): 0 cell 0;
  // 1 checkerboard (x + y) mod 2; 2 alternate columns x mod 2; 3 (y + 2 (x mod 2)) mod 4;
  // 4 alternate rows y mod 2; wrapped by the number of cells.
  int cellPatternMode = 0;
  std::vector<SubpixelCell> subpixelCells;  // empty: RGB (or BGR) stripes a third of a pixel wide
  QuiltFormat quilt;                        // the device's default quilt (a preset's, or 8x6)
  // The unit and its device (display/lenticular_presets.h): the file's serial ("" none), the
  // preset recognised ("portrait"; "" none), and how it was recognised ("serial LKG-P0123").
  std::string serial, device, deviceBasis;
  std::vector<std::string> warnings;  // what the reader defaulted or ignored, one line each
};

inline constexpr int kCellPatternModes = 5;
// The subpixel cell of pixel column x, row yUp (counted from the bottom), as Looking Glass's
// interlacing shader picks it (holoplay-core, the Unity plugin's Lenticular shader).
int cellIndex(const LenticularCalibration& calibration, int x, int yUp);

// How a lens sheet sends the light of its subpixels (docs/lenticular.md, "The optics").
//  - Bundles: all subpixels of one view fraction f leave either in one direction, the angle
//    theta(f) = (f - 1/2) viewCone wherever they are on the panel (Parallel: the calibration's
//    pitch is the lenses' own), or toward one eye point, (C tan theta(f), y, C) at the
//    convergence distance C (Converging: the pitch a camera at C measured, so that the whole
//    panel shows view f to that point; Looking Glass's quilt cameras stand on that line).
//  - The focal spot: the width, in subpixels, of the strip of the panel one eye sees through a
//    lens at once. 0 is an ideal lens (one subpixel seen per lens and row); 3 a pixel-wide spot
//    (each colour channel seen exactly once).
// The default, converging at the design distance with a one-subpixel spot, is derived in
// docs/lenticular.md.
enum class LensBundles { Parallel, Converging };
// Parses "parallel" or "converging"; returns false for anything else.
bool parseLensBundles(const std::string& text, LensBundles& bundles);
const char* lensBundlesName(LensBundles bundles);

struct LensOptics {
  LensBundles bundles = LensBundles::Converging;
  double convergenceDistanceMm = 0;  // C; 0: the design's view distance D (designLenticular)
  double spotWidthSubpixels = 1.0;   // W, from 0 (ideal) to kMaxLensSpotSubpixels
};
inline constexpr double kMaxLensSpotSubpixels = 12.0;

// What follows from a calibration, and where the viewer is assumed to be.
struct LenticularDesign {
  LenticularCalibration calibration;
  double pixelPitchMm = 0;  // 25.4 / DPI
  double widthMm = 0, heightMm = 0;
  double pitchPx = 0;                // pitch_px above: lenses across the screen width, along x
  double tilt = 0;                   // tilt above (negated with flipImageX, as the shaders do)
  double lensSlantDegrees = 0;       // lens axis from vertical: atan(1 / |slope|)
  double lensPitchMm = 0;            // 25.4 / pitch, across the lenticules
  double horizontalLensPitchMm = 0;  // widthMm / pitch_px, along a pixel row
  double pixelsPerLens = 0;          // screenW / pitch_px
  double subpixelsPerLens = 0;       // 3 screenW / pitch_px
  double lenticuleCount = 0;         // lenses that cross the panel: pitch_px (1 + |tilt|)
  double viewDistanceMm = 0;         // the design viewer's distance (vertical perspective)
  double viewZoneWidthMm = 0;        // the view cone's width there: 2 D tan(viewCone / 2)
  int quiltViews = 48;               // the default quilt's views: the display's angular samples
  LensOptics optics;                 // convergenceDistanceMm resolved (D when not given)
};

// The default design distance: where the view cone spans a 1 m wide zone (one or two people
// side by side), D = 500 mm / tan(viewCone / 2).
inline constexpr double kLenticularZoneWidthMm = 1000.0;

// Derives the design and checks the calibration; throws InputError naming calibration.source
// and the key ("/slope: must not be 0"). viewDistanceMm <= 0 picks the default distance. The
// optics' convergence distance 0 becomes the view distance; an optics out of range throws
// std::invalid_argument (requests check theirs first, see checkLensOptics).
LenticularDesign designLenticular(const LenticularCalibration& calibration,
                                  double viewDistanceMm = 0, const LensOptics& optics = {});

// The same design read with other optics (the simulator's readings); convergence distance 0:
// the design's view distance.
LenticularDesign withOptics(const LenticularDesign& design, LensOptics optics);

// Empty when the optics are usable, else what is wrong ("spot width must be from 0 to 12
// subpixels"), for the caller to report under its own field.
std::string lensOpticsProblem(const LensOptics& optics);

// The view fraction in [0, 1) of colour channel `channel` (0 R, 1 G, 2 B) of the pixel in
// framebuffer column x, row y (row 0 at the top, as in images): the published formula at the
// pixel's centre.
double viewFraction(const LenticularDesign& design, int x, int y, int channel);

// The same formula at a continuous framebuffer position (pixel (x, y) covers [x, x+1) x [y, y+1),
// y down); the subpixel's own offset is added. viewFraction(d, x, y, c) is
// viewFractionAt(d, x + 0.5, y + 0.5, c).
double viewFractionAt(const LenticularDesign& design, double filmX, double filmY, int channel);

// Where that subpixel is on the panel as the viewer sees it (mm, z = 0); the three subpixels of a
// pixel are centred on the pixel.
Vec3d subpixelPointMm(const LenticularDesign& design, double filmX, double filmY, int channel);

// The horizontal angle (radians, positive toward +x) into which the lens sends view f:
// (f - 1/2) * viewCone, and its inverse (not wrapped: outside [0, 1) beyond the cone).
double viewAngle(const LenticularDesign& design, double fraction);
double viewFractionOfAngle(const LenticularDesign& design, double angle);

// The optics, per subpixel. The horizontal slope dx/dz (toward the viewer) of the light of view
// fraction f leaving the panel at x = panelX mm: tan theta(f) with parallel bundles,
// (C tan theta(f) - panelX) / C with bundles converging at C.
double lensSlope(const LenticularDesign& design, double panelX, double fraction);
// Its inverse: the view fraction whose light from panelX passes through the eye (not wrapped;
// an eye outside the cone gets a fraction outside [0, 1), which the lens wraps).
double lensFractionSeen(const LenticularDesign& design, double panelX, const Vec3d& eyeMm);
// Where on the design line (z = D) the light of view f from panelX arrives, as the fraction of
// the cone a quilt camera there stands at (quilt camera k of N stands at (k + 1/2) / N): f itself
// when the bundles converge at D; interlace picks its views by this.
double lensQuiltFraction(const LenticularDesign& design, double panelX, double fraction);
// The eye point on the design line at fraction t of the cone: (D tan theta(t), 0, D), the quilt
// cameras' and the dense measure's eyes.
Vec3d lensEyeOnDesignLine(const LenticularDesign& design, double t);

// One subpixel's width in view fraction, delta = 1 / subpixelsPerLens: along a row, the
// subpixels under a lens tile its period, so a subpixel spans delta of the views.
double subpixelViewWidth(const LenticularDesign& design);
// What an eye integrates: the weight with which it sees a subpixel whose view fraction differs
// from the eye's by `difference` (wrapped to [-1/2, 1/2]). The subpixel spans delta of the views
// and the focal spot W delta, so the weight is their overlap over the spot's width (the box delta
// convolved with the box W delta, divided by W delta): for W = 0, 1 inside the subpixel's
// half-open span [-delta/2, delta/2) and 0 elsewhere. Subpixels tiling the period sum to 1.
double lensSpotWeight(const LenticularDesign& design, double difference);
// The same for a part of a subpixel (cut by a lens's edge) spanning the views [low, high]
// relative to the eye's: the overlap with the spot over its width; W = 0: 1 if low <= 0 < high.
double lensSpotWeight(const LenticularDesign& design, double low, double high);
// Where that weight is non-zero: |difference| < (1 + W) delta / 2.
double lensSpotHalfSupport(const LenticularDesign& design);

// The ray a subpixel sample shows: it leaves the panel point with the optics' horizontal slope
// (lensSlope) and, vertically, toward the design viewer's eye line (y = 0, z = D), the one-axis
// perspective of a horizontal-parallax display. `origin` is that point on the viewer's side
// (z = D), and `direction` runs from it to the panel point, normalised to direction.z = -1.
struct LenticularRay {
  Vec3d origin, direction, panelPoint;
  double viewFraction = 0;
};
LenticularRay lenticularRay(const LenticularDesign& design, double filmX, double filmY,
                            int channel);
// The same ray leaving the same panel point, with the view fraction given instead of the
// formula's (a prefilter's sub-ray; the fraction is not wrapped, so it may pass the cone's edge).
LenticularRay lenticularRay(const LenticularDesign& design, double filmX, double filmY, int channel,
                            double viewFraction);

// The view step of one colour channel: neighbouring subpixels of a channel lie one pixel apart
// along a row, so the panel samples each channel's views every pitch_px / screenW, one
// pixel's worth of view fraction (three subpixel widths).
inline double channelViewStep(const LenticularDesign& design) {
  return design.pitchPx / design.calibration.screenW;
}

}  // namespace parallax
