#include "parallax/photocal/shot_layout.h"

#include <algorithm>

#include "parallax/vision/vision.h"

namespace parallax::photocal {

std::array<std::array<double, 2>, 4> MarkerRing::cornersPx(const Placement& p) const {
  const double x0 = p.x, y0 = p.y, x1 = p.x + markerPx, y1 = p.y + markerPx;
  return {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}};
}

MarkerRing markerRing(const PanelGrid& panel, int firstId, int cellsAcross) {
  MarkerRing ring;
  ring.firstId = firstId;
  const int cells = vision::kMarkerCells;
  const int cellPx = std::max(4, std::min(panel.width, panel.height) / cellsAcross);
  ring.markerPx = cells * cellPx;
  ring.quietPx = 2 * cellPx;
  const int step = ring.markerPx + ring.quietPx;
  // Along an edge of `length` pixels: n markers with a quiet zone between and outside them,
  // spread evenly.
  const auto positions = [&](int length) {
    const int n = std::max(2, (length - ring.quietPx) / step);
    std::vector<int> at;
    const double spare = length - 2.0 * ring.quietPx - ring.markerPx;
    for (int i = 0; i < n; ++i)
      at.push_back(ring.quietPx + int(std::lround(spare * i / double(n - 1))));
    return at;
  };
  int id = firstId;
  const std::vector<int> xs = positions(panel.width), ys = positions(panel.height);
  const int right = panel.width - ring.quietPx - ring.markerPx;
  const int bottom = panel.height - ring.quietPx - ring.markerPx;
  for (int x : xs) ring.markers.push_back({id++, x, ring.quietPx});
  for (size_t i = 1; i + 1 < ys.size(); ++i) ring.markers.push_back({id++, right, ys[i]});
  for (auto x = xs.rbegin(); x != xs.rend(); ++x) ring.markers.push_back({id++, *x, bottom});
  for (size_t i = ys.size() - 2; i >= 1; --i) ring.markers.push_back({id++, ring.quietPx, ys[i]});
  return ring;
}

void drawMarkerRing(const MarkerRing& ring, Image& picture) {
  const int band = ring.bandPx();
  for (int y = 0; y < picture.height(); ++y)
    for (int x = 0; x < picture.width(); ++x)
      if (x < band || y < band || x >= picture.width() - band || y >= picture.height() - band)
        picture.at(x, y) = Vec3f(1.0f);
  const int cells = vision::kMarkerCells, cellPx = ring.markerPx / cells;
  for (const MarkerRing::Placement& m : ring.markers) {
    const std::vector<uint8_t> pattern = vision::markerCells(m.id);
    for (int y = 0; y < ring.markerPx; ++y)
      for (int x = 0; x < ring.markerPx; ++x)
        picture.at(m.x + x, m.y + y) =
            Vec3f(pattern[size_t(y / cellPx) * cells + size_t(x / cellPx)] ? 1.0f : 0.0f);
  }
}

}  // namespace parallax::photocal
