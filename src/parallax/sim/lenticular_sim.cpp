#include "parallax/sim/lenticular_sim.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/core/parallel.h"
#include "parallax/image/metrics.h"

namespace parallax {

namespace {

// The difference of two views on the circle of views (view 1 is view 0), in [-1/2, 1/2].
double wrapped(double difference) {
  return difference - std::round(difference);
}

// One pixel row's subpixels, 3 x + channel: their view fractions and where they sit (x, mm).
struct Row {
  const float *fraction, *positionMm;
  double viewsPerWidth = 0;  // how the view changes across a subpixel: +-delta (invView, flips)
  double pixelStepMm = 0;    // from one pixel to the next along the row: +-pitch (flipImageX)
};

// The lens that covers panel point `pointMm` (x, mm) on the row of pixel x: the point's own view
// (from the pixel's green subpixel, views running along the row), and the lens's edges, from
// where its view is 0 to where it is 1, in mm from the point (lowest <= 0 < highest).
void lensAround(const LenticularDesign& d, const Row& row, int x, double pointMm, double& own,
                double& lowest, double& highest) {
  const size_t green = size_t(3 * x + 1);
  own = row.fraction[green] +
        row.viewsPerWidth * (pointMm - row.positionMm[green]) / (d.pixelPitchMm / 3);
  own -= std::floor(own);
  lowest = (row.viewsPerWidth > 0 ? -own : own - 1) * d.horizontalLensPitchMm;
  highest = lowest + d.horizontalLensPitchMm;
}

// What an eye looking at panel point `centreMm` (x, mm) sees through the lens there, toward view
// `eyeView`: the subpixels of row `y` under the lens that covers the point, from view 0 to view 1
// (cut at its edges: a lens period holds a fractional number of subpixels, and every view once),
// each weighted by the optics for its span of views relative to the eye's (lensSpotWeight),
// their colours summed channel by channel. A subpixel lights a third of its pixel, so a channel's
// sum is scaled by 3 over the total weight: a panel of one colour, seen through a pixel-wide spot,
// looks that colour; through a narrower spot, each colour where its subpixels are seen. Near the
// panel's edge, where the lens is cut, the nearest view holds.
Vec3f seenThroughLens(const LenticularDesign& d, const Row& row, const Image& panel, int y, int x,
                      double centreMm, double eyeView) {
  const int w = panel.width();
  const double lens = d.horizontalLensPitchMm, width = d.pixelPitchMm / 3;
  const double delta = subpixelViewWidth(d), support = lensSpotHalfSupport(d);
  double own, lowest, highest;
  lensAround(d, row, x, centreMm, own, lowest, highest);
  // Only the subpixels whose views the spot reaches: around where under this lens the view is
  // the eye's (and one lens over, should the spot reach across the lens's edge).
  const double target = eyeView - std::floor(eyeView);
  const double at = (row.viewsPerWidth > 0 ? 1.0 : -1.0) * (target - own) * lens;  // from the point
  const double span = (support + delta) * lens + d.pixelPitchMm;
  double first = highest, last = lowest;  // the stretch of the lens to search, mm from the point
  for (const double centre : {at - lens, at, at + lens}) {
    first = std::min(first, std::max(lowest, centre - span));
    last = std::max(last, std::min(highest, centre + span));
  }
  double acc[3] = {0, 0, 0}, total = 0, nearest = 2;
  int nearestK = -1;
  if (first > last) return {};
  const double k0 = x + first / row.pixelStepMm, k1 = x + last / row.pixelStepMm;
  const int from = std::max(0, int(std::floor(std::min(k0, k1))) - 1);
  const int to = std::min(w - 1, int(std::ceil(std::max(k0, k1))) + 1);
  for (int k = from; k <= to; ++k)
    for (int ch = 0; ch < 3; ++ch) {
      const size_t i = size_t(3 * k + ch);
      const double offset = row.positionMm[i] - centreMm;
      // The part of the subpixel under this lens, [a, b] in subpixel widths from its centre.
      const double a = std::max(-0.5, (lowest - offset) / width);
      const double b = std::min(0.5, (highest - offset) / width);
      if (!(a < b)) continue;
      const double difference = wrapped(row.fraction[i] - eyeView);
      if (std::fabs(difference) < nearest) nearest = std::fabs(difference), nearestK = int(i);
      if (std::fabs(difference) > support + 0.5 * delta) continue;
      // Where a subpixel sits under the lens is where its light goes: its views run along it.
      const double low = difference + row.viewsPerWidth * (row.viewsPerWidth > 0 ? a : b);
      const double high = difference + row.viewsPerWidth * (row.viewsPerWidth > 0 ? b : a);
      const double weight = lensSpotWeight(d, low, high);
      acc[ch] += weight * panel.at(k, y)[ch];
      total += weight;
    }
  Vec3f seen;
  if (total > 0) {
    for (int ch = 0; ch < 3; ++ch) seen[ch] = float(3.0 * acc[ch] / total);
  } else if (nearestK >= 0) {
    seen[nearestK % 3] = 3.0f * panel.at(nearestK / 3, y)[nearestK % 3];
  }
  return seen;
}

}  // namespace

LenticularSubpixels lenticularSubpixels(const LenticularDesign& d) {
  const int w = d.calibration.screenW, h = d.calibration.screenH;
  LenticularSubpixels t;
  t.fraction.resize(size_t(3 * w) * size_t(h));
  t.positionMm.resize(t.fraction.size());
  // The sign from two neighbouring subpixels of one pixel: their views step by +-delta.
  const double step = wrapped(viewFraction(d, 0, 0, 1) - viewFraction(d, 0, 0, 0));
  const double apart = subpixelPointMm(d, 0.5, 0.5, 1).x - subpixelPointMm(d, 0.5, 0.5, 0).x;
  t.viewsPerWidth = (step * apart >= 0 ? 1.0 : -1.0) * subpixelViewWidth(d);
  t.pixelStepMm = subpixelPointMm(d, 1.5, 0.5, 1).x - subpixelPointMm(d, 0.5, 0.5, 1).x;
  parallelFor(h, 0, 16, [&](int64_t begin, int64_t end) {
    for (int y = int(begin); y < int(end); ++y)
      for (int x = 0; x < w; ++x)
        for (int ch = 0; ch < 3; ++ch) {
          const size_t i = size_t(3 * w) * size_t(y) + size_t(3 * x + ch);
          t.fraction[i] = float(viewFraction(d, x, y, ch));
          t.positionMm[i] = float(subpixelPointMm(d, x + 0.5, y + 0.5, ch).x);
        }
  });
  return t;
}

Image simulateLenticularView(const LenticularDesign& d, const Image& panel, const Vec3d& eyeMm,
                             const LenticularSubpixels* subpixels) {
  const LenticularCalibration& c = d.calibration;
  const int w = c.screenW, h = c.screenH;
  if (panel.width() != w || panel.height() != h)
    throw InputError(c.source, "/screenW",
                     "the panel image is " + std::to_string(panel.width()) + "x" +
                         std::to_string(panel.height()) + ", the calibration's screen " +
                         std::to_string(w) + "x" + std::to_string(h));
  if (!(eyeMm.z > 0)) throw std::invalid_argument("the eye must be in front of the panel (z > 0)");

  const LenticularSubpixels own = subpixels ? LenticularSubpixels{} : lenticularSubpixels(d);
  const LenticularSubpixels& table = subpixels ? *subpixels : own;
  Image view(w, h);
  // Rows in parallel: each is computed the same way whichever worker runs it.
  parallelFor(h, 0, 16, [&](int64_t begin, int64_t end) {
    for (int y = int(begin); y < int(end); ++y) {
      const Row row{table.fraction.data() + size_t(3 * w) * size_t(y),
                    table.positionMm.data() + size_t(3 * w) * size_t(y), table.viewsPerWidth,
                    table.pixelStepMm};
      for (int x = 0; x < w; ++x) {
        // The pixel's centre (its subpixels' mean): the point of the panel the eye looks at.
        const double centreMm =
            (double(row.positionMm[size_t(3 * x)]) + row.positionMm[size_t(3 * x + 1)] +
             row.positionMm[size_t(3 * x + 2)]) /
            3.0;
        // What the eye sees over the pixel's width: a lens shows one colour across it, so where a
        // lens's edge crosses the pixel, each lens's colour weighted by the part it covers. A
        // sample at the centre alone counts each lens by the pixel centres it holds (6 or 7 of a
        // Portrait's 6.29), and which it is goes with which subpixel the lens shows
        // (docs/lenticular.md, "Which view the centre eye sees").
        const double half = 0.5 * std::fabs(row.pixelStepMm);
        double view0, lowest, highest;
        lensAround(d, row, x, centreMm, view0, lowest, highest);
        // The pixel's parts, [-half, edge] and [edge, half] mm from its centre: one, the whole
        // pixel, when no lens edge crosses it (a lens is wider than a pixel: at most one does).
        const double edge = lowest > -half ? lowest : highest < half ? highest : half;
        Vec3f seen;
        for (const auto& [from, to] : {std::pair{-half, edge}, std::pair{edge, half}}) {
          if (!(to - from > 1e-9 * half)) continue;
          const double point = centreMm + 0.5 * (from + to);
          const Vec3f part =
              seenThroughLens(d, row, panel, y, x, point, lensFractionSeen(d, point, eyeMm));
          seen = seen + part * float((to - from) / (2 * half));
        }
        // Into the viewer's frame: mirrored panels show column 0 on the right or row 0 at the
        // bottom.
        view.at(c.flipImageX ? w - 1 - x : x, c.flipImageY ? h - 1 - y : y) = seen;
      }
    }
  });
  return view;
}

Image lenticularAtDisplayResolution(const LenticularDesign& d, const Image& image) {
  const double lensPx = d.horizontalLensPitchMm / (d.widthMm / image.width());
  const double rows = std::fabs(d.calibration.slope) * image.height() / d.calibration.screenH;
  return boxFilterY(boxFilterX(image, lensPx), std::max(1.0, rows));
}

}  // namespace parallax
