// Framing a scene for a display: how large (the width fit), where in depth (the zero-parallax
// plane) and how deep (a barrier camera's virtual gap g', a lenticular camera's depth scale) the
// content appears. render, view
// --display-eye and simulate --reference all frame a scene through frameForDisplay, so that
// the ideal views match the render (docs/display-geometry.md, "Depth budget").
#pragma once

#include <string>

#include "parallax/display/display.h"
#include "parallax/display/display_model.h"
#include "parallax/display/lenticular.h"
#include "parallax/scene/scene.h"

namespace parallax {

struct Framing {
  DisplayFit fit = DisplayFit::None;  // the mode used: Window, Depth or None
  DisplayPlacement placement;         // width and centre resolved (no fit bounds left)
  DisplayDesign design;               // a barrier with the virtual gap g' the camera uses
                                      // (design.camera.virtualGapMm set when the framing chose it)
  bool lenticular = false;            // framed for a lenticular panel (no gap: a depth scale)
  bool hasContent = false;            // false: nothing to measure (an empty scene)
  double scaleMmPerUnit = 0;          // display mm per scene unit
  double focusMm = 0;  // the zero-parallax plane's offset from the placement's centre (mm)
  bool focusAuto = true;
  double budgetMm = 0;  // half the displayed depth range allowed (mm)
  bool budgetAuto = true;
  double depthOfFieldMm = 0;  // G4 with the physical gap, g Tv / dx; a lens's: lensDepthOfFieldMm
  double gapMm = 0, virtualGapMm = 0;  // barriers
  // How the display shows the camera's depth: a point the camera sees at z is shown at about
  // z depthScale (barriers: g / g'; lenticular panels: exactly, display/depth_scaled_display.h).
  double depthScale = 1;
  bool virtualGapFixed = false;  // the display file gives g', so the framing keeps it
  // The content's bounds, nearest and farthest z (display mm, toward the viewer) in the framed
  // scene, and as the display shows them: flattened by depthScale.
  double nearMm = 0, farMm = 0;
  double shownNearMm = 0, shownFarMm = 0;
  // The displayed content stays within the budget (within 0.5 %).
  bool withinBudget() const;
};

// The framing of `scene` (its display placement and content bounds) for `design` (whose spec
// may fix g'): the mode from placement.fitMode (Auto: Camera for a file camera's shot and
// Depth otherwise without a given display width, None with one), then for Camera the window
// that frames the shot at its focus distance (zero parallax there); for Window the largest picture
// whose content bounds, seen from the view-zone centre, fall inside the window less 5 %; for Depth
// the same with the zero-parallax plane at the harmonic mean of the content's nearest and farthest
// distances from that eye (or at placement.focusMm), and g' = max(g, g * largest |z| / budget).
// Throws InputError when a given focus puts content at or behind the eye.
Framing frameForDisplay(const Scene& scene, const DisplayDesign& design);

// The same for a lenticular panel, whose depth of field is its lens's (lensDepthOfFieldMm,
// display/depth_scaled_display.h): for Depth the camera's depth scale k = min(1, budget /
// largest |z|) flattens the content into the budget (never deepened).
Framing frameForDisplay(const Scene& scene, const LenticularDesign& design);

// The framing of `scene` for a display of any kind: the barrier's or the lenticular panel's
// above; for a kind that frames nothing, the scene's own placement (fit None).
Framing frameForDisplay(const Scene& scene, const DisplayModel& display);

// The scene with its display placement replaced by the framing's (the design's g' is
// framing.design; simulate reads it from the render's display.json).
Scene framedScene(Scene scene, const DisplayDesign& design);

// The harmonic mean of the distances from the eye (at z = eyeZ) of z = near and z = far, as a
// z: the plane with equal and opposite vergence (1/distance) errors to both ends.
double harmonicFocusZ(double nearZ, double farZ, double eyeZ);

// A request's overrides (its fields fit, focus, depth_budget); an empty string leaves the
// scene's value. Throws RequestError("fit" | "focus" | "depth_budget", ...) on a bad value.
void applyFramingOptions(DisplayPlacement& placement, const std::string& fit,
                         const std::string& focus, const std::string& depthBudget);

const char* displayFitName(DisplayFit fit);
// Depth and Camera compress the content's depth into the budget; Window and None do not.
bool compressesDepth(DisplayFit fit);

// One line when the displayed content reaches beyond the budget (empty otherwise), e.g.
// "the content spans -112 to +98 mm; the display is sharp within +-27 mm (G4); {fit} depth
// compresses it" (the {fit} field spelled by the front end, core/error.h).
std::string depthWarning(const Framing& framing);
// One line describing the framing: the content's range, the focus, g' (or the depth scale) and
// the depth of field.
std::string depthSummary(const Framing& framing);

}  // namespace parallax
