// The slanted lenticular display as a DisplayModel: one exact ray per subpixel, in the direction
// its view fraction gives (lenticular.h, docs/lenticular.md).
#include <algorithm>
#include <cmath>

#include "parallax/display/display_model.h"

namespace parallax {

namespace {

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
  const LenticularDesign* lenticularDesign() const override { return &design_; }

 private:
  LenticularDesign design_;
  ViewFilterKind filterKind_;
  double viewsAlongRow_ = 1;
  double unblendedViews_ = 0;  // the prefilter's spread in view (a view fraction)
  double rowsSpread_ = 1;      // and down the panel (rows)

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
