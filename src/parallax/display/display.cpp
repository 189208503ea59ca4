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

namespace {

InputError refusal(const DisplaySpec& spec, const std::string& key, const std::string& message) {
  return InputError(spec.source, key, message);
}

// A quantity outside its physically sensible range (display.h, "Ranges").
void requireRange(const DisplaySpec& spec, const std::string& key, double v,
                  const DisplayRange& r) {
  if (!(v >= r.lowest && v <= r.highest) || (r.openBelow && v == r.lowest))
    throw refusal(spec, key,
                  std::string("must be ") + (r.openBelow ? "above " : "from ") + number(r.lowest) +
                      (r.openBelow ? " and up to " : " to ") + number(r.highest) + " " + r.unit +
                      " (got " + number(v) + ")");
}

// Every given quantity within its range, the camera's too, before any relation is derived.
void checkRanges(const DisplaySpec& spec, const BarrierCameraSettings& camera) {
  for (const auto& [key, panel] :
       {std::pair{"/image_layer", &spec.imagePanel}, std::pair{"/mask_layer", &spec.maskPanel}}) {
    if (panel->width < 1 || panel->height < 1 || panel->width > kMaxPanelPixels ||
        panel->height > kMaxPanelPixels)
      throw refusal(spec, std::string(key) + "/resolution",
                    "must be from 1x1 to " + std::to_string(kMaxPanelPixels) + "x" +
                        std::to_string(kMaxPanelPixels) + " pixels");
    if (!(panel->pitchMm > 0) || !std::isfinite(panel->pitchMm))
      throw refusal(spec, std::string(key) + "/pixel_pitch_mm", "must be a positive number");
    requireRange(spec, std::string(key) + "/pixel_pitch_mm", panel->pitchMm, kPixelPitchRange);
  }
  const double g = spec.gapMm;
  if (!(g > 0) || !std::isfinite(g))
    throw refusal(spec, "/gap_mm", "must be positive (got " + number(g) + ")");
  requireRange(spec, "/gap_mm", g, kGapRange);
  if (spec.viewDistanceMm)
    requireRange(spec, "/view_distance_mm", *spec.viewDistanceMm, kDistanceRange);
  requireRange(spec, "/view_zone/center_x_mm", spec.viewZoneCenterXMm, kOffsetRange);
  requireRange(spec, "/view_zone/height_mm", spec.viewZoneHeightMm, kOffsetRange);
  if (spec.viewZoneWidthMm)
    requireRange(spec, "/view_zone/width_mm", *spec.viewZoneWidthMm, kZoneWidthRange);
  if (spec.views) requireRange(spec, "/views", *spec.views, kPeriodPxRange);
  if (spec.screenPeriodPx)
    requireRange(spec, "/screen_period_px", *spec.screenPeriodPx, kPeriodPxRange);
  if (spec.slitPeriodPx) requireRange(spec, "/slit_period_px", *spec.slitPeriodPx, kPeriodPxRange);
  const MaskSpec& m = spec.mask;
  requireRange(spec, "/mask/phase_px", m.phasePx, kShiftPxRange);
  requireRange(spec, "/mask/panel_offset_px", m.panelOffsetPx, kShiftPxRange);
  requireRange(spec, "/mask/amplitude_mm", m.wiggleAmplitudeMm, kWiggleRange);
  requireRange(spec, "/mask/wavelength_mm", m.wiggleWavelengthMm, kWiggleRange);
  requireRange(spec, "/mask/vertical_period_px", m.verticalPeriodPx,
               DisplayRange{0, kPeriodPxRange.highest, "mask pixels", false});
  if (camera.virtualGapMm) requireRange(spec, "/virtual/gap_mm", *camera.virtualGapMm, kGapRange);
  if (camera.virtualDistanceMm && !std::isinf(*camera.virtualDistanceMm))
    requireRange(spec, "/virtual/distance_mm", *camera.virtualDistanceMm, kDistanceRange);
}

// G1: rear period / front period = (D + g) / D.
double rearOverFront(double g, double D) {
  return (D + g) / D;
}

// The measured periods Tx and Tv, and the distance D they give (G1).
void measuredPeriods(const DisplaySpec& spec, DisplayDesign& d) {
  const double g = spec.gapMm;
  const bool imageInFront = spec.order == LayerOrder::BarrierBack;
  if (!spec.screenPeriodPx || !spec.slitPeriodPx)
    throw refusal(spec, spec.screenPeriodPx ? "/slit_period_px" : "/screen_period_px",
                  "measured periods need both screen_period_px and slit_period_px");
  d.screenPeriodMm = *spec.screenPeriodPx * spec.imagePanel.pitchMm;
  d.slitPeriodMm = *spec.slitPeriodPx * spec.maskPanel.pitchMm;
  const double front = imageInFront ? d.screenPeriodMm : d.slitPeriodMm;
  const double rear = imageInFront ? d.slitPeriodMm : d.screenPeriodMm;
  if (!(rear > front))
    throw refusal(spec, "/slit_period_px",
                  std::string("G1 needs the rear period to exceed the front period (Tr/Tf = "
                              "(D+g)/D > 1); in this layer order the ") +
                      (imageInFront ? "slit period must exceed the screen period"
                                    : "slit period must be shorter than the screen period") +
                      " (got Tx = " + number(d.screenPeriodMm) +
                      " mm, Tv = " + number(d.slitPeriodMm) + " mm)");
  d.viewDistanceMm = g / (rear / front - 1.0);
  if (!(d.viewDistanceMm >= kDistanceRange.lowest && d.viewDistanceMm <= kDistanceRange.highest))
    throw refusal(spec, "/slit_period_px",
                  "the measured periods give a viewing distance of " + number(d.viewDistanceMm) +
                      " mm (G1), outside " + number(kDistanceRange.lowest) + " to " +
                      number(kDistanceRange.highest) + " mm");
  if (spec.viewDistanceMm &&
      std::abs(*spec.viewDistanceMm - d.viewDistanceMm) > 0.01 * d.viewDistanceMm)
    throw refusal(spec, "/view_distance_mm",
                  "contradicts the measured periods, which give D = " + number(d.viewDistanceMm) +
                      " mm (G1); omit one");
}

// The periods Tx and Tv from the distance D and either the views (G1) or the zone width (G2).
void givenPeriods(const DisplaySpec& spec, DisplayDesign& d) {
  const double g = spec.gapMm;
  const bool imageInFront = spec.order == LayerOrder::BarrierBack;
  if (!spec.viewDistanceMm) throw refusal(spec, "/view_distance_mm", "is required");
  const double D = *spec.viewDistanceMm;
  if (!(D > 0) || !std::isfinite(D))
    throw refusal(spec, "/view_distance_mm", "must be positive and finite (got " + number(D) + ")");
  d.viewDistanceMm = D;
  double front = 0, rear = 0;
  if (spec.viewZoneWidthMm) {
    if (spec.views)
      throw refusal(spec, "/views", "give either views or view_zone/width_mm, not both");
    const double S = *spec.viewZoneWidthMm;
    if (!(S > 0)) throw refusal(spec, "/view_zone/width_mm", "must be positive");
    rear = S * g / D;  // G2: S = Tr D / g
    front = rear / rearOverFront(g, D);
  } else {
    if (!spec.views)
      throw refusal(spec, "/views", "give views, view_zone/width_mm or measured periods");
    const double screen = *spec.views * spec.imagePanel.pitchMm;
    (imageInFront ? front : rear) = screen;
    if (imageInFront)
      rear = screen * rearOverFront(g, D);
    else
      front = screen / rearOverFront(g, D);
  }
  d.screenPeriodMm = imageInFront ? front : rear;
  d.slitPeriodMm = imageInFront ? rear : front;
}

// The periods in pixels and what follows from them: the views, S (G2), Sv (G3), the depth of
// field (G4) and the farthest consistent distance.
void deriveViews(const DisplaySpec& spec, bool measured, DisplayDesign& d) {
  const double g = spec.gapMm, dxImage = spec.imagePanel.pitchMm;
  const bool imageInFront = spec.order == LayerOrder::BarrierBack;
  d.screenPeriodPx = d.screenPeriodMm / dxImage;
  d.slitPeriodPx = d.slitPeriodMm / spec.maskPanel.pitchMm;
  d.views = d.screenPeriodPx;
  const std::string periodKey =
      measured ? "/screen_period_px" : (spec.viewZoneWidthMm ? "/view_zone/width_mm" : "/views");
  if (d.screenPeriodPx < 2.0)
    throw refusal(spec, periodKey,
                  "fewer than 2 pixels per group (Tx/dx = " + number(d.screenPeriodPx) +
                      "): no parallax is left");
  if (d.slitPeriodPx < 2.0)
    throw refusal(spec, measured ? "/slit_period_px" : periodKey,
                  "the slit period is " + number(d.slitPeriodPx) +
                      " mask pixels; the mask needs at least 2 pixels per period");
  if (d.screenPeriodMm > frontPanel(spec).widthMm())
    throw refusal(spec, periodKey, "one group is wider than the display");

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
}

// The mask's own parameters, the pinhole rows, and where aperture 0 lies.
void deriveApertures(const DisplaySpec& spec, DisplayDesign& d) {
  const MaskSpec& m = spec.mask;
  if (!(m.dutyCycle > 0 && m.dutyCycle <= 1))
    throw refusal(spec, "/mask/duty_cycle", "must be in (0, 1] (got " + number(m.dutyCycle) + ")");
  if (m.kind == MaskKind::Slanted && !(std::abs(m.slantDegrees) < 80))
    throw refusal(spec, "/mask/angle_deg", "must be between -80 and 80 degrees from vertical");
  if (m.kind == MaskKind::Wiggling && !(m.wiggleWavelengthMm > 0))
    throw refusal(spec, "/mask/wavelength_mm", "a wiggling mask needs a positive wavelength");
  if (m.kind == MaskKind::Jittered && !(m.jitterAmplitude >= 0 && m.jitterAmplitude < 0.5))
    throw refusal(spec, "/mask/jitter",
                  "must be in [0, 0.5) slit periods, or slits would swap order");
  if (m.kind == MaskKind::Jittered && m.jitterAmplitude + 0.5 * m.dutyCycle >= 0.5)
    throw refusal(spec, "/mask/jitter",
                  "jitter + duty_cycle / 2 must stay below 0.5 periods, or "
                  "neighbouring slits would overlap");
  if (m.kind == MaskKind::Pinholes) {
    if (!(m.verticalPeriodPx >= 2))
      throw refusal(spec, "/mask/vertical_period_px",
                    "a pinhole grid needs a vertical period of at least 2 mask pixels");
    d.aperturesDown =
        std::floor(spec.maskPanel.heightMm() / (m.verticalPeriodPx * spec.maskPanel.pitchMm));
  }
  const double halfWidth = 0.5 * spec.imagePanel.widthMm();
  const double groupIndex = std::round(halfWidth / d.screenPeriodMm - 0.5);
  const double groupCentre = -halfWidth + (groupIndex + 0.5) * d.screenPeriodMm;
  const double e = spec.viewZoneCenterXMm, D = d.viewDistanceMm;
  d.apertureOriginMm = e + (groupCentre - e) * (D - d.maskLayerZ()) / (D - d.imageLayerZ());
}

// The camera's choices: subpixel rays, and the virtual gap g' and distance D' (section 2.3).
void applyCamera(const DisplaySpec& spec, const BarrierCameraSettings& camera, DisplayDesign& d) {
  d.camera = camera;
  if (camera.subpixelRays && spec.imagePanel.subpixels == SubpixelOrder::None)
    throw refusal(spec, "/subpixel_rays", "needs an image layer whose subpixels are RGB or BGR");
  d.virtualGapMm = camera.virtualGapMm.value_or(d.gapMm);
  d.virtualDistanceMm = camera.virtualDistanceMm.value_or(d.viewDistanceMm);
  if (!(d.virtualGapMm > 0) || !std::isfinite(d.virtualGapMm))
    throw refusal(spec, "/virtual/gap_mm", "must be positive");
  if (!(d.virtualDistanceMm > 0))
    throw refusal(spec, "/virtual/distance_mm", "must be positive or \"infinity\"");
}

}  // namespace

DisplayDesign designDisplay(const DisplaySpec& spec, const BarrierCameraSettings& camera) {
  checkRanges(spec, camera);
  DisplayDesign d;
  d.spec = spec;
  d.gapMm = spec.gapMm;
  const bool measured = spec.screenPeriodPx || spec.slitPeriodPx;
  if (measured)
    measuredPeriods(spec, d);
  else
    givenPeriods(spec, d);
  deriveViews(spec, measured, d);
  deriveApertures(spec, d);
  applyCamera(spec, camera, d);
  return d;
}

int interleavedViewCount(const DisplayDesign& design) {
  return pixelViewCount(design) * (design.camera.subpixelRays ? 3 : 1);
}

int pixelViewCount(const DisplayDesign& design) {
  return std::max(1, int(std::lround(design.screenPeriodPx)));
}

}  // namespace parallax
