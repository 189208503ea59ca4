#include "parallax/photocal/barrier_shot.h"

#include <cmath>
#include <numbers>

#include "parallax/core/error.h"

namespace parallax::photocal {

namespace {

PanelGrid grid(const Panel& panel) {
  return {panel.width, panel.height, panel.pitchMm};
}

}  // namespace

double shotGratings(double x, double y) {
  constexpr double kTwoPi = 2 * std::numbers::pi;
  return 0.5 + (std::cos(kTwoPi * x / BarrierShot::kPeriodsPx[0]) +
                std::cos(kTwoPi * x / BarrierShot::kPeriodsPx[1]) +
                std::cos(kTwoPi * y / BarrierShot::kFrontRowPeriodPx)) /
                   6;
}

BarrierShot barrierShot(const DisplaySpec& display) {
  BarrierShot shot;
  shot.frontIsImage = display.order == LayerOrder::BarrierBack;
  shot.front = grid(shot.frontIsImage ? display.imagePanel : display.maskPanel);
  shot.rear = grid(shot.frontIsImage ? display.maskPanel : display.imagePanel);
  // Cells a 108th of the shorter side (10 pixels on a 1080-row panel): at twice the design
  // distance a phone's wide lens still gives a cell five photo pixels, and markers small
  // against the dark bands of the moire of two colour panels' stripes.
  shot.ring = markerRing(shot.front, BarrierShot::kFirstMarkerId, 108);
  // The interior: inside the ring, with a margin for rays crossing the gap at a slant.
  const int inset = shot.ring.bandPx() + 16;
  shot.x0 = inset;
  shot.x1 = shot.front.width - inset;
  shot.y0 = inset;
  shot.bands = (shot.front.height - 2 * inset) / BarrierShot::kBandPx;
  if (shot.bands < 2 || shot.x1 - shot.x0 < 2 * BarrierShot::kBlockPx + 8 ||
      int(shot.ring.markers.size()) < 8)
    throw InputError(display.source, "",
                     "its front panel (" + std::to_string(shot.front.width) + "x" +
                         std::to_string(shot.front.height) +
                         " pixels) is too small for the calibration shot's markers and gratings");
  return shot;
}

BarrierShotPictures drawBarrierShot(const BarrierShot& shot) {
  BarrierShotPictures p{Image(shot.front.width, shot.front.height, Vec3f(1.0f)),
                        Image(shot.rear.width, shot.rear.height, Vec3f(1.0f))};
  drawMarkerRing(shot.ring, p.front);
  const int bandRows = shot.bands * BarrierShot::kBandPx;
  for (int y = shot.y0; y < shot.y0 + bandRows; ++y) {
    const int row = (y - shot.y0) % BarrierShot::kBandPx;
    if (row >= BarrierShot::kFrontRows[0] && row < BarrierShot::kFrontRows[1])
      for (int x = shot.x0; x < shot.x1; ++x)
        p.front.at(x, y) = Vec3f(float(
            shotGratings(x + 0.5 - 0.5 * shot.front.width, y + 0.5 - 0.5 * shot.front.height)));
  }
  // The rear's bands sit behind the front's (the same heights in mm; the panels may differ in
  // pitch), across the rear's whole width inside the ring's margin (a rear panel offset
  // sideways still shows gratings behind the front's interior).
  for (int y = 0; y < shot.rear.height; ++y) {
    const double frontRow = shot.front.yPx(shot.rear.yMm(y + 0.5)) - shot.y0;
    if (frontRow < 0 || frontRow >= bandRows) continue;
    const double bandRow = std::fmod(frontRow, double(BarrierShot::kBandPx));
    if (bandRow < BarrierShot::kRearRows[0] || bandRow >= BarrierShot::kRearRows[1]) continue;
    for (int x = 0; x < shot.rear.width; ++x) {
      const double frontX = shot.front.xPx(shot.rear.xMm(x + 0.5));
      if (frontX >= shot.x0 - 16 && frontX < shot.x1 + 16)
        p.rear.at(x, y) = Vec3f(
            float(shotGratings(x + 0.5 - 0.5 * shot.rear.width, y + 0.5 - 0.5 * shot.rear.height)));
    }
  }
  return p;
}

}  // namespace parallax::photocal
