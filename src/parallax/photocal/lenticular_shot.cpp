#include "parallax/photocal/lenticular_shot.h"

#include <cmath>
#include <numbers>

#include "parallax/core/error.h"

namespace parallax::photocal {

LenticularShot lenticularShot(const LenticularDesign& d) {
  LenticularShot shot;
  shot.panel = {d.calibration.screenW, d.calibration.screenH, d.pixelPitchMm};
  // Cells a 40th of the shorter side (38 pixels, 3 mm, on a Portrait: six lenses): read
  // through the lenses from twice the design distance, where a small panel with a large D (a
  // Portrait: 120 mm wide, D = 1.37 m) is a few hundred photo pixels across even at 70 mm.
  shot.ring = markerRing(shot.panel, LenticularShot::kFirstMarkerId, 40);
  const int inset = shot.ring.bandPx() + shot.ring.quietPx;
  shot.x0 = shot.y0 = inset;
  shot.x1 = shot.panel.width - inset;
  shot.y1 = shot.panel.height - inset;
  if (shot.x1 - shot.x0 < 64 || shot.y1 - shot.y0 < 64 || shot.ring.markers.size() < 8)
    throw InputError(d.calibration.source, "",
                     "its panel (" + std::to_string(shot.panel.width) + "x" +
                         std::to_string(shot.panel.height) +
                         " pixels) is too small for the calibration shot's markers and fringes");
  return shot;
}

Image drawLenticularShot(const LenticularShot& shot, const LenticularDesign& d) {
  Image picture(shot.panel.width, shot.panel.height, Vec3f(0.5f));
  drawMarkerRing(shot.ring, picture);
  constexpr double kTwoPi = 2 * std::numbers::pi;
  for (int y = shot.y0; y < shot.y1; ++y)
    for (int x = shot.x0; x < shot.x1; ++x) {
      const double r = viewFraction(d, x, y, 0), b = viewFraction(d, x, y, 2);
      picture.at(x, y) = Vec3f(float(0.5 + 0.5 * std::cos(kTwoPi * r)), 0.5f,
                               float(0.5 + 0.5 * std::sin(kTwoPi * b)));
    }
  return picture;
}

}  // namespace parallax::photocal
