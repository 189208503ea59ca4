// Barrier design: the relations G1-G4 of docs/display-geometry.md.
#include "parallax/display/display.h"

#include <cmath>
#include <sstream>

#include "parallax/core/error.h"

namespace parallax {

namespace {

std::string number(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

const Panel& frontPanel(const DisplaySpec& spec) {
  return spec.order == LayerOrder::BarrierBack ? spec.imagePanel : spec.maskPanel;
}

}  // namespace

double DisplayDesign::imageLayerZ() const {
  return spec.order == LayerOrder::BarrierBack ? 0.0 : -gapMm;
}
double DisplayDesign::maskLayerZ() const {
  return spec.order == LayerOrder::BarrierBack ? -gapMm : 0.0;
}
double DisplayDesign::frontWidthMm() const {
  return frontPanel(spec).widthMm();
}
double DisplayDesign::frontHeightMm() const {
  return frontPanel(spec).heightMm();
}

double DisplayDesign::adjacentViewDisparityMm(double depthMm) const {
  return viewWidthMm * std::abs(depthMm) / (viewDistanceMm - depthMm);
}

DisplaySpec defaultDisplaySpec() {
  return DisplaySpec{};
}

DisplayDesign designDisplay(const DisplaySpec& spec) {
  const auto fail = [&spec](const std::string& key, const std::string& message) {
    return InputError(spec.source, key, message);
  };
  // A quantity outside its physically sensible range (display.h, "Ranges").
  const auto requireRange = [&fail](const std::string& key, double v, const DisplayRange& r) {
    if (!(v >= r.lowest && v <= r.highest) || (r.openBelow && v == r.lowest))
      throw fail(key, std::string("must be ") + (r.openBelow ? "above " : "from ") +
                          number(r.lowest) + (r.openBelow ? " and up to " : " to ") +
                          number(r.highest) + " " + r.unit + " (got " + number(v) + ")");
  };
  for (const auto& [key, panel] :
       {std::pair{"/image_layer", &spec.imagePanel}, std::pair{"/mask_layer", &spec.maskPanel}}) {
    if (panel->width < 1 || panel->height < 1 || panel->width > kMaxPanelPixels ||
        panel->height > kMaxPanelPixels)
      throw fail(std::string(key) + "/resolution", "must be from 1x1 to " +
                                                       std::to_string(kMaxPanelPixels) + "x" +
                                                       std::to_string(kMaxPanelPixels) + " pixels");
    if (!(panel->pitchMm > 0) || !std::isfinite(panel->pitchMm))
      throw fail(std::string(key) + "/pixel_pitch_mm", "must be a positive number");
    requireRange(std::string(key) + "/pixel_pitch_mm", panel->pitchMm, kPixelPitchRange);
  }
  const double g = spec.gapMm;
  if (!(g > 0) || !std::isfinite(g))
    throw fail("/gap_mm", "must be positive (got " + number(g) + ")");
  requireRange("/gap_mm", g, kGapRange);
  if (spec.viewDistanceMm) requireRange("/view_distance_mm", *spec.viewDistanceMm, kDistanceRange);
  requireRange("/view_zone/center_x_mm", spec.viewZoneCenterXMm, kOffsetRange);
  requireRange("/view_zone/height_mm", spec.viewZoneHeightMm, kOffsetRange);
  if (spec.viewZoneWidthMm)
    requireRange("/view_zone/width_mm", *spec.viewZoneWidthMm, kZoneWidthRange);
  if (spec.views) requireRange("/views", *spec.views, kPeriodPxRange);
  if (spec.screenPeriodPx) requireRange("/screen_period_px", *spec.screenPeriodPx, kPeriodPxRange);
  if (spec.slitPeriodPx) requireRange("/slit_period_px", *spec.slitPeriodPx, kPeriodPxRange);
  {
    const MaskSpec& m = spec.mask;
    requireRange("/mask/phase_px", m.phasePx, kShiftPxRange);
    requireRange("/mask/panel_offset_px", m.panelOffsetPx, kShiftPxRange);
    requireRange("/mask/amplitude_mm", m.wiggleAmplitudeMm, kWiggleRange);
    requireRange("/mask/wavelength_mm", m.wiggleWavelengthMm, kWiggleRange);
    requireRange("/mask/vertical_period_px", m.verticalPeriodPx,
                 DisplayRange{0, kPeriodPxRange.highest, "mask pixels", false});
  }
  if (spec.virtualGapMm) requireRange("/virtual/gap_mm", *spec.virtualGapMm, kGapRange);
  if (spec.virtualDistanceMm && !std::isinf(*spec.virtualDistanceMm))
    requireRange("/virtual/distance_mm", *spec.virtualDistanceMm, kDistanceRange);

  DisplayDesign d;
  d.spec = spec;
  d.gapMm = g;
  const double dxImage = spec.imagePanel.pitchMm, dxMask = spec.maskPanel.pitchMm;
  const bool imageInFront = spec.order == LayerOrder::BarrierBack;
  // G1: rear period / front period = (D + g) / D.
  const auto rearOverFront = [g](double D) { return (D + g) / D; };

  const bool measured = spec.screenPeriodPx || spec.slitPeriodPx;
  if (measured) {
    if (!spec.screenPeriodPx || !spec.slitPeriodPx)
      throw fail(spec.screenPeriodPx ? "/slit_period_px" : "/screen_period_px",
                 "measured periods need both screen_period_px and slit_period_px");
    d.screenPeriodMm = *spec.screenPeriodPx * dxImage;
    d.slitPeriodMm = *spec.slitPeriodPx * dxMask;
    const double front = imageInFront ? d.screenPeriodMm : d.slitPeriodMm;
    const double rear = imageInFront ? d.slitPeriodMm : d.screenPeriodMm;
    if (!(rear > front))
      throw fail("/slit_period_px",
                 std::string("G1 needs the rear period to exceed the front period (Tr/Tf = "
                             "(D+g)/D > 1); in this layer order the ") +
                     (imageInFront ? "slit period must exceed the screen period"
                                   : "slit period must be shorter than the screen period") +
                     " (got Tx = " + number(d.screenPeriodMm) +
                     " mm, Tv = " + number(d.slitPeriodMm) + " mm)");
    d.viewDistanceMm = g / (rear / front - 1.0);
    if (!(d.viewDistanceMm >= kDistanceRange.lowest && d.viewDistanceMm <= kDistanceRange.highest))
      throw fail("/slit_period_px", "the measured periods give a viewing distance of " +
                                        number(d.viewDistanceMm) + " mm (G1), outside " +
                                        number(kDistanceRange.lowest) + " to " +
                                        number(kDistanceRange.highest) + " mm");
    if (spec.viewDistanceMm &&
        std::abs(*spec.viewDistanceMm - d.viewDistanceMm) > 0.01 * d.viewDistanceMm)
      throw fail("/view_distance_mm", "contradicts the measured periods, which give D = " +
                                          number(d.viewDistanceMm) + " mm (G1); omit one");
  } else {
    if (!spec.viewDistanceMm) throw fail("/view_distance_mm", "is required");
    const double D = *spec.viewDistanceMm;
    if (!(D > 0) || !std::isfinite(D))
      throw fail("/view_distance_mm", "must be positive and finite (got " + number(D) + ")");
    d.viewDistanceMm = D;
    double front = 0, rear = 0;
    if (spec.viewZoneWidthMm) {
      if (spec.views) throw fail("/views", "give either views or view_zone/width_mm, not both");
      const double S = *spec.viewZoneWidthMm;
      if (!(S > 0)) throw fail("/view_zone/width_mm", "must be positive");
      rear = S * g / D;  // G2: S = Tr D / g
      front = rear / rearOverFront(D);
    } else {
      if (!spec.views) throw fail("/views", "give views, view_zone/width_mm or measured periods");
      const double screen = *spec.views * dxImage;
      (imageInFront ? front : rear) = screen;
      if (imageInFront)
        rear = screen * rearOverFront(D);
      else
        front = screen / rearOverFront(D);
    }
    d.screenPeriodMm = imageInFront ? front : rear;
    d.slitPeriodMm = imageInFront ? rear : front;
  }
  d.screenPeriodPx = d.screenPeriodMm / dxImage;
  d.slitPeriodPx = d.slitPeriodMm / dxMask;
  d.views = d.screenPeriodPx;
  const std::string periodKey =
      measured ? "/screen_period_px" : (spec.viewZoneWidthMm ? "/view_zone/width_mm" : "/views");
  if (d.screenPeriodPx < 2.0)
    throw fail(periodKey, "fewer than 2 pixels per group (Tx/dx = " + number(d.screenPeriodPx) +
                              "): no parallax is left");
  if (d.slitPeriodPx < 2.0)
    throw fail(measured ? "/slit_period_px" : periodKey,
               "the slit period is " + number(d.slitPeriodPx) +
                   " mask pixels; the mask needs at least 2 pixels per period");
  if (d.screenPeriodMm > frontPanel(spec).widthMm())
    throw fail(periodKey, "one group is wider than the display");

  const double rear = imageInFront ? d.slitPeriodMm : d.screenPeriodMm;
  d.viewZoneWidthMm = rear * d.viewDistanceMm / g;  // G2
  d.viewWidthMm = d.viewZoneWidthMm / d.views;
  // One aperture serves each whole group of the image layer.
  d.aperturesAcross = std::floor(spec.imagePanel.widthMm() / d.screenPeriodMm + 1e-9);
  d.apertureSpanMm = (d.aperturesAcross - 1) * d.slitPeriodMm;  // G3: Sv = (N - 1) Tv
  d.depthOfFieldMm = g * d.slitPeriodMm / dxImage;              // G4
  // The paper's D_max = D S / (Sv - S); only meaningful when the apertures span more than S.
  d.farthestConsistentDistanceMm =
      d.apertureSpanMm > d.viewZoneWidthMm
          ? d.viewDistanceMm * d.viewZoneWidthMm / (d.apertureSpanMm - d.viewZoneWidthMm)
          : kInfinity;

  const MaskSpec& m = spec.mask;
  if (!(m.dutyCycle > 0 && m.dutyCycle <= 1))
    throw fail("/mask/duty_cycle", "must be in (0, 1] (got " + number(m.dutyCycle) + ")");
  if (m.kind == MaskKind::Slanted && !(std::abs(m.slantDegrees) < 80))
    throw fail("/mask/angle_deg", "must be between -80 and 80 degrees from vertical");
  if (m.kind == MaskKind::Wiggling && !(m.wiggleWavelengthMm > 0))
    throw fail("/mask/wavelength_mm", "a wiggling mask needs a positive wavelength");
  if (m.kind == MaskKind::Jittered && !(m.jitterAmplitude >= 0 && m.jitterAmplitude < 0.5))
    throw fail("/mask/jitter", "must be in [0, 0.5) slit periods, or slits would swap order");
  if (m.kind == MaskKind::Jittered && m.jitterAmplitude + 0.5 * m.dutyCycle >= 0.5)
    throw fail("/mask/jitter",
               "jitter + duty_cycle / 2 must stay below 0.5 periods, or "
               "neighbouring slits would overlap");
  if (m.kind == MaskKind::Pinholes) {
    if (!(m.verticalPeriodPx >= 2))
      throw fail("/mask/vertical_period_px",
                 "a pinhole grid needs a vertical period of at least 2 mask pixels");
    d.aperturesDown = std::floor(spec.maskPanel.heightMm() / (m.verticalPeriodPx * dxMask));
  }
  {
    const double halfWidth = 0.5 * spec.imagePanel.widthMm();
    const double groupIndex = std::round(halfWidth / d.screenPeriodMm - 0.5);
    const double groupCentre = -halfWidth + (groupIndex + 0.5) * d.screenPeriodMm;
    const double e = spec.viewZoneCenterXMm, D = d.viewDistanceMm;
    d.apertureOriginMm = e + (groupCentre - e) * (D - d.maskLayerZ()) / (D - d.imageLayerZ());
  }
  if (spec.subpixelRays && spec.imagePanel.subpixels == SubpixelOrder::None)
    throw fail("/subpixel_rays", "needs an image layer whose subpixels are RGB or BGR");
  d.virtualGapMm = spec.virtualGapMm.value_or(g);
  d.virtualDistanceMm = spec.virtualDistanceMm.value_or(d.viewDistanceMm);
  if (!(d.virtualGapMm > 0) || !std::isfinite(d.virtualGapMm))
    throw fail("/virtual/gap_mm", "must be positive");
  if (!(d.virtualDistanceMm > 0))
    throw fail("/virtual/distance_mm", "must be positive or \"infinity\"");
  return d;
}

int interleavedViewCount(const DisplayDesign& design) {
  return pixelViewCount(design) * (design.spec.subpixelRays ? 3 : 1);
}

int pixelViewCount(const DisplayDesign& design) {
  return std::max(1, int(std::lround(design.screenPeriodPx)));
}

}  // namespace parallax
