#include "parallax/sim/lenticular_sim.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "parallax/core/error.h"

namespace parallax {

namespace {

// The difference of two views on the circle of views (view 1 is view 0), in [-1/2, 1/2].
double wrapped(double difference) {
  return difference - std::round(difference);
}

// What channel `ch` of a row shows toward view `eyeView` in the lens around pixel x: the views of
// the row's channel-ch subpixels, unwrapped along the row from pixel x, are searched for the pair
// that brackets the eye's view nearest pixel x's own, and the pair's values interpolated linearly
// in view. Past the panel's edge the last subpixel is held.
float seenThroughLens(const std::vector<double>& fractions, const Image& panel, int y, int x,
                      int ch, double eyeView) {
  const int w = panel.width();
  const auto view = [&](int k) { return fractions[size_t(3 * k + ch)]; };
  const double target = wrapped(eyeView - view(x));  // relative to pixel x's view
  if (target == 0) return panel.at(x, y)[ch];
  // Walk toward the target: the side whose neighbour's view moves the same way.
  const int probe = x + 1 < w ? x + 1 : x - 1;
  const bool sameWay = (wrapped(view(probe) - view(x)) > 0) == (target > 0);
  const int dir = (probe > x) == sameWay ? 1 : -1;
  double here = 0;
  for (int k = x; k + dir >= 0 && k + dir < w; k += dir) {
    const double next = here + wrapped(view(k + dir) - view(k));
    if ((next - target) * (here - target) <= 0) {
      const double a = (target - here) / (next - here);
      return float((1 - a) * panel.at(k, y)[ch] + a * panel.at(k + dir, y)[ch]);
    }
    if (std::fabs(next) > 1) break;  // a whole lens searched (only with degenerate steps)
    here = next;
  }
  const int edge = dir > 0 ? w - 1 : 0;
  return panel.at(edge, y)[ch];
}

}  // namespace

Image simulateLenticularView(const LenticularDesign& d, const Image& panel, const Vec3d& eyeMm) {
  const LenticularCalibration& c = d.calibration;
  const int w = c.screenW, h = c.screenH;
  if (panel.width() != w || panel.height() != h)
    throw InputError(c.source, "/screenW",
                     "the panel image is " + std::to_string(panel.width()) + "x" +
                         std::to_string(panel.height()) + ", the calibration's screen " +
                         std::to_string(w) + "x" + std::to_string(h));
  if (!(eyeMm.z > 0)) throw std::invalid_argument("the eye must be in front of the panel (z > 0)");

  Image view(w, h);
  std::vector<double> fractions(size_t(3 * w));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x)
      for (int ch = 0; ch < 3; ++ch) fractions[size_t(3 * x + ch)] = viewFraction(d, x, y, ch);
    for (int x = 0; x < w; ++x) {
      const Vec3d p = subpixelPointMm(d, x + 0.5, y + 0.5, 1);
      const double eyeView = viewFractionOfAngle(d, std::atan2(eyeMm.x - p.x, eyeMm.z));
      Vec3f seen;
      for (int ch = 0; ch < 3; ++ch)
        seen[ch] = seenThroughLens(fractions, panel, y, x, ch, eyeView);
      // Into the viewer's frame: mirrored panels show column 0 on the right or row 0 at the bottom.
      view.at(c.flipImageX ? w - 1 - x : x, c.flipImageY ? h - 1 - y : y) = seen;
    }
  }
  return view;
}

}  // namespace parallax
