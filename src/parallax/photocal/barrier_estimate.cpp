// The barrier estimate (barrier_estimate.h; the derivation is docs/calibration.md, "From
// photos"). Per photo: the markers give a first camera; the front bands give, per block, where
// the front really is (the phases of its gratings against where the camera says it is), and
// those thousands of points fit the camera again; then the rear bands give, per block, which
// rear point the camera sees through each front point. One least-squares fit over all photos'
// blocks gives the gap, the rear offset and the rotation.
#include "parallax/photocal/barrier_estimate.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "parallax/core/error.h"
#include "parallax/photocal/least_squares.h"
#include "parallax/photocal/photo_sampler.h"

namespace parallax::photocal {

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr int kBlockPx = BarrierShot::kBlockPx;
constexpr int kFrontBlockPx = kBlockPx / 2;  // the front needs no vernier: twice the points
constexpr double kMinContrast = 0.03;        // a grating's amplitude over the mean light
constexpr int kMinMarkers = 2;               // a first camera; the front's gratings fit it again
constexpr int kCameraRounds = 5;
// The blocks trusted in each round: well inside half the periods (6 across, 16 down) at first,
// then ever nearer to where the better camera puts them.
constexpr double kTrustedShiftPx[kCameraRounds] = {4, 3, 2, 1.5, 1.5};

double wrap(double v, double period) {
  return v - period * std::round(v / period);
}

// A sinusoid fit over one block: the light against the white light there (the envelope E) times
// 1 and the cos and sin of 2 pi w / P for each component, w one of two coordinates (across or
// down). The envelope is what the same columns show where both panels are white, next to the
// block: the moire of two colour panels' stripes (dark bands where one panel's red stripes lie
// over the other's green), the camera's vignetting and its aliasing of the pixels' structure all
// multiply the pattern, and would otherwise shift its phases. Each component's phase offset is
// the shift of its coordinate that the light shows.
class PhaseFit {
 public:
  struct Component {
    int coordinate;  // 0 across, 1 down
    double period;
  };
  explicit PhaseFit(std::vector<Component> components)
      : components_(std::move(components)), ls_(1 + 2 * int(components_.size())) {}
  void add(double across, double down, double light, double envelope) {
    double row[7] = {};
    row[0] = envelope;
    for (size_t j = 0; j < components_.size(); ++j) {
      const double w = components_[j].coordinate == 0 ? across : down;
      row[1 + 2 * j] = envelope * std::cos(kTwoPi * w / components_[j].period);
      row[2 + 2 * j] = envelope * std::sin(kTwoPi * w / components_[j].period);
    }
    ls_.add(row, light);
    envelopeSum_ += envelope;
    ++samples_;
  }
  // False when there is too little to fit. shift[j] in (-P/2, P/2]; amplitudes relative to the
  // white light, mean the block's mean white light.
  bool solve(double* shift, double* amplitude, double* mean) const {
    std::vector<double> x;
    const int unknowns = 1 + 2 * int(components_.size());
    if (ls_.rows() < 8 * unknowns || !ls_.solve(x)) return false;
    *mean = samples_ ? envelopeSum_ / samples_ : 0;
    for (size_t j = 0; j < components_.size(); ++j) {
      const double b = x[1 + 2 * j], c = x[2 + 2 * j];
      amplitude[j] = std::hypot(b, c);
      shift[j] = std::atan2(-c, b) * components_[j].period / kTwoPi;
    }
    return true;
  }

 private:
  std::vector<Component> components_;
  LeastSquares ls_;
  double envelopeSum_ = 0;
  int samples_ = 0;
};

// The white light along the front row band at the columns xs (front pixels): the mean of the
// band's rows firstRow to lastRow (exclusive), NaN off the photo.
std::vector<double> whiteLight(const BarrierShot& shot, const PhotoSampler& photo,
                               const std::vector<double>& xs, double firstRow, double lastRow) {
  std::vector<double> light(xs.size(), 0.0);
  int rows = 0;
  for (double y = firstRow + 0.5; y < lastRow; y += 1.0, ++rows)
    for (size_t k = 0; k < xs.size(); ++k)
      light[k] += photo.atPoint(shot.front.xMm(xs[k]), shot.front.yMm(y), 0);
  for (double& v : light) v /= std::max(1, rows);
  return light;
}

// The white light at row y, between the guard rows above (centred at yAbove) and below.
double envelopeAt(const std::vector<double>& above, const std::vector<double>& below, size_t k,
                  double yAbove, double yBelow, double y) {
  const double t = (y - yAbove) / (yBelow - yAbove);
  return above[k] + t * (below[k] - above[k]);
}

// A band's white guard rows: the middle four of each 16-row guard (38 to 42 below the front's
// gratings, 86 to 90 below the rear's), so that the rear's gratings seen across the gap at a
// slant (up to 6 rows off) and a camera a few pixels off do not reach them.
constexpr double kGuardBelowFront[2] = {38, 42}, kGuardBelowRear[2] = {86, 90};

// The vernier: the shift that is shift0 modulo P0 and shift1 modulo P1, within half P0 P1.
double vernier(double shift0, double shift1) {
  const double p0 = BarrierShot::kPeriodsPx[0], p1 = BarrierShot::kPeriodsPx[1];
  double best = 1e9, value = shift0;
  for (int k = -7; k <= 7; ++k) {
    const double candidate = shift0 + k * p0;
    const double miss = std::abs(wrap(candidate - shift1, p1));
    if (miss < best) best = miss, value = candidate;
  }
  return value;
}

struct RearBlock {
  int photo = 0;
  double xMm = 0, yMm = 0;  // the block's centre on the front (corrected), mm
  double u0 = 0, v0 = 0;    // the rear pixel (from its centre, x right, y down) the nominal
                            // display puts there
  // Observed u - u0 modulo each grating period across, v - v0 modulo 32, and (index 3) u - u0
  // modulo one rear pixel from the moire of the two panels' colour stripes.
  double shift[4] = {0, 0, 0, 0};
  double amplitude[4] = {0, 0, 0, 0};
  double du = 0;  // u - u0 from the vernier
};

struct CameraAt {
  double x, y, z;
};

}  // namespace

FrontBlocks measureFront(const BarrierShot& shot, const PhotoSampler& photo) {
  const PanelGrid& front = shot.front;
  FrontBlocks out;
  out.bands = shot.bands;
  out.across = 2 * ((shot.x1 - shot.x0 - 8) / kBlockPx);
  out.shiftX.assign(size_t(out.bands * out.across), NAN);
  out.shiftY = out.shiftX;
  for (int b = 0; b < shot.bands; ++b) {
    const double top = shot.y0 + b * BarrierShot::kBandPx;
    // The white rows above: the previous band's last guard, or the margin inside the ring.
    const double aboveFrom = b > 0 ? top - BarrierShot::kBandPx + kGuardBelowRear[0] : top - 10;
    const double aboveTo = b > 0 ? top - BarrierShot::kBandPx + kGuardBelowRear[1] : top - 6;
    for (int j = 0; j < out.across; ++j) {
      const int x0 = shot.x0 + 4 + j * kFrontBlockPx;
      std::vector<double> xs;
      for (double x = x0 + 0.25; x < x0 + kFrontBlockPx; x += 0.5) xs.push_back(x);
      const std::vector<double> above = whiteLight(shot, photo, xs, aboveFrom, aboveTo);
      const std::vector<double> below =
          whiteLight(shot, photo, xs, top + kGuardBelowFront[0], top + kGuardBelowFront[1]);
      const double yAbove = 0.5 * (aboveFrom + aboveTo);
      const double yBelow = top + 0.5 * (kGuardBelowFront[0] + kGuardBelowFront[1]);
      PhaseFit fit({{0, BarrierShot::kPeriodsPx[0]},
                    {0, BarrierShot::kPeriodsPx[1]},
                    {1, BarrierShot::kFrontRowPeriodPx}});
      // Rows 4 to 28: the blur of the camera brings the white rows' light into the first and
      // last few, unevenly in the downward phase.
      for (int r = BarrierShot::kFrontRows[0] + 4; r < BarrierShot::kFrontRows[1] - 4; ++r) {
        const double y = top + r + 0.5;
        for (size_t k = 0; k < xs.size(); ++k) {
          const float light = photo.atPoint(front.xMm(xs[k]), front.yMm(y), 0);
          const double envelope = envelopeAt(above, below, k, yAbove, yBelow, y);
          if (std::isfinite(light) && std::isfinite(envelope))
            fit.add(xs[k] - 0.5 * front.width, y - 0.5 * front.height, light, envelope);
        }
      }
      double shift[3], amplitude[3], mean;
      if (!fit.solve(shift, amplitude, &mean) ||
          !(std::min({amplitude[0], amplitude[1], amplitude[2]}) > kMinContrast))
        continue;
      out.white.push_back(mean);
      // The markers' camera puts the front within a few pixels: each period's shift, taken
      // nearest to none, then averaged (the vernier's jumps of a period are for the rear's
      // offset, which may be anything).
      const double second = shift[0] + wrap(shift[1] - shift[0], BarrierShot::kPeriodsPx[1]);
      out.shiftX[size_t(b * out.across + j)] = 0.5 * (shift[0] + second);
      out.shiftY[size_t(b * out.across + j)] = shift[2];
      out.whiteAt.push_back(b * out.across + j);
    }
  }
  // Blocks in the dark bands of the moire (a third of the brightest blocks' light or less) are
  // noise over almost nothing: dropped.
  std::vector<double> sorted = out.white;
  std::sort(sorted.begin(), sorted.end());
  const double bright = sorted.empty() ? 0 : sorted[size_t(0.9 * double(sorted.size() - 1))];
  for (size_t k = 0; k < out.white.size(); ++k) {
    if (out.white[k] >= bright / 3) {
      ++out.seen;
      continue;
    }
    out.shiftX[size_t(out.whiteAt[k])] = NAN;
    out.shiftY[size_t(out.whiteAt[k])] = NAN;
  }
  return out;
}

std::vector<vision::PlaneCorrespondence> frontPoints(const BarrierShot& shot,
                                                     const FrontBlocks& blocks,
                                                     const vision::CameraFit& camera, size_t photo,
                                                     double trustedShiftPx) {
  std::vector<vision::PlaneCorrespondence> points;
  const double rows = 0.5 * (BarrierShot::kFrontRows[0] + BarrierShot::kFrontRows[1]);
  for (int b = 0; b < blocks.bands; ++b)
    for (int j = 0; j < blocks.across; ++j) {
      const double sx = blocks.at(blocks.shiftX, b, j), sy = blocks.at(blocks.shiftY, b, j);
      // Only blocks the camera already puts near where they are: farther ones may have slipped
      // a period; the next round, with a better camera, takes them.
      if (!(std::abs(sx) < trustedShiftPx && std::abs(sy) < trustedShiftPx)) continue;
      const double x = shot.x0 + 4 + (j + 0.5) * kFrontBlockPx;
      const double y = shot.y0 + b * BarrierShot::kBandPx + rows;
      const vision::PhotoPoint p = vision::projectPoint(camera.intrinsics, camera.poses[photo],
                                                        {shot.front.xMm(x), shot.front.yMm(y), 0});
      points.push_back({shot.front.xMm(x + sx), shot.front.yMm(y + sy), p});
    }
  return points;
}

BarrierMeasurement measureBarrier(const DisplaySpec& nominal, const std::vector<NamedPhoto>& photos,
                                  const std::function<void(int, int)>& progress) {
  if (photos.empty()) throw InputError("photos", "", "no photo of shot grid given");
  const BarrierShot shot = barrierShot(nominal);
  const PanelGrid& front = shot.front;
  const PanelGrid& rear = shot.rear;
  const int total = int(photos.size()) * (kCameraRounds + 1) + 1;
  int done = 0;
  const auto step = [&] {
    if (progress) progress(++done, total);
  };

  // ---- the camera: the markers, then the front's gratings ------------------------------------
  MarkerCamera markers = markerCamera(shot.ring, front, "grid", photos, kMinMarkers);
  step();
  std::vector<FrontBlocks> fronts(photos.size());
  for (int round = 0; round < kCameraRounds; ++round) {
    std::vector<std::vector<vision::PlaneCorrespondence>> more(photos.size());
    for (size_t i = 0; i < photos.size(); ++i) {
      const PhotoSampler photo(photos[i].photo, markers.fit.intrinsics, markers.fit.poses[i]);
      fronts[i] = measureFront(shot, photo);
      more[i] = frontPoints(shot, fronts[i], markers.fit, i, kTrustedShiftPx[round]);
      step();
    }
    refitCamera(markers, photos, more);
  }
  const vision::CameraFit& camera = markers.fit;
  BarrierMeasurement out;
  out.focalPx = camera.intrinsics.focalPx;
  out.focalSigmaPx = camera.focalSigmaPx;
  out.k1 = camera.intrinsics.k1;
  out.k2 = camera.intrinsics.k2;
  // The gap is the parallax over the camera's distance, and the distance is only as good as the
  // focal length: photos that all face the panel squarely leave it (and so the gap) open.
  const double focalRelative = markers.focalRelativeSigma;
  if (!(focalRelative < 0.01)) {
    std::string all;
    for (const NamedPhoto& p : photos) all += (all.empty() ? "" : ", ") + p.name;
    throw InputError(all, "",
                     "the photos do not fix the camera's distance (focal length known to " +
                         std::to_string(int(std::lround(focalRelative * 100))) +
                         " %): take at least one from 10 to 30 degrees to the side of the panel");
  }

  // ---- the rear gratings, block by block -----------------------------------------------------
  const double gap0 = nominal.gapMm;
  std::vector<RearBlock> blocks;
  std::vector<CameraAt> cameras;
  for (size_t pi = 0; pi < photos.size(); ++pi) {
    const vision::CameraPose& pose = camera.poses[pi];
    const std::array<double, 3> c = cameraCentre(markers, pi, photos[pi].name);
    cameras.push_back({c[0], c[1], c[2]});
    BarrierPhotoReport report;
    report.name = photos[pi].name;
    report.markers = markers.markersFound[pi];
    report.cameraMm = c;
    report.offAxisDegrees = std::atan2(std::hypot(c[0], c[1]), c[2]) * 180 / std::numbers::pi;
    report.markerRmsPx = camera.rmsErrorPx[pi];
    const PhotoSampler photo(photos[pi].photo, camera.intrinsics, pose);
    const FrontBlocks frontBlocks = measureFront(shot, photo);
    report.frontBlocks = frontBlocks.seen;
    // Where the line from the camera through front point (x, y) mm meets the rear plane.
    const auto landing = [&](double x, double y, double gap) {
      return std::array<double, 2>{x + (x - c[0]) * gap / c[2], y + (y - c[1]) * gap / c[2]};
    };
    const auto blockX = [&](int j) { return shot.x0 + 4 + j * kBlockPx; };
    std::vector<double> contrasts;
    for (int b = 0; b < shot.bands; ++b) {
      const double top = shot.y0 + b * BarrierShot::kBandPx;
      const double yAbove = top + 0.5 * (kGuardBelowFront[0] + kGuardBelowFront[1]);
      const double yBelow = top + 0.5 * (kGuardBelowRear[0] + kGuardBelowRear[1]);
      // The front rows whose lines land in the middle of the rear's gratings (rows 52 to 76 of
      // its band; the rear may sit a few pixels up or down, and the camera's slant moves them).
      std::vector<double> rows;
      for (double y = top + BarrierShot::kRearRows[0] - 10 + 0.5;
           y < top + BarrierShot::kRearRows[1] + 10; y += 1.0) {
        const double landed =
            front.yPx(landing(front.xMm(0.5 * front.width), front.yMm(y), gap0)[1]) - top;
        if (landed >= BarrierShot::kRearRows[0] + 4 && landed < BarrierShot::kRearRows[1] - 4)
          rows.push_back(y);
      }
      for (int j = 0; j < frontBlocks.across / 2; ++j) {
        // The front's mapping error next to this block: the front blocks above and below.
        double ex = 0, ey = 0;
        int n = 0;
        for (int nb : {b, b + 1})
          for (int half : {2 * j, 2 * j + 1})
            if (nb < shot.bands && std::isfinite(frontBlocks.at(frontBlocks.shiftX, nb, half))) {
              ex += frontBlocks.at(frontBlocks.shiftX, nb, half);
              ey += frontBlocks.at(frontBlocks.shiftY, nb, half);
              ++n;
            }
        if (n == 0 || rows.empty()) continue;
        ex /= n, ey /= n;
        std::vector<double> xs;
        for (double x = blockX(j) + 0.25; x < blockX(j) + kBlockPx; x += 0.5) xs.push_back(x);
        const std::vector<double> above =
            whiteLight(shot, photo, xs, top + kGuardBelowFront[0], top + kGuardBelowFront[1]);
        const std::vector<double> below =
            whiteLight(shot, photo, xs, top + kGuardBelowRear[0], top + kGuardBelowRear[1]);
        PhaseFit fit({{0, BarrierShot::kPeriodsPx[0]},
                      {0, BarrierShot::kPeriodsPx[1]},
                      {1, BarrierShot::kFrontRowPeriodPx}});
        for (const double y : rows)
          for (size_t k = 0; k < xs.size(); ++k) {
            const float light = photo.atPoint(front.xMm(xs[k]), front.yMm(y), 0);
            const double envelope = envelopeAt(above, below, k, yAbove, yBelow, y);
            if (!std::isfinite(light) || !std::isfinite(envelope)) continue;
            // The front point really seen there is (ex, ey) pixels further on; the rear pixel
            // its line reaches, from the rear's centre (x right, y down), for the nominal gap.
            const auto r = landing(front.xMm(xs[k] + ex), front.yMm(y + ey), gap0);
            fit.add(r[0] / rear.pitchMm, -r[1] / rear.pitchMm, light, envelope);
          }
        RearBlock block;
        double mean;
        if (!fit.solve(block.shift, block.amplitude, &mean)) continue;
        // The white rows' moire: light passes where a front stripe's aperture lies over the
        // rear's of its colour, so the white light peaks where the two stripe gratings are in
        // phase, m = (rear pixel reached, from its left edge) - (front pixel) an integer. Its
        // phase measures u - u0 modulo a rear pixel, and unlike the gratings (whose rear pixels
        // are seen only where the stripes line up, a whole number of pixels from the front's)
        // it follows the line exactly; an error of the camera moves both ends of the line alike
        // and leaves it.
        {
          PhaseFit moire({{0, 1.0}});
          for (const auto& [light, y] : {std::pair{&above, yAbove}, std::pair{&below, yBelow}})
            for (size_t k = 0; k < xs.size(); ++k) {
              if (!std::isfinite((*light)[k])) continue;
              const double xf = xs[k] + ex;
              const double m = rear.xPx(landing(front.xMm(xf), front.yMm(y + ey), gap0)[0]) - xf;
              moire.add(m, 0, (*light)[k], 1.0);
            }
          double moireMean;
          if (!moire.solve(&block.shift[3], &block.amplitude[3], &moireMean)) continue;
        }
        contrasts.push_back(block.amplitude[0] + block.amplitude[1]);
        if (!(std::min({block.amplitude[0], block.amplitude[1], block.amplitude[2]}) >
              kMinContrast))
          continue;
        block.photo = int(pi);
        block.xMm = front.xMm(blockX(j) + 0.5 * kBlockPx + ex);
        block.yMm = front.yMm(0.5 * (rows.front() + rows.back()) + ey);
        const auto r = landing(block.xMm, block.yMm, gap0);
        block.u0 = r[0] / rear.pitchMm;
        block.v0 = -r[1] / rear.pitchMm;
        block.du = vernier(block.shift[0], block.shift[1]);
        blocks.push_back(block);
        ++report.rearBlocks;
      }
    }
    std::sort(contrasts.begin(), contrasts.end());
    report.contrast = contrasts.empty() ? 0 : contrasts[contrasts.size() / 2];
    if (report.rearBlocks < 4)
      throw InputError(photos[pi].name, "",
                       "the gratings are not resolved (contrast " +
                           std::to_string(report.contrast).substr(0, 5) +
                           "): too blurred, too far or shaken; take it closer, in focus");
    out.photos.push_back(report);
    step();
  }

  // ---- one fit over all blocks --------------------------------------------------------------
  // Unknowns g, s_x, s_y, theta. With the line's rear point X_r = X + (X - C_x) g / C_z (and
  // Y_r), the rear pixel seen (from its centre, x right, y down) is
  //   u = [X_r - s_x + theta Y_r] / p,   v = -[Y_r - s_y - theta X_r] / p,
  // linear in the unknowns once theta g is taken at the last pass's values.
  const double periods[4] = {BarrierShot::kPeriodsPx[0], BarrierShot::kPeriodsPx[1],
                             BarrierShot::kFrontRowPeriodPx, 1.0};
  double g = gap0, sx = 0, sy = 0, theta = 0, sigma2 = 0;
  std::vector<double> x, covariance;
  struct Observation {
    size_t block;
    int component;  // 0, 1 across (u), 2 down (v), 3 across (u) from the moire
    double value, weight;
  };
  // An observation's row (the unknowns' coefficients) and constant part.
  const auto rowFor = [&](const RearBlock& b, int component, double* row) {
    const CameraAt& c = cameras[size_t(b.photo)];
    const double p = rear.pitchMm;
    const double xr = b.xMm + (b.xMm - c.x) * g / c.z, yr = b.yMm + (b.yMm - c.y) * g / c.z;
    if (component != 2) {
      row[0] = (b.xMm - c.x + theta * (b.yMm - c.y)) / (c.z * p);
      row[1] = -1 / p, row[2] = 0, row[3] = yr / p;
      return b.xMm / p - b.u0;
    }
    row[0] = -(b.yMm - c.y - theta * (b.xMm - c.x)) / (c.z * p);
    row[1] = 0, row[2] = 1 / p, row[3] = xr / p;
    return -b.yMm / p - b.v0;
  };
  const auto predicted = [&](const RearBlock& b, int component) {
    double row[4];
    const double constant = rowFor(b, component, row);
    return constant + row[0] * g + row[1] * sx + row[2] * sy + row[3] * theta;
  };
  // The moire's phases say where each block's line lands only modulo a rear pixel; the gratings'
  // first fit (pass 0) is good to a quarter of a pixel or so, which a wrong gap's slope across
  // the panel can exceed. So between the passes, the gap is searched over its whole range for
  // the one whose moire phases agree best (the phasors' sum is longest; s_x, which moves every
  // block alike, drops out of its length), before the moire is unwrapped against it.
  const auto coherentGap = [&](double thetaNow) {
    double bestGap = g, bestLength = -1;
    for (double trial = 0.6 * gap0; trial <= 1.4 * gap0; trial += 0.0005 * gap0) {
      double re = 0, im = 0;
      for (const RearBlock& b : blocks) {
        const CameraAt& c = cameras[size_t(b.photo)];
        const double xr = b.xMm + (b.xMm - c.x) * trial / c.z;
        const double yr = b.yMm + (b.yMm - c.y) * trial / c.z;
        const double model = (xr + thetaNow * yr) / rear.pitchMm - b.u0;
        const double w = b.amplitude[3];
        re += w * std::cos(kTwoPi * (b.shift[3] - model));
        im += w * std::sin(kTwoPi * (b.shift[3] - model));
      }
      const double length = std::hypot(re, im);
      if (length > bestLength) bestLength = length, bestGap = trial;
    }
    return bestGap;
  };
  for (int pass = 0; pass < 4; ++pass) {
    if (pass == 1) {
      // s_x: the moire's common phase at the searched gap, its whole pixels from pass 0.
      g = coherentGap(theta);
      double re = 0, im = 0;
      for (const RearBlock& b : blocks) {
        const CameraAt& c = cameras[size_t(b.photo)];
        const double xr = b.xMm + (b.xMm - c.x) * g / c.z;
        const double yr = b.yMm + (b.yMm - c.y) * g / c.z;
        const double model = (xr + theta * yr) / rear.pitchMm - b.u0;  // with s_x = 0
        re += b.amplitude[3] * std::cos(kTwoPi * (b.shift[3] - model));
        im += b.amplitude[3] * std::sin(kTwoPi * (b.shift[3] - model));
      }
      // shift = model - s_x / p: the common phase is -s_x / p modulo a pixel.
      const double fraction = -std::atan2(im, re) / kTwoPi * rear.pitchMm;
      sx = fraction + rear.pitchMm * std::round((sx - fraction) / rear.pitchMm);
    }
    LeastSquares ls(4);
    // The first pass takes each block's vernier across (those near the median: a vernier that
    // slipped is a period off) and its shift down; later ones unwrap each component against the
    // model and use it alone, leaving out what is four sigmas off.
    std::vector<Observation> obs;
    if (pass == 0) {
      std::vector<double> dus;
      for (const RearBlock& b : blocks) dus.push_back(b.du);
      std::nth_element(dus.begin(), dus.begin() + long(dus.size() / 2), dus.end());
      const double median = dus[dus.size() / 2];
      for (size_t i = 0; i < blocks.size(); ++i) {
        if (std::abs(blocks[i].du - median) <= 6) obs.push_back({i, 0, blocks[i].du, 1.0});
        obs.push_back({i, 2, blocks[i].shift[2], 1.0});
      }
    } else {
      // The moire alone once the gratings' verniers have placed it within half a pixel: the
      // gratings' shifts carry the stripes' whole-pixel steps (a quarter of a pixel either way
      // across; down, the rows' black matrix does the same more weakly). The rear's height,
      // which no key of the display file holds, stays where the first pass put it.
      for (size_t i = 0; i < blocks.size(); ++i)
        for (int j : {3}) {
          const double model = predicted(blocks[i], j);
          const double r = wrap(blocks[i].shift[j] - model, periods[j]);
          if (pass >= 2 && r * r > 16 * sigma2) continue;
          obs.push_back({i, j, model + r, blocks[i].amplitude[j] * blocks[i].amplitude[j]});
        }
    }
    double weightSum = 0;
    for (const Observation& o : obs) {
      double row[4];
      const double constant = rowFor(blocks[o.block], o.component, row);
      ls.add(row, o.value - constant, o.weight);
      weightSum += o.weight;
    }
    if (pass > 0) {
      const double pin[4] = {0, 0, 1, 0};
      ls.add(pin, sy, weightSum);
    }
    if (ls.rows() < 8 || !ls.solve(x, &covariance))
      throw InputError("photos", "", "too few grating blocks were seen to measure the gap");
    g = x[0], sx = x[1], sy = x[2], theta = x[3];
    double sum = 0, weights = 0;
    for (const Observation& o : obs) {
      const double r = o.value - predicted(blocks[o.block], o.component);
      sum += o.weight * r * r;
      weights += o.weight;
    }
    sigma2 = sum / std::max(1e-300, weights);
    // The covariance per unit weight scaled by the residuals'.
    const double perUnit = sum / std::max(1.0, double(obs.size()) - 4);
    for (double& v : covariance) v *= perUnit;
  }
  step();
  out.residualPx = std::sqrt(sigma2);
  out.gapMm = g;
  out.gapSigmaMm = std::hypot(std::sqrt(covariance[0]), g * focalRelative);
  // A set whose photos pin the gap too loosely is refused rather than written: the slit period
  // needs the gap within 1 % (docs/calibration.md), and past a sigma of 0.8 % the study's sets
  // (whose sigmas are honest: 96 % within two) miss it one time in three.
  constexpr double kMaxGapRelativeSigma = 0.008;
  if (!(out.gapSigmaMm < kMaxGapRelativeSigma * g)) {
    std::string all;
    for (const NamedPhoto& p : photos) all += (all.empty() ? "" : ", ") + p.name;
    const long hundredths = std::lround(10000 * out.gapSigmaMm / g);
    const std::string cents = std::to_string(100 + hundredths % 100).substr(1);
    throw InputError(all, "",
                     "the photos pin the gap only to ± " + std::to_string(hundredths / 100) + "." +
                         cents +
                         " % (one sigma; at most 0.80 % is needed): take one 10 to 30 degrees to "
                         "the left of the panel and one to the right, the whole panel sharp in "
                         "both");
  }
  out.rearOffsetXMm = sx;
  out.rearOffsetSigmaMm = std::sqrt(covariance[5]);
  out.rearOffsetYMm = sy;
  out.rotationDegrees = theta * 180 / std::numbers::pi;
  out.rotationSigmaDegrees = std::sqrt(covariance[15]) * 180 / std::numbers::pi;
  // The display file's offset: the mask panel against the image panel, in mask pixels, as the
  // amount the drawn mask moves to make up for it (a mask sitting o pixels to the left: +o).
  const double maskPitch = nominal.maskPanel.pitchMm;
  const double maskShiftMm = shot.frontIsImage ? sx : -sx;
  out.maskPanelOffsetPx = -maskShiftMm / maskPitch;
  out.maskPanelOffsetSigmaPx = out.rearOffsetSigmaMm / maskPitch;
  out.maskRotationDegrees = shot.frontIsImage ? out.rotationDegrees : -out.rotationDegrees;
  out.rotationEdgeErrorPx = std::abs(theta) * 0.5 * nominal.maskPanel.heightMm() / maskPitch;
  return out;
}

}  // namespace parallax::photocal
