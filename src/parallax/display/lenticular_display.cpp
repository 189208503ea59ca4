// The slanted lenticular display as a DisplayModel: one exact ray per subpixel, in the direction
// its view fraction gives (lenticular.h, docs/lenticular.md).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "parallax/core/lane_kernel.h"
#include "parallax/display/display_model.h"
#include "parallax/display/lenticular_presets.h"

// glibc's vector tangents (libmvec, which libm's link script pulls in as needed): with this
// declaration GCC calls them from vectorised lane loops (_ZGVeN8v_tan with AVX-512,
// _ZGVdN4v_tan with AVX2, _ZGVbN2v_tan otherwise), within 4 ulp of libm's scalar tan. glibc
// declares them itself only under -ffast-math.
extern "C" {
#pragma omp declare simd notinbranch
double tan(double) noexcept;
}

namespace parallax {

namespace {

// What LenticularDisplay::ray reads from the design, fixed per display, so that rays16 can run
// its formulas lane-wise. A subpixel's offset from its pixel (the calibration's stripes, or its
// cells) comes from `offsetX/Y[cell * 3 + channel]` (screen fractions), cell
// `cellOfPattern[pattern]` for the cell pattern of (column, row up); stripes are one cell.
struct LensRayConstants {
  double width = 1, height = 1;  // screenW, screenH (pixels)
  int lastRow = 0;               // screenH - 1
  double tilt = 0, pitchPx = 0, center = 0;
  bool flipX = false, flipY = false, invView = false;
  int cellPatternMode = 0;
  bool hasCells = false;  // the calibration's own cells (else its stripes, as one cell)
  int cellOfPattern[4] = {0, 0, 0, 0};
  double offsetX[3 * 4] = {}, offsetY[3 * 4] = {}, meanOffsetX[4] = {};
  double widthMm = 0, heightMm = 0, viewDistance = 0, convergence = 0, coneRadians = 0;
  bool parallel = false;
  // The prefilter (LenticularDisplay's constructor).
  ViewFilterKind filter = ViewFilterKind::View;
  double viewsAlongRow = 1, pixelsPerLens = 1, unblendedViews = 0, rowsSpread = 1;
};

LensRayConstants lensRayConstants(const LenticularDesign& d) {
  const LenticularCalibration& c = d.calibration;
  LensRayConstants k;
  k.width = c.screenW, k.height = c.screenH, k.lastRow = c.screenH - 1;
  k.tilt = d.tilt, k.pitchPx = d.pitchPx, k.center = c.center;
  k.flipX = c.flipImageX, k.flipY = c.flipImageY, k.invView = c.invView;
  const int cells = std::max<int>(1, int(c.subpixelCells.size()));
  k.cellPatternMode = c.subpixelCells.empty() ? 0 : c.cellPatternMode;
  k.hasCells = !c.subpixelCells.empty();
  for (int pattern = 0; pattern < 4; ++pattern) k.cellOfPattern[pattern] = pattern % cells;
  for (int cell = 0; cell < std::min(cells, 4); ++cell) {
    // In the order and the arithmetic of lenticular.cpp's subpixelOffset and subpixelPointMm.
    double mean = 0;
    for (int channel = 0; channel < 3; ++channel) {
      double dx = 0, dy = 0;
      if (c.subpixelCells.empty()) {
        dx = (c.flipSubpixels ? 2 - channel : channel) / (3.0 * c.screenW);
      } else {
        const SubpixelCell& s = c.subpixelCells[size_t(cell)];
        dx = s.offsetX[size_t(channel)] / c.screenW;
        dy = s.offsetY[size_t(channel)] / c.screenH;
      }
      k.offsetX[cell * 3 + channel] = dx, k.offsetY[cell * 3 + channel] = dy;
      mean += dx / 3.0;
    }
    k.meanOffsetX[cell] = mean;
  }
  k.widthMm = d.widthMm, k.heightMm = d.heightMm;
  k.viewDistance = d.viewDistanceMm, k.convergence = d.optics.convergenceDistanceMm;
  k.coneRadians = c.viewConeDegrees * kPiD / 180.0;
  k.parallel = d.optics.bundles == LensBundles::Parallel;
  return k;
}

// The calibration's cell pattern (lenticular.cpp's cellIndex) of pixel (x, y up), branch-free.
// Integer arithmetic in doubles (exact below 2^53), so that a lane loop holds one type and
// vectorises: a mod 2 and a mod 4 as two's complement `& 1` and `& 3` give them.
inline double parity(double a) {
  return a - 2.0 * std::floor(a * 0.5);
}
inline double modFour(double a) {
  return a - 4.0 * std::floor(a * 0.25);
}

// The cell pattern of pixel (x, y up) (lenticular.cpp's cellIndex before its `% cells`), for the
// calibration's mode m: `isMode[m]` is 1 for it and 0 for the others.
inline double cellPattern(const double isMode[5], double x, double yUp) {
  return isMode[1] * parity(x + yUp) + isMode[2] * parity(x) +
         isMode[3] * modFour(yUp + 2.0 * parity(x)) + isMode[4] * parity(yUp);
}

// table[index] for a whole-number index in [0, n), as selects rather than a gather.
template <int n>
inline double pick(const double (&table)[n], double index) {
  double value = table[0];
  for (int j = 1; j < n; ++j) value = index == double(j) ? table[j] : value;
  return value;
}

// LenticularDisplay::ray for sixteen lanes: the same formulas (viewFractionAt, subpixelPointMm,
// lensSlope, lenticularRay in lenticular.cpp) in the same order, written so that the lane loops
// vectorise. Reciprocals instead of divisions and glibc's vector tangent may change a double's
// last bits, which the float rays absorb (the pictures are the same byte for byte, measured on
// every preset; LenticularDisplay.SixteenLaneRaysAreTheSingleRays bounds the difference). Outside
// the class: GCC cannot make ISA clones of a virtual function (core/lane_kernel.h). `warp` is
// the view filter's warp.
PARALLAX_LANE_KERNEL void lensRays16(const LensRayConstants& k, const ViewFilterWarp& warp,
                                     const float filmX[16], const float filmY[16],
                                     const float sampleU[16], const float sampleV[16],
                                     double origin[3][16], double direction[3][16]) {
  alignas(64) double fx[16], fy[16], channel[16], centreX[16], rowCentre[16], offX[16], offY[16];
  alignas(64) double warped[16], panelX[16], panelY[16], angle[16], slope[16];
  const bool none = k.filter == ViewFilterKind::None;
  const bool period = k.filter == ViewFilterKind::Period;
  for (int i = 0; i < 16; ++i) fx[i] = double(filmX[i]), fy[i] = double(filmY[i]);
  // The filter's warp is a call (a table for the Gaussian): lane by lane, and only where the
  // spread in view is not zero (none from the default spot on).
  const bool spread = !none && !period && k.unblendedViews != 0;
  for (int i = 0; i < 16; ++i)
    warped[i] = spread ? warp(fx[i] - std::floor(fx[i])) * k.unblendedViews : 0.0;
  // The constants as locals, the integer work in doubles (exact) and the flips as arithmetic
  // (1 - u as 1 + (-1) u, exact): every loop holds doubles only, nothing it stores can alias
  // what it reads, and it vectorises.
  double isMode[5], cellOfPattern[4], offsetX[12], offsetY[12], meanOffsetX[4];
  for (int m = 0; m < 5; ++m) isMode[m] = m == k.cellPatternMode ? 1.0 : 0.0;
  for (int j = 0; j < 4; ++j) cellOfPattern[j] = k.cellOfPattern[j];
  for (int j = 0; j < 12; ++j) offsetX[j] = k.offsetX[j], offsetY[j] = k.offsetY[j];
  for (int j = 0; j < 4; ++j) meanOffsetX[j] = k.meanOffsetX[j];
  // Stripes (no cells): one cell, whose offsets depend on the channel only, so that a striped
  // panel pays for no cell pattern (the two cases in loops of their own below).
  const bool cells = k.cellPatternMode != 0 || k.hasCells;
  const double stripeX[3] = {offsetX[0], offsetX[1], offsetX[2]};
  const double width = k.width, height = k.height, tilt = k.tilt, pitchPx = k.pitchPx;
  const double center = k.center, viewsAlongRow = k.viewsAlongRow;
  const double pixelsPerLens = k.pixelsPerLens, rowsSpread = k.rowsSpread;
  const double coneRadians = k.coneRadians, widthMm = k.widthMm, heightMm = k.heightMm;
  const double lastRow = k.lastRow;
  const double inverseWidth = 1.0 / width, inverseHeight = 1.0 / height, third = 1.0 / 3.0;
  const double flipXBase = k.flipX ? 1.0 : 0.0, flipXSign = k.flipX ? -1.0 : 1.0;
  const double flipYBase = k.flipY ? 1.0 : 0.0, flipYSign = k.flipY ? -1.0 : 1.0;
  const double invBase = k.invView ? 1.0 : 0.0, invSign = k.invView ? -1.0 : 1.0;
  const double spreadX = none ? 0.0 : 1.0, spreadY = none ? 0.0 : 1.0;
  const double periodSpread = period ? 1.0 : 0.0, warpSpread = none || period ? 0.0 : 1.0;
  alignas(64) double column[16], panelColumn[16], panelRow[16];
  PARALLAX_SIMD
  for (int i = 0; i < 16; ++i) {
    // Film column 3x + c: panel column x, channel c (column / 3 rounded down, exact: the
    // quotient's fraction is at least 1/6 from a whole number).
    column[i] = std::floor(fx[i]);
    panelColumn[i] = std::floor((column[i] + 0.5) * third);
    channel[i] = column[i] - 3.0 * panelColumn[i];
    panelRow[i] = std::floor(fy[i]);
    centreX[i] = panelColumn[i] + 0.5, rowCentre[i] = panelRow[i] + 0.5;
  }
  // The subpixel's offset in its pixel: by cell and channel, or (stripes) by channel only. Two
  // loops rather than a branch in one, which stops it vectorising.
  if (cells) {
    PARALLAX_SIMD
    for (int i = 0; i < 16; ++i) {
      const double cell =
          pick(cellOfPattern, cellPattern(isMode, panelColumn[i], lastRow - panelRow[i]));
      offX[i] = pick(offsetX, cell * 3.0 + channel[i]);
      offY[i] = pick(offsetY, cell * 3.0 + channel[i]);
    }
  } else {
    PARALLAX_SIMD
    for (int i = 0; i < 16; ++i) offX[i] = pick(stripeX, channel[i]), offY[i] = 0.0;
  }
  PARALLAX_SIMD
  for (int i = 0; i < 16; ++i) {
    // viewFractionAt(x + 1/2, rowCentre, channel): the subpixel's own view.
    const double u = flipXBase + flipXSign * (centreX[i] * inverseWidth);
    const double v = 1.0 - rowCentre[i] * inverseHeight;
    const double phase = (u + flipXSign * offX[i] + (v + offY[i]) * tilt) * pitchPx - center;
    const double f = invBase + invSign * (phase - std::floor(phase));
    const double ownView = f >= 1.0 ? f - 1.0 : f;
    const double across = fx[i] - column[i] - 0.5;
    const double lensOffset = viewsAlongRow * (double(sampleV[i]) - ownView) * pixelsPerLens;
    // With the filter none the central ray: x + 1/2 and the row's centre (the additions of
    // zero are exact).
    panelX[i] = centreX[i] + spreadX * (across * third + lensOffset);
    panelY[i] = rowCentre[i] + spreadY * ((fy[i] - rowCentre[i]) * rowsSpread);
    const double view =
        ownView + periodSpread * (double(sampleU[i]) - 0.5) + warpSpread * warped[i];
    angle[i] = (view - 0.5) * coneRadians;
  }
  PARALLAX_SIMD
  for (int i = 0; i < 16; ++i) slope[i] = tan(angle[i]);
  const double D = k.viewDistance, inverseD = 1.0 / D, inverseC = 1.0 / k.convergence;
  const bool parallel = k.parallel;
  alignas(64) double ox[16], dx[16], dy[16], shiftX[16], shiftY[16];
  // subpixelPointMm(panelX, panelY, channel): the offset of the channel's subpixel from the
  // pixel's mean, in the cell of the panel point's pixel.
  if (cells) {
    PARALLAX_SIMD
    for (int i = 0; i < 16; ++i) {
      const double cell = pick(cellOfPattern, cellPattern(isMode, std::floor(panelX[i]),
                                                          lastRow - std::floor(panelY[i])));
      shiftX[i] = pick(offsetX, cell * 3.0 + channel[i]) - pick(meanOffsetX, cell);
      shiftY[i] = pick(offsetY, cell * 3.0 + channel[i]);
    }
  } else {
    PARALLAX_SIMD
    for (int i = 0; i < 16; ++i)
      shiftX[i] = pick(stripeX, channel[i]) - meanOffsetX[0], shiftY[i] = 0.0;
  }
  PARALLAX_SIMD
  for (int i = 0; i < 16; ++i) {
    const double u = panelX[i] * inverseWidth + shiftX[i];
    const double v = 1.0 - panelY[i] * inverseHeight + shiftY[i];
    const double pointX = (flipXBase + flipXSign * u - 0.5) * widthMm;
    const double pointY = (flipYBase + flipYSign * v - 0.5) * heightMm;
    // lensSlope, then lenticularRay's origin on the design line and direction.
    const double lens = parallel ? slope[i] : slope[i] - pointX * inverseC;
    ox[i] = pointX + D * lens;
    dx[i] = (pointX - ox[i]) * inverseD;
    dy[i] = pointY * inverseD;
  }
  for (int i = 0; i < 16; ++i) {
    origin[0][i] = ox[i], origin[1][i] = 0.0, origin[2][i] = D;
    direction[0][i] = dx[i], direction[1][i] = dy[i], direction[2][i] = -1.0;
  }
}

class LenticularDisplay final : public DisplayModel {
 public:
  LenticularDisplay(const LenticularDesign& design, const ViewFilter& filter)
      : design_(design), filterKind_(filter.kind), warp_(filter) {
    // Which way views run along a row (+1: the view grows with the column): a pixel's step.
    const double step = viewFraction(design_, 1, 0, 0) - viewFraction(design_, 0, 0, 0);
    viewsAlongRow_ = step - std::round(step) >= 0 ? 1.0 : -1.0;
    // The prefilter's spans, fixed by the optics (ray() explains them): in view, the part of a
    // subpixel's span the spot leaves unblended; down the panel, the rows of the colour cycle
    // while the spot leaves rows without the subpixel's channel (W <= 1), one row from W = 2.
    const double spot = design_.optics.spotWidthSubpixels;
    unblendedViews_ = std::max(0.0, 1.0 - spot) * subpixelViewWidth(design_);
    const double cycleRows = std::max(1.0, std::fabs(design_.calibration.slope));
    rowsSpread_ = 1.0 + (cycleRows - 1.0) * std::clamp(2.0 - spot, 0.0, 1.0);
    lanes_ = lensRayConstants(design_);
    lanes_.filter = filterKind_;
    lanes_.viewsAlongRow = viewsAlongRow_, lanes_.pixelsPerLens = design_.pixelsPerLens;
    lanes_.unblendedViews = unblendedViews_, lanes_.rowsSpread = rowsSpread_;
  }

  DisplayKind kind() const override { return DisplayKind::Lenticular; }
  const std::string& source() const override { return design_.calibration.source; }
  DisplayWindow window() const override { return displayWindow(design_); }
  FilmLayout film() const override {
    const int w = design_.calibration.screenW, h = design_.calibration.screenH;
    return {3 * w, h, w, h, true};
  }
  int channelOfColumn(int column) const override { return column % 3; }

  // Film column 3x + c is channel c of panel column x, wherever the calibration puts that
  // subpixel. A sample's position inside its column moves the ray's panel point across the
  // subpixel's third of the pixel, and its view over the part of the subpixel's span of views
  // that the lens's focal spot does not already blend: (1 - W) of it for a spot W subpixels
  // wide, none from W = 1 on (docs/lenticular.md, "Prefilter"). Its second angular sample
  // places the ray across the lens the subpixel sits under. The column's centre with the
  // central samples casts exactly the published formula's ray.
  DisplayRay ray(double filmX, double filmY, double u, double v) const override {
    const int column = int(std::floor(filmX));
    const int x = column / 3, channel = column % 3;
    const double rowCentre = std::floor(filmY) + 0.5;
    const double ownView = viewFractionAt(design_, x + 0.5, rowCentre, channel);
    LenticularRay r;
    if (filterKind_ == ViewFilterKind::None) {
      r = lenticularRay(design_, x + 0.5, rowCentre, channel, ownView);
    } else {
      const double across = filmX - column - 0.5;  // [-1/2, 1/2) across the subpixel
      // The second angular sample places the ray across the lens the subpixel sits under: an
      // eye sees the subpixel over that lens's whole width (from view 0 to view 1 along the
      // row), so its light is the average over the lens of what those eyes should see there.
      const double lensOffset = viewsAlongRow_ * (v - ownView) * design_.pixelsPerLens;
      const double panelX = x + 0.5 + across / 3.0 + lensOffset;
      // Spread in view: what the eye's spot does not integrate by itself. An eye at view f sees
      // the subpixels' spans blended by the spot: spot (W delta) * span (delta). Rays spread
      // over that blend again would blur twice; spread over the span only where the spot is
      // narrower than the subpixel, the render's own box and the spot together make the span.
      // Period: anywhere in the lens's cone (the old cell's analogue, for comparison).
      const double view = filterKind_ == ViewFilterKind::Period
                              ? ownView + (u - 0.5)
                              : ownView + warp_(across + 0.5) * unblendedViews_;
      // Down the panel: with a spot up to a subpixel wide (W <= 1) the eye sees a channel only
      // in the rows where that channel's subpixel is at its view, a run of rows in every |slope|
      // (the lenses' colour cycle, which the eye does not resolve: docs/lenticular.md, "What an
      // eye integrates"). The subpixel's light is then the average over the |slope| rows around
      // its own of what the eye should see there; a ray from its own row only aliases fine
      // horizontal detail into colour moire. From W = 2 on every row shows the eye every
      // channel, and its own acuity does the averaging: the rays stay in their row.
      const double panelY = rowCentre + (filmY - rowCentre) * rowsSpread_;
      r = lenticularRay(design_, panelX, panelY, channel, view);
    }
    return {r.origin, r.direction};
  }
  void rays16(const float filmX[16], const float filmY[16], const float u[16], const float v[16],
              double origin[3][16], double direction[3][16]) const override {
    lensRays16(lanes_, warp_, filmX, filmY, u, v, origin, direction);
  }
  bool columnFans() const override { return false; }

  // The views of a lenticular panel are continuous; its angular samples for quilts, direct
  // mapping and the dense measure are the device's quilt views, evenly across the cone.
  int viewCount() const override { return design_.quiltViews; }
  int viewIndex(int column, int row) const override {
    const double f = viewFraction(design_, column / 3, row, column % 3);
    return std::clamp(int(std::floor(f * design_.quiltViews)), 0, design_.quiltViews - 1);
  }
  Vec3d viewPosition(int view) const override {
    return eyeAcrossZone((view + 0.5) / design_.quiltViews);
  }
  // Beyond the cone (t outside [0, 1], a sweep wider than the zone) the angle goes on, up to
  // 80 degrees to either side, where the panel is seen edge-on.
  Vec3d eyeAcrossZone(double t) const override {
    const double limit = 80.0 / design_.calibration.viewConeDegrees;
    return lensEyeOnDesignLine(design_, std::clamp(t, 0.5 - limit, 0.5 + limit));
  }
  double viewZoneWidthMm() const override { return design_.viewZoneWidthMm; }
  bool horizontalParallaxOnly() const override { return true; }
  std::vector<DesignFigure> designReport() const override {
    const LenticularDesign& d = design_;
    return {{"pixels_per_lens", d.pixelsPerLens, ""},
            {"lens_pitch", d.lensPitchMm, "mm"},
            {"lens_slant", d.lensSlantDegrees, "deg"},
            {"view_cone", d.calibration.viewConeDegrees, "deg"},
            {"view_distance", d.viewDistanceMm, "mm"},
            {"view_zone_width", d.viewZoneWidthMm, "mm"},
            {"views", double(d.quiltViews), ""},
            {"lens_spot", d.optics.spotWidthSubpixels, "subpixels"}};
  }
  QuiltShape defaultQuilt() const override {
    return {design_.calibration.quilt.columns, design_.calibration.quilt.rows};
  }
  // The device quilt's size shared among the views.
  PanelSize quiltTile(int columns, int rows) const override {
    return {design_.calibration.quilt.width / columns, design_.calibration.quilt.height / rows};
  }
  // A unit's own file (not a preset): which device it was recognised as decides its quilt.
  std::string deviceNote() const override {
    const LenticularCalibration& c = design_.calibration;
    if (c.source.rfind("lkg:", 0) == 0) return "";
    char text[160];
    std::snprintf(text, sizeof text, "%dx%d views on %dx%d", c.quilt.columns, c.quilt.rows,
                  c.quilt.width, c.quilt.height);
    const std::string quilt = text;
    if (!c.device.empty())
      return c.source + " is a " + lenticularPresetDescription(c.device) + " (lkg:" + c.device +
             ", by its " + c.deviceBasis + "): its default quilt " + quilt;
    std::snprintf(text, sizeof text, " (%dx%d pixels at %g DPI", c.screenW, c.screenH, c.dpi);
    return c.source + text + (c.serial.empty() ? "" : ", serial " + c.serial) +
           ") is no Looking Glass device parallax knows: its default quilt is derived from the "
           "panel, " +
           quilt;
  }
  std::string summaryClause() const override {
    char text[96];
    std::snprintf(text, sizeof text, "%.2f pixels per lens, views over %.0f degrees; ",
                  design_.pixelsPerLens, design_.calibration.viewConeDegrees);
    return text;
  }
  const LenticularDesign* lenticularDesign() const override { return &design_; }

 private:
  LenticularDesign design_;
  ViewFilterKind filterKind_;
  double viewsAlongRow_ = 1;
  double unblendedViews_ = 0;  // the prefilter's spread in view (a view fraction)
  double rowsSpread_ = 1;      // and down the panel (rows)
  LensRayConstants lanes_;     // the same, for rays16

 public:
  bool centralRayOnly() const override { return filterKind_ == ViewFilterKind::None; }

 private:
  ViewFilterWarp warp_;
};

}  // namespace

DisplayWindow displayWindow(const LenticularDesign& design) {
  return {design.widthMm, design.heightMm, {0, 0, design.viewDistanceMm}};
}

std::unique_ptr<DisplayModel> makeLenticularDisplay(const LenticularDesign& design,
                                                    const ViewFilter& filter) {
  return std::make_unique<LenticularDisplay>(design, filter);
}

}  // namespace parallax
