// Where things sit on a panel for a calibration shot, in the two coordinates the shots use: a
// panel's pixels (x right, y down from the top-left corner, pixel (i, j) centred at (i + 0.5,
// j + 0.5)) and the display frame (mm, x right, y up, origin at the panel's centre;
// docs/display-geometry.md).
#pragma once

#include <array>
#include <vector>

#include "parallax/image/image.h"

namespace parallax::photocal {

struct PanelGrid {
  int width = 0, height = 0;  // pixels
  double pitchMm = 0;         // square pixels
  double xMm(double xPx) const { return (xPx - 0.5 * width) * pitchMm; }
  double yMm(double yPx) const { return (0.5 * height - yPx) * pitchMm; }
  double xPx(double xMm) const { return xMm / pitchMm + 0.5 * width; }
  double yPx(double yMm) const { return 0.5 * height - yMm / pitchMm; }
};

// A ring of ArUco markers (vision::markerCells) around the front layer's edge, each with a
// white quiet zone, that tells a photo where the panel is and how the camera stood. Marker ids
// start at firstId, so that each shot's markers say which shot a photo shows.
struct MarkerRing {
  int firstId = 0;
  int markerPx = 0;  // side, a multiple of vision::kMarkerCells
  int quietPx = 0;   // white around each marker
  struct Placement {
    int id = 0;
    int x = 0, y = 0;  // top-left pixel of the marker
  };
  std::vector<Placement> markers;
  int bandPx() const { return 2 * quietPx + markerPx; }  // the ring's width from the edge
  // A marker's corners (top-left, top-right, bottom-right, bottom-left) in panel pixels.
  std::array<std::array<double, 2>, 4> cornersPx(const Placement& placement) const;
};

// The ring for a panel: cells of a `cellsAcross`-th of the shorter side (at least 4 pixels),
// two cells of quiet zone, as many markers as fit along each edge.
MarkerRing markerRing(const PanelGrid& panel, int firstId, int cellsAcross);

// Draws the ring into a picture of the panel's size: the band white, the markers black on it;
// the rest of the picture untouched.
void drawMarkerRing(const MarkerRing& ring, Image& picture);

}  // namespace parallax::photocal
