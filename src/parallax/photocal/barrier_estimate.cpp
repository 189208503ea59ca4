// The barrier estimate (barrier_estimate.h; the derivation is docs/calibration.md, "From
// photos"). Per photo: the markers give a first camera; the front bands give, per block, where
// the front really is (the phases of its gratings against where the camera says it is), and
// those thousands of points fit the camera again; then the rear bands give, per block, which
// rear point the camera sees through each front point. One least-squares fit over all photos'
// blocks gives the gap, the rear offset and the rotation.
#include "parallax/photocal/barrier_estimate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include "parallax/core/error.h"
#include "parallax/photocal/least_squares.h"
#include "parallax/photocal/photo_sampler.h"

namespace parallax::photocal {

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr int kBlockPx = BarrierShot::kBlockPx;
constexpr int kFrontBlockPx = kBlockPx / 2;  // the front needs no vernier: twice the points
constexpr double kMinContrast = 0.03;  // a grating's amplitude over the mean light
constexpr int kMinMarkers = 2;         // a first camera; the front's gratings fit it again
constexpr int kCameraRounds = 5;
constexpr double kTrustedShiftPx = 4;  // well inside half the periods (6 across, 16 down)

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
  double xMm = 0, yMm = 0;   // the block's centre on the front (corrected), mm
  double u0 = 0;             // rear pixel (from the centre) the nominal display puts there
  double shift[2] = {0, 0};  // observed u - u0, modulo each period
  double amplitude[2] = {0, 0};
  double du = 0;  // resolved u - u0
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
                                                     const vision::CameraFit& camera,
                                                     size_t photo) {
  std::vector<vision::PlaneCorrespondence> points;
  const double rows = 0.5 * (BarrierShot::kFrontRows[0] + BarrierShot::kFrontRows[1]);
  for (int b = 0; b < blocks.bands; ++b)
    for (int j = 0; j < blocks.across; ++j) {
      const double sx = blocks.at(blocks.shiftX, b, j), sy = blocks.at(blocks.shiftY, b, j);
      // Only blocks the camera already puts near where they are: farther ones may have slipped
      // a period; the next round, with a better camera, takes them.
      if (!(std::abs(sx) < kTrustedShiftPx && std::abs(sy) < kTrustedShiftPx)) continue;
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
      more[i] = frontPoints(shot, fronts[i], markers.fit, i);
      if (std::getenv("PARALLAX_DEBUG_PHOTOCAL")) {
        std::fprintf(stderr, "round %d photo %zu before: marker rms %.3f; shifts:", round, i, markers.fit.rmsErrorPx[i]);
        for (size_t k = 0; k < fronts[i].shiftX.size(); k += 7)
          std::fprintf(stderr, " (%.1f,%.1f)", fronts[i].shiftX[k], fronts[i].shiftY[k]);
        std::fprintf(stderr, "\n");
      }
      step();
    }
    refitCamera(markers, photos, more);
    if (std::getenv("PARALLAX_DEBUG_PHOTOCAL"))
      for (size_t i = 0; i < photos.size(); ++i) {
        const auto c = markers.fit.poses[i].cameraCentre();
        std::fprintf(stderr, "round %d photo %zu: %d front blocks, f %.1f +- %.1f, k1 %.3f, rms %.3f, C %.1f %.1f %.1f\n", round, i, fronts[i].seen,
                     markers.fit.intrinsics.focalPx, markers.fit.focalSigmaPx, markers.fit.intrinsics.k1,
                     markers.fit.rmsErrorPx[i], c[0], c[1], c[2]);
      }
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
      // The rows whose lines land on the rear gratings: between the guards, found by their
      // contrast (the rear may sit a few pixels up or down).
      const int firstRow = BarrierShot::kRearRows[0] - 8, lastRow = BarrierShot::kRearRows[1] + 4;
      std::vector<double> allXs;
      for (double x = shot.x0 + 4.25; x < shot.x1 - 4; x += 0.5) allXs.push_back(x);
      const std::vector<double> allAbove =
          whiteLight(shot, photo, allXs, top + kGuardBelowFront[0], top + kGuardBelowFront[1]);
      const std::vector<double> allBelow =
          whiteLight(shot, photo, allXs, top + kGuardBelowRear[0], top + kGuardBelowRear[1]);
      const int rows = lastRow - firstRow;
      std::vector<double> rowAmplitude(size_t(rows), 0.0);
      for (int r = 0; r < rows; ++r) {
        PhaseFit fit({{0, BarrierShot::kPeriodsPx[0]}, {0, BarrierShot::kPeriodsPx[1]}});
        const double y = top + firstRow + r + 0.5;
        for (size_t k = 0; k < allXs.size(); k += 2) {
          const double xm = front.xMm(allXs[k]), ym = front.yMm(y);
          const float light = photo.atPoint(xm, ym, 0);
          const double envelope = envelopeAt(allAbove, allBelow, k, yAbove, yBelow, y);
          if (std::isfinite(light) && std::isfinite(envelope))
            fit.add(landing(xm, ym, gap0)[0] / rear.pitchMm, 0, light, envelope);
        }
        double shift[2], amplitude[2], mean;
        if (fit.solve(shift, amplitude, &mean)) rowAmplitude[size_t(r)] = amplitude[0] + amplitude[1];
      }
      const double best = *std::max_element(rowAmplitude.begin(), rowAmplitude.end());
      for (int j = 0; j < frontBlocks.across / 2; ++j) {
        // The front's mapping error next to this block: the front blocks above and below.
        double e = 0;
        int n = 0;
        for (int nb : {b, b + 1})
          for (int half : {2 * j, 2 * j + 1})
            if (nb < shot.bands && std::isfinite(frontBlocks.at(frontBlocks.shiftX, nb, half))) {
              e += frontBlocks.at(frontBlocks.shiftX, nb, half);
              ++n;
            }
        if (n == 0) continue;
        e /= n;
        std::vector<double> xs;
        for (double x = blockX(j) + 0.25; x < blockX(j) + kBlockPx; x += 0.5) xs.push_back(x);
        const std::vector<double> above =
            whiteLight(shot, photo, xs, top + kGuardBelowFront[0], top + kGuardBelowFront[1]);
        const std::vector<double> below =
            whiteLight(shot, photo, xs, top + kGuardBelowRear[0], top + kGuardBelowRear[1]);
        PhaseFit fit({{0, BarrierShot::kPeriodsPx[0]}, {0, BarrierShot::kPeriodsPx[1]}});
        double rowSum = 0;
        int rowCount = 0;
        for (int r = 0; r < rows; ++r) {
          if (!(rowAmplitude[size_t(r)] > 0.6 * best)) continue;
          const double y = top + firstRow + r + 0.5;
          rowSum += y;
          ++rowCount;
          for (size_t k = 0; k < xs.size(); ++k) {
            const float light = photo.atPoint(front.xMm(xs[k]), front.yMm(y), 0);
            const double envelope = envelopeAt(above, below, k, yAbove, yBelow, y);
            if (!std::isfinite(light) || !std::isfinite(envelope)) continue;
            // The front point really seen there is e pixels further along.
            const double xm = front.xMm(xs[k] + e), ym = front.yMm(y);
            fit.add(landing(xm, ym, gap0)[0] / rear.pitchMm, 0, light, envelope);
          }
        }
        RearBlock block;
        double mean;
        if (rowCount == 0 || !fit.solve(block.shift, block.amplitude, &mean)) continue;
        contrasts.push_back(block.amplitude[0] + block.amplitude[1]);
        if (!(std::min(block.amplitude[0], block.amplitude[1]) > kMinContrast)) continue;
        block.photo = int(pi);
        block.xMm = front.xMm(blockX(j) + 0.5 * kBlockPx + e);
        block.yMm = front.yMm(rowSum / rowCount);
        block.u0 = landing(block.xMm, block.yMm, gap0)[0] / rear.pitchMm;
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
  // Unknowns g, s_x, theta: u = [X + (X - C_x) g / C_z - s_x + theta (Y + (Y - C_y) g / C_z)] / p
  // (rear pixels from the rear's centre), linearised in theta g.
  const double p0 = BarrierShot::kPeriodsPx[0], p1 = BarrierShot::kPeriodsPx[1];
  double g = gap0, sx = 0, theta = 0, sigma2 = 0;
  std::vector<double> x, covariance;
  for (int pass = 0; pass < 4; ++pass) {
    LeastSquares ls(3);
    const auto rowFor = [&](const RearBlock& b, double* row) {
      const CameraAt& c = cameras[size_t(b.photo)];
      const double p = rear.pitchMm;
      row[0] = (b.xMm - c.x + theta * (b.yMm - c.y)) / (c.z * p);
      row[1] = -1 / p;
      row[2] = (b.yMm + (b.yMm - c.y) * g / c.z) / p;
      return b.xMm / p;  // the constant part
    };
    const auto predicted = [&](const RearBlock& b) {
      double row[3];
      const double constant = rowFor(b, row);
      return constant + row[0] * g + row[1] * sx + row[2] * theta - b.u0;
    };
    // The first pass takes each block's vernier; later ones unwrap each period's shift against
    // the model and use it alone, leaving out blocks four sigmas off.
    struct Observation {
      size_t block;
      double value, weight;
    };
    std::vector<Observation> obs;
    for (size_t i = 0; i < blocks.size(); ++i) {
      const RearBlock& b = blocks[i];
      if (pass == 0) {
        obs.push_back({i, b.du, 1.0});
        continue;
      }
      const double model = predicted(b);
      for (int j = 0; j < 2; ++j) {
        const double value = model + wrap(b.shift[j] - model, j == 0 ? p0 : p1);
        const double r = value - model;
        if (pass >= 2 && r * r > 16 * sigma2) continue;
        obs.push_back({i, value, b.amplitude[j] * b.amplitude[j]});
      }
    }
    if (pass == 0) {
      // The verniers' median offset first: a block whose vernier slipped by a period is far
      // from it.
      std::vector<double> dus;
      for (const RearBlock& b : blocks) dus.push_back(b.du);
      std::nth_element(dus.begin(), dus.begin() + long(dus.size() / 2), dus.end());
      const double median = dus[dus.size() / 2];
      std::erase_if(obs, [&](const Observation& o) { return std::abs(o.value - median) > 6; });
    }
    for (const Observation& o : obs) {
      const RearBlock& b = blocks[o.block];
      double row[3];
      const double constant = rowFor(b, row);
      ls.add(row, o.value + b.u0 - constant, o.weight);
    }
    if (ls.rows() < 6 || !ls.solve(x, &covariance))
      throw InputError("photos", "", "too few grating blocks were seen to measure the gap");
    g = x[0], sx = x[1], theta = x[2];
    double sum = 0, weights = 0;
    for (const Observation& o : obs) {
      const double r = o.value - predicted(blocks[o.block]);
      sum += o.weight * r * r;
      weights += o.weight;
    }
    sigma2 = sum / std::max(1e-300, weights);
    // The covariance per unit weight scaled by the residuals'.
    const double perUnit = sum / std::max(1.0, double(obs.size()) - 3);
    for (double& v : covariance) v *= perUnit;
  }
  step();
  out.residualPx = std::sqrt(sigma2);
  out.gapMm = g;
  out.gapSigmaMm = std::hypot(std::sqrt(covariance[0]), g * focalRelative);
  out.rearOffsetXMm = sx;
  out.rearOffsetSigmaMm = std::sqrt(covariance[4]);
  out.rotationDegrees = theta * 180 / std::numbers::pi;
  out.rotationSigmaDegrees = std::sqrt(covariance[8]) * 180 / std::numbers::pi;
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
