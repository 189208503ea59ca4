// How a display pixel's sub-rays spread in angle: the display's own anti-aliasing prefilter
// (docs/display-geometry.md, "Super-sampling"). A pixel is lit through its own aperture and
// the display samples angle every column width over the gap (one view), so a pixel's sub-rays
// cover the pixel in space and about one view in angle, not a whole aperture period.
#pragma once

#include <array>
#include <string>

namespace parallax {

enum class ViewFilterKind {
  None,      // the central ray only: pixel centre through aperture centre
  View,      // a box `width` views wide (1: exactly the pixel's own view window)
  Tent,      // a triangle whose half-maximum width is `width` views (support 2 x width); at
             // width 1 it is the physical pixel-times-opening fan of a one-pixel opening
  Gaussian,  // a Gaussian whose full width at half maximum is `width` views (cut at 2 sigma)
  Period,    // the whole aperture period, whatever `width` says (the old cell; for comparison)
};

// Parses "none", "view", "tent", "gaussian", "period"; returns false for anything else.
bool parseViewFilterKind(const std::string& text, ViewFilterKind& kind);
const char* viewFilterName(ViewFilterKind kind);

struct ViewFilter {
  ViewFilterKind kind = ViewFilterKind::View;
  double widthViews = 1.0;
};

// Maps a uniform sample u in [0, 1) to an angular offset in views from the pixel's central
// ray, distributed as the filter's weight (its inverse cumulative distribution), so that
// stratified u stay stratified. Period and None have no offset here (the ray generator
// handles them); View and Tent are closed forms, the Gaussian is tabulated once and
// interpolated.
class ViewFilterWarp {
 public:
  explicit ViewFilterWarp(const ViewFilter& filter);
  double operator()(double u) const;
  // The offsets' support in views: |offset| <= halfSupport().
  double halfSupport() const { return halfSupport_; }

 private:
  static constexpr int kTable = 256;
  ViewFilterKind kind_;
  std::array<double, kTable + 1> inverseCdf_{};
  double halfSupport_ = 0;
};

}  // namespace parallax
