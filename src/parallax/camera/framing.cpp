#include "parallax/camera/framing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <vector>

#include "parallax/camera/display_camera.h"
#include "parallax/core/error.h"
#include "parallax/display/depth_scaled_display.h"

namespace parallax {

namespace {

// The content's corners in the display's axes (x = up x normal, y = up, z = normal), scene
// units from the placement's centre.
std::vector<Vec3d> contentCorners(const Bounds3f& b, const DisplayPlacement& placement) {
  const Vec3f normal = normalize(placement.normal);
  const Vec3f right = normalize(cross(placement.up, normal));
  const Vec3f up = cross(normal, right);
  std::vector<Vec3d> corners;
  for (int i = 0; i < 8; ++i) {
    const Vec3f p{i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z};
    const Vec3f d = p - placement.center;
    corners.push_back({dot(d, right), dot(d, up), dot(d, normal)});
  }
  return corners;
}

// True if every corner at `scale` mm per unit, moved by -shift in z, lies in front of the eye
// and is seen from it inside the window, `margin` in from each edge.
bool fitsInside(const std::vector<Vec3d>& corners, const DisplayWindow& window, double scale,
                double shift, double margin) {
  const Vec3d& e = window.eyeMm;
  const double halfW = 0.5 * window.widthMm * (1 - 2 * margin);
  const double halfH = 0.5 * window.heightMm * (1 - 2 * margin);
  for (const Vec3d& c : corners) {
    const double x = c.x * scale, y = c.y * scale, z = c.z * scale - shift;
    if (!(z < e.z)) return false;
    const double s = e.z / (e.z - z);  // the line eye -> corner meets z = 0 at e + (p - e) s
    if (std::abs(e.x + (x - e.x) * s) > halfW || std::abs(e.y + (y - e.y) * s) > halfH)
      return false;
  }
  return true;
}

// The largest scale at which the corners, moved by -shiftAt(scale), fit (bisection between a
// scale that fits and one that does not); `fallback` when none or every scale fits.
double largestScale(const std::vector<Vec3d>& corners, const DisplayWindow& window,
                    const std::function<double(double)>& shiftAt, double fallback) {
  constexpr double margin = 0.05;
  const auto fits = [&](double s) { return fitsInside(corners, window, s, shiftAt(s), margin); };
  double good = fallback * 1e-6;
  if (!fits(good)) return fallback;
  double bad = good;
  for (int i = 0; i < 80 && fits(bad); ++i) bad *= 2;
  if (fits(bad)) return fallback;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (good + bad);
    (fits(mid) ? good : bad) = mid;
  }
  return good;
}

// The shift z0 that puts z = 0 at the harmonic mean of the distances from the eye (z = eyeZ) of
// z = nearZ - z0 and z = farZ - z0. With u = eyeZ + z0 the condition 1/(u - a) + 1/(u - b) =
// 2/eyeZ is u^2 - u (a + b + eyeZ) + ab + eyeZ (a + b)/2 = 0, whose discriminant is
// (a - b)^2 + eyeZ^2; the larger root keeps the content in front of the eye.
double harmonicShift(double a, double b, double eyeZ) {
  const double u = 0.5 * ((a + b + eyeZ) + std::sqrt((a - b) * (a - b) + eyeZ * eyeZ));
  return u - eyeZ;
}

// Whether the content's frustum hull (its corners at the nearest z and at the farthest z, each a
// rectangle), at `scale` and moved by -shift, covers the window for every ray of the display:
// rays from every window point toward any eye of the zone (half-width zoneHalfWidth about
// window.eyeMm's x at its z), whose horizontal slopes the camera multiplies by the depth scale
// min(1, budget / deepest). A ray inside both end rectangles runs inside the hull between them
// and so crosses a height field that spans it (a photo's mesh parts the near cap from the far
// cap): every such ray meets the content.
bool coversWindow(const std::vector<Vec3d>& corners, const DisplayWindow& window, double scale,
                  double shift, double zoneHalfWidth, double budget) {
  double lo = corners[0].z, hi = corners[0].z;
  for (const Vec3d& c : corners) lo = std::min(lo, c.z), hi = std::max(hi, c.z);
  const double deepest = std::max(scale * hi - shift, shift - scale * lo);
  const double k = deepest > budget ? budget / deepest : 1.0;
  const Vec3d& e = window.eyeMm;
  const double slope = (0.5 * window.widthMm + std::abs(e.x) + zoneHalfWidth) / e.z;
  for (const double end : {hi, lo}) {
    double xl = 1e300, xr = -1e300, yl = 1e300, yr = -1e300;
    for (const Vec3d& c : corners)
      if (std::abs(c.z - end) <= 1e-6 * (std::abs(hi) + std::abs(lo) + 1))
        xl = std::min(xl, c.x * scale), xr = std::max(xr, c.x * scale),
        yl = std::min(yl, c.y * scale), yr = std::max(yr, c.y * scale);
    const double z = scale * end - shift;
    const double spread = k * std::abs(z) * slope;
    if (xl > -0.5 * window.widthMm - spread || xr < 0.5 * window.widthMm + spread) return false;
    // Vertically a ray from the window's edge runs toward the eye's height at the eye's depth.
    for (const double y : {-0.5 * window.heightMm, 0.5 * window.heightMm}) {
      const double at = y + (e.y - y) * z / e.z;
      if (at < yl || at > yr) return false;
    }
  }
  return true;
}

// The smallest scale at which coversWindow holds (bisection from a scale that does not, `from`,
// to one that does); 0 when none up to 2^40 times `from` does.
double smallestCoveringScale(const std::vector<Vec3d>& corners, const DisplayWindow& window,
                             const std::function<double(double)>& shiftAt, double from,
                             double zoneHalfWidth, double budget) {
  const auto covers = [&](double s) {
    return coversWindow(corners, window, s, shiftAt(s), zoneHalfWidth, budget);
  };
  double bad = from, good = from;
  for (int i = 0; i < 40 && !covers(good); ++i) good *= 2;
  if (!covers(good)) return 0;
  if (covers(bad)) return bad;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (good + bad);
    (covers(mid) ? good : bad) = mid;
  }
  return good;
}

std::string millimetres(double mm) {
  char text[32];
  std::snprintf(text, sizeof text, "%+.0f", std::abs(mm) < 0.5 ? 0.0 : mm);
  return text;
}

}  // namespace

bool compressesDepth(DisplayFit fit) {
  return fit == DisplayFit::Depth || fit == DisplayFit::Camera;
}

double harmonicFocusZ(double nearZ, double farZ, double eyeZ) {
  const double tn = eyeZ - nearZ, tf = eyeZ - farZ;
  return eyeZ - 2 * tn * tf / (tn + tf);
}

bool Framing::withinBudget() const {
  return std::max(shownNearMm, -shownFarMm) <= budgetMm * 1.005;
}

namespace {

// What both kinds share: the mode, the width fit and the focus for `window`, the budget (auto:
// `depthOfFieldMm`) and the content's near and far z in the camera's frame; the placement
// resolved. The depth compression (and the shown range) is the kind's own.
Framing frameContent(const Scene& scene, const DisplayWindow& window, double depthOfFieldMm,
                     double zoneHalfWidthMm) {
  const DisplayPlacement& given = scene.display;
  Framing f;
  f.fit = given.fitMode;
  if (f.fit == DisplayFit::Auto)
    f.fit = !given.fit ? DisplayFit::None : given.shot ? DisplayFit::Camera : DisplayFit::Depth;
  // Without a file camera's shot there is nothing to frame the camera's way.
  if (f.fit == DisplayFit::Camera && !given.shot) f.fit = DisplayFit::Depth;
  f.focusAuto = !given.focusMm;
  f.budgetAuto = !given.depthBudgetMm;
  f.depthOfFieldMm = depthOfFieldMm;
  f.budgetMm = given.depthBudgetMm.value_or(depthOfFieldMm);

  const Bounds3f bounds = given.content ? *given.content : scene.framingBounds();
  f.hasContent = !bounds.empty();
  const double givenScale = window.widthMm / double(fitDisplayWidth(given, window));
  double scale = givenScale, shift = given.focusMm.value_or(0.0);
  std::vector<Vec3d> corners;
  if (f.hasContent) {
    corners = contentCorners(bounds, given);
    if (!given.contentHull.empty()) {
      const Vec3f normal = normalize(given.normal);
      const Vec3f right = normalize(cross(given.up, normal));
      const Vec3f up = cross(normal, right);
      corners.clear();
      for (const Vec3f& p : given.contentHull) {
        const Vec3f d = p - given.center;
        corners.push_back({dot(d, right), dot(d, up), dot(d, normal)});
      }
    }
    double lo = corners[0].z, hi = corners[0].z;
    for (const Vec3d& c : corners) lo = std::min(lo, c.z), hi = std::max(hi, c.z);
    const double eyeZ = window.eyeMm.z;
    const double fallback = window.widthMm / double(given.width);
    if (f.fit == DisplayFit::Window && !given.focusMm) {
      DisplayPlacement today = given;  // exactly today's width-only fit
      today.fit = given.fit ? *given.fit : bounds;
      scale = window.widthMm / double(fitDisplayWidth(today, window));
    } else if (f.fit == DisplayFit::Window || (f.fit == DisplayFit::Depth && given.focusMm)) {
      const auto sameShift = [&](double) { return shift; };
      scale = largestScale(corners, window, sameShift, fallback);
    } else if (f.fit == DisplayFit::Camera) {
      // The window is the shot's frame at its focus distance d (the placement's centre): the
      // camera sees a height 2 d tan(yfov / 2) there, and a width `aspect` times that; the
      // window (of the display's own aspect) is the smallest that holds that frame, as a
      // camera's sensor fit "auto" would. A point on the focus plane then falls where it fell
      // in the camera's picture, seen from any eye; the zero-parallax plane is that plane.
      const ShotFrame& shot = *given.shot;
      const double height = 2.0 * shot.focusDistance * std::tan(0.5 * shot.yfovRadians);
      const double displayAspect = window.widthMm / window.heightMm;
      const double aspect = shot.aspectRatio > 0 ? shot.aspectRatio : displayAspect;
      scale = window.widthMm / std::max(height * aspect, height * displayAspect);
    } else if (f.fit == DisplayFit::Depth) {
      // The focus plane moves with the scale (a deeper picture puts it elsewhere) and the fit
      // depends on the focus (content nearer the eye looks larger): solve both at once, the
      // shift being a function of the scale, for the largest scale that fits.
      const auto shiftAt = [&](double s) { return harmonicShift(s * hi, s * lo, eyeZ); };
      scale = largestScale(corners, window, shiftAt, fallback);
      // A picture that should fill the window (an RGB-D photo): the smallest scale at which it
      // covers the window for every ray, from the inside fit up.
      if (given.fillWindow && !given.contentHull.empty())
        if (const double cover =
                smallestCoveringScale(corners, window, shiftAt, scale, zoneHalfWidthMm, f.budgetMm))
          scale = cover;
      shift = shiftAt(scale);
    } else {
      scale = window.widthMm / double(given.width);  // None: the block as it is
    }
    f.nearMm = scale * hi - shift;
    f.farMm = scale * lo - shift;
  }
  f.scaleMmPerUnit = scale;
  f.focusMm = shift;
  f.shownNearMm = f.nearMm;
  f.shownFarMm = f.farMm;

  f.placement = given;
  const Vec3f normal = normalize(given.normal);
  f.placement.center = given.center + normal * float(shift / scale);
  f.placement.width = float(window.widthMm / scale);
  f.placement.fit.reset();
  f.placement.fitMode = DisplayFit::None;  // framing the framed placement again changes nothing
  f.placement.focusMm.reset();
  f.placement.content = bounds;
  return f;
}

}  // namespace

Framing frameForDisplay(const Scene& scene, const DisplayDesign& design) {
  Framing f = frameContent(scene, displayWindow(design), design.depthOfFieldMm,
                           0.5 * design.viewZoneWidthMm);
  f.gapMm = design.gapMm;
  f.virtualGapFixed = design.camera.virtualGapMm.has_value();
  f.design = design;

  // g': fixed by the display file, or for Depth just enough to flatten the content into the
  // budget (never below g: shallow content keeps its depth).
  double virtualGap = design.virtualGapMm;
  if (compressesDepth(f.fit) && !f.virtualGapFixed && f.hasContent) {
    const double deepest = std::max(f.nearMm, -f.farMm);
    virtualGap = std::clamp(design.gapMm * deepest / f.budgetMm, design.gapMm, kGapRange.highest);
    if (virtualGap > design.gapMm * (1 + 1e-9)) {
      BarrierCameraSettings camera = design.camera;
      camera.virtualGapMm = virtualGap;
      f.design = designDisplay(design.spec, camera);
    } else {
      virtualGap = design.gapMm;
    }
  }
  f.virtualGapMm = virtualGap;
  f.depthScale = design.gapMm / virtualGap;
  f.shownNearMm = f.nearMm * f.depthScale;
  f.shownFarMm = f.farMm * f.depthScale;
  return f;
}

Framing frameForDisplay(const Scene& scene, const LenticularDesign& design) {
  Framing f = frameContent(scene, displayWindow(design), lensDepthOfFieldMm(design),
                           0.5 * design.viewZoneWidthMm);
  f.lenticular = true;
  // The scale flattens the deeper side exactly onto the budget (a ray's slope can turn toward
  // the normal without limit, unlike g', so the content always fits); shallow content keeps its
  // depth.
  if (compressesDepth(f.fit) && f.hasContent) {
    const double deepest = std::max(f.nearMm, -f.farMm);
    if (deepest > f.budgetMm) f.depthScale = f.budgetMm / deepest;
  }
  f.shownNearMm = f.nearMm * f.depthScale;
  f.shownFarMm = f.farMm * f.depthScale;
  return f;
}

Framing frameForDisplay(const Scene& scene, const DisplayModel& display) {
  if (const DisplayDesign* barrier = display.barrierDesign())
    return frameForDisplay(scene, *barrier);
  if (const LenticularDesign* lenticular = display.lenticularDesign())
    return frameForDisplay(scene, *lenticular);
  Framing unframed;
  unframed.placement = scene.display;
  return unframed;
}

Scene framedScene(Scene scene, const DisplayDesign& design) {
  scene.display = frameForDisplay(scene, design).placement;
  return scene;
}

const char* displayFitName(DisplayFit fit) {
  switch (fit) {
    case DisplayFit::Auto:
      return "auto";
    case DisplayFit::Window:
      return "window";
    case DisplayFit::Depth:
      return "depth";
    case DisplayFit::None:
      return "none";
    case DisplayFit::Camera:
      return "camera";
  }
  return "auto";
}

void applyFramingOptions(DisplayPlacement& placement, const std::string& fit,
                         const std::string& focus, const std::string& depthBudget) {
  if (!fit.empty()) {
    bool known = false;
    for (DisplayFit mode : {DisplayFit::Auto, DisplayFit::Window, DisplayFit::Depth,
                            DisplayFit::None, DisplayFit::Camera})
      if (fit == displayFitName(mode)) placement.fitMode = mode, known = true;
    if (!known)
      throw RequestError("fit", "expected window, depth, camera, none or auto, got '" + fit + "'");
  }
  const auto parseMm = [](const std::string& text, const char* field, double lowest, double highest,
                          bool openBelow) -> std::optional<double> {
    if (text == "auto") return std::nullopt;
    char* end = nullptr;
    const double mm = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(mm))
      throw RequestError(field, "expected a number of millimetres or auto, got '" + text + "'");
    if (mm < lowest || mm > highest || (openBelow && !(mm > lowest)))
      throw RequestError(field, std::string("expected ") + (openBelow ? "above " : "from ") +
                                    millimetres(lowest).substr(lowest == 0 ? 1 : 0) + " up to " +
                                    millimetres(highest).substr(1) + " mm, got " + text);
    return mm;
  };
  if (!focus.empty()) placement.focusMm = parseMm(focus, "focus", -kMaxFocusMm, kMaxFocusMm, false);
  if (!depthBudget.empty())
    placement.depthBudgetMm = parseMm(depthBudget, "depth_budget", 0, kMaxDepthBudgetMm, true);
}

std::string depthWarning(const Framing& f) {
  if (!f.hasContent || f.withinBudget()) return {};
  std::string line = "the content spans " + millimetres(f.shownFarMm) + " to " +
                     millimetres(f.shownNearMm) + " mm";
  char text[96];
  if (f.lenticular && f.depthScale != 1) {
    std::snprintf(text, sizeof text, " as shown (depth x%.2f)", f.depthScale);
    line += text;
  } else if (!f.lenticular && f.virtualGapMm != f.gapMm) {
    line += " as shown (g' = " + millimetres(f.virtualGapMm).substr(1) + " mm)";
  }
  std::snprintf(text, sizeof text, "; the display is sharp within ±%.0f mm (%s)", f.depthOfFieldMm,
                f.lenticular ? "the lens's depth of field" : "G4");
  line += text;
  if (!f.budgetAuto) line += ", the budget is ±" + millimetres(f.budgetMm).substr(1) + " mm";
  if (!compressesDepth(f.fit))
    line += "; {fit} depth compresses it";
  else if (f.virtualGapFixed)
    line += "; the display file fixes the virtual gap (virtual/gap_mm)";
  else
    line += "; the virtual gap reached its limit";
  return line;
}

std::string depthSummary(const Framing& f) {
  if (!f.hasContent) return "depth: no content to frame";
  char shown[96];
  if (f.lenticular)
    std::snprintf(shown, sizeof shown, "depth x%.3f", f.depthScale);
  else
    std::snprintf(shown, sizeof shown, "g' %.2f mm, g %.2f mm", f.virtualGapMm, f.gapMm);
  char text[320];
  std::snprintf(text, sizeof text,
                "depth (fit %s): the content spans %s to %s mm, shown %s to %s mm (%s); focus %s "
                "mm (%s); sharp within ±%.1f mm (%s), budget ±%.1f mm",
                displayFitName(f.fit), millimetres(f.farMm).c_str(), millimetres(f.nearMm).c_str(),
                millimetres(f.shownFarMm).c_str(), millimetres(f.shownNearMm).c_str(), shown,
                millimetres(f.focusMm).c_str(),
                f.focusAuto ? (f.fit == DisplayFit::Depth    ? "auto: harmonic mean"
                               : f.fit == DisplayFit::Camera ? "auto: the camera's focus distance"
                                                             : "auto: 0")
                            : "given",
                f.depthOfFieldMm, f.lenticular ? "lens" : "G4", f.budgetMm);
  std::string summary = text;
  if (f.fit == DisplayFit::Camera && f.placement.shot) {
    std::snprintf(text, sizeof text, "; the window frames the camera's shot %.4g units away (%s)",
                  double(f.placement.shot->focusDistance), f.placement.shot->focusSource.c_str());
    summary += text;
  }
  return summary;
}

}  // namespace parallax
