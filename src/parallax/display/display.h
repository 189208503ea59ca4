// A two-layer parallax-barrier display: what the user describes (DisplaySpec) and what follows
// from it (DisplayDesign), in the frame of docs/display-geometry.md: millimetres, x right,
// y up, z toward the viewer, the front layer at z = 0 and the rear layer at z = -gap.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>

namespace parallax {

enum class SubpixelOrder { RGB, BGR, None };
// BarrierFront: the mask in front, the image behind (the paper's Fig. 3).
// BarrierBack: the image in front, the mask behind as a patterned backlight ("parallax
// illumination", the paper's prototype).
enum class LayerOrder { BarrierFront, BarrierBack };
enum class MaskKind { Slits, Slanted, Wiggling, Jittered, Pinholes };

struct Panel {
  int width = 1920, height = 1080;  // pixels
  double pitchMm = 0.2745;          // pixel pitch, square pixels
  SubpixelOrder subpixels = SubpixelOrder::RGB;

  double widthMm() const { return width * pitchMm; }
  double heightMm() const { return height * pitchMm; }
};

struct MaskSpec {
  MaskKind kind = MaskKind::Slits;
  double dutyCycle = 1.0 / 9.0;  // aperture width / slit period (and height / period, pinholes)
  double phasePx = 0.0;          // shift of the whole mask, in mask pixels
  // A measured sideways offset of the mask panel against the image panel (calibration), in
  // mask pixels: the drawn pattern moves by it, the apertures the camera traces do not, so
  // that the physical apertures land where the rays expect them.
  double panelOffsetPx = 0.0;
  double slantDegrees = 0.0;       // Slanted: angle from vertical, positive leans right going up
  double wiggleAmplitudeMm = 0.0;  // Wiggling: x offset A sin(2 pi y / wavelength)
  double wiggleWavelengthMm = 0.0;
  double jitterAmplitude = 0.0;  // Jittered: max offset of each slit, in slit periods (< 0.5)
  uint64_t jitterSeed = 1;
  double verticalPeriodPx = 0.0;  // Pinholes: vertical pinhole period in mask pixels
};

// What the user knows. Exactly one of: views (with distance), viewZoneWidthMm (with distance),
// or the two measured periods (screenPeriodPx and slitPeriodPx; the distance then follows).
struct DisplaySpec {
  std::string source = "<built-in>";
  Panel imagePanel, maskPanel;
  LayerOrder order = LayerOrder::BarrierBack;
  double gapMm = 3.0;
  std::optional<double> viewDistanceMm = 600.0;
  double viewZoneCenterXMm = 0.0;
  double viewZoneHeightMm = 0.0;      // y of the view line (HPO) at the view distance
  std::optional<double> views = 9.0;  // pixels per group on the image layer
  std::optional<double> viewZoneWidthMm;
  std::optional<double> screenPeriodPx, slitPeriodPx;
  MaskSpec mask;
  // A diffuser foil between the panels (sim/diffuser.h): the rear layer's blur, Gaussian sigma
  // in mm; 0 without one. What simulate sees the panel through and the layer solvers solve
  // for, unless told otherwise.
  double diffuserSigmaMm = 0.0;
};

// How a camera traces a barrier display: render choices, not the display's physics
// (docs/architecture.md). The display file may carry them (subpixel_rays, virtual/...); the
// reader fills DisplayDescription::camera.
struct BarrierCameraSettings {
  // Trace one ray per R, G, B subpixel of the image layer (three times the views) instead of
  // one per pixel; needs an image layer with an RGB or BGR subpixel order.
  bool subpixelRays = false;
  std::optional<double> virtualGapMm, virtualDistanceMm;  // section 2.3's g' and D'
};

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Ranges. designDisplay refuses, naming the key, any quantity outside its physically sensible
// range, so that no nonsense (a 1e-300 mm pixel, a 1e300 mm gap) reaches the rays:
//   pixel_pitch_mm      1e-3 .. 10 mm          resolution     1 .. 65536 pixels a side
//   gap_mm, virtual/gap_mm  above 0, up to 1000 mm
//   view_distance_mm, virtual/distance_mm  10 mm .. 100 m (virtual: or "infinity"), and the
//                       distance the measured periods give (G1)
//   view_zone/center_x_mm, view_zone/height_mm  -100 m .. 100 m
//   view_zone/width_mm  above 0, up to 100 m
//   views, screen_period_px, slit_period_px  above 0, up to 65536 pixels
//   mask/phase_px, mask/panel_offset_px  -1e6 .. 1e6 pixels
//   mask/amplitude_mm, mask/wavelength_mm  0 .. 1e5 mm   mask/vertical_period_px  0 .. 65536
//   (and, for their mask types: angle_deg -80 .. 80, jitter 0 .. 0.5 periods)
struct DisplayRange {
  double lowest, highest;
  const char* unit;
  bool openBelow;  // lowest itself is refused
};
inline constexpr int kMaxPanelPixels = 1 << 16;
inline constexpr DisplayRange kPixelPitchRange{1e-3, 10, "mm", false};
inline constexpr DisplayRange kGapRange{0, 1000, "mm", true};
inline constexpr DisplayRange kDistanceRange{10, 1e5, "mm", false};
inline constexpr DisplayRange kOffsetRange{-1e5, 1e5, "mm", false};
inline constexpr DisplayRange kZoneWidthRange{0, 1e5, "mm", true};
inline constexpr DisplayRange kPeriodPxRange{0, 65536, "pixels", true};
inline constexpr DisplayRange kShiftPxRange{-1e6, 1e6, "pixels", false};
inline constexpr DisplayRange kWiggleRange{0, 1e5, "mm", false};

struct DisplayDesign {
  DisplaySpec spec;
  BarrierCameraSettings camera;  // the settings it was designed with
  double gapMm = 0, viewDistanceMm = 0;
  double screenPeriodMm = 0, screenPeriodPx = 0;  // Tx, on the image layer
  double slitPeriodMm = 0, slitPeriodPx = 0;      // Tv, on the mask layer
  double views = 0;                               // Tx / dx
  double viewZoneWidthMm = 0;                     // S
  double viewWidthMm = 0;                         // S / views
  double aperturesAcross = 0, aperturesDown = 1;
  double apertureSpanMm = 0;                        // Sv = (N - 1) Tv
  double depthOfFieldMm = 0;                        // G4: g Tv / dx either side of the mask
  double farthestConsistentDistanceMm = kInfinity;  // the paper's D S / (Sv - S)
  double virtualGapMm = 0, virtualDistanceMm = 0;   // g' and D': camera's, or g and D
  // x of aperture 0 on the mask layer (before the mask's phase): the projection, from the
  // view-zone centre, of the centre of the group nearest x = 0, with groups laid from the
  // image layer's left edge so that group boundaries fall on pixel boundaries.
  double apertureOriginMm = 0;

  double imageLayerZ() const;  // 0 or -gap
  double maskLayerZ() const;
  double frontWidthMm() const;
  double frontHeightMm() const;
  // Disparity between adjacent views, on the aperture plane, for a point at depth z (mm,
  // positive toward the viewer), in mm: (S / views) |z| / (D - z).
  double adjacentViewDisparityMm(double depthMm) const;
};

// The views a barrier interleaves, one per film column of a group: round(views) pixel columns,
// three times as many with subpixel rays. The one place this count is made.
int interleavedViewCount(const DisplayDesign& design);
// The same counting pixel columns only (the eyes' views, whatever the rays): round(Tx / dx),
// the range of a barrier's viewIndex in pixel mode.
int pixelViewCount(const DisplayDesign& design);

// The paper's prototype: two 1920x1080 panels of 0.2745 mm pixels, g = 3 mm, 9 views,
// D = 600 mm, barrier-back.
DisplaySpec defaultDisplaySpec();

// Derives the design (G1-G4) and checks it, with the camera's settings (the default: one ray
// per pixel, the physical gap and distance). Throws InputError naming `spec.source` and the key
// with the broken relation ("/gap_mm: must be positive", "/slit_period_px: ...",
// "/virtual/gap_mm: ...").
DisplayDesign designDisplay(const DisplaySpec& spec, const BarrierCameraSettings& camera = {});

}  // namespace parallax
