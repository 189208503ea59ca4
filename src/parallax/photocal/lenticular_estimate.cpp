// The lenticular estimate (lenticular_estimate.h): per photo, the fringes' phase psi as a plane
// over the lens sheet (the photo read at lens-sheet points through the camera the markers gave);
// then one least-squares fit of the sheet (g, m, phi) to every photo's plane.
#include "parallax/photocal/lenticular_estimate.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "parallax/core/error.h"
#include "parallax/photocal/least_squares.h"
#include "parallax/photocal/lenticular_shot.h"
#include "parallax/photocal/photo_sampler.h"

namespace parallax::photocal {

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr double kMinCoherence = 0.3;

double wrapHalf(double v) {
  return v - std::round(v);
}

struct FringePlane {
  double gx = 0, gy = 0, phase = 0;  // Psi / 2 pi = gx x + gy y + phase (cycles, mm)
  double sigmaGradient = 0, sigmaPhase = 0;
  double coherence = 0;
  int samples = 0;
};

// The fringes' phase plane from the photo at lens-sheet points (x, y) on a grid of `step` mm.
FringePlane fitFringes(const PhotoSampler& photo, double x0, double x1, double y0, double y1,
                       double sheetZ, double step) {
  const int nx = int((x1 - x0) / step), ny = int((y1 - y0) / step);
  std::vector<std::array<float, 3>> rgb(size_t(nx) * size_t(ny));
  std::vector<char> valid(rgb.size(), 0);
  double mean[3] = {0, 0, 0}, square[3] = {0, 0, 0};
  int count = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      float c[3];
      const size_t k = size_t(j) * size_t(nx) + size_t(i);
      if (!photo.rgbAt(photo.project(x0 + (i + 0.5) * step, y0 + (j + 0.5) * step, sheetZ), c))
        continue;
      valid[k] = 1;
      for (int ch = 0; ch < 3; ++ch) {
        rgb[k][size_t(ch)] = c[ch];
        mean[ch] += c[ch];
        square[ch] += double(c[ch]) * c[ch];
      }
      ++count;
    }
  FringePlane plane;
  plane.samples = count;
  if (count < 100) return plane;
  double amplitude[3];
  for (int ch = 0; ch < 3; ++ch) {
    mean[ch] /= count;
    amplitude[ch] = std::sqrt(std::max(1e-12, 2 * (square[ch] / count - mean[ch] * mean[ch])));
  }
  // The phasor red + i blue, each channel's mean and amplitude taken out.
  std::vector<std::complex<double>> z(rgb.size());
  for (size_t k = 0; k < z.size(); ++k)
    if (valid[k])
      z[k] = {(rgb[k][0] - mean[0]) / amplitude[0], (rgb[k][2] - mean[2]) / amplitude[2]};
  // The gradient from neighbours' phase differences (the fringes change by far less than half a
  // cycle from one grid point to the next), then the phase from the demodulated sum.
  std::complex<double> sx = 0, sy = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const size_t k = size_t(j) * size_t(nx) + size_t(i);
      if (!valid[k]) continue;
      if (i + 1 < nx && valid[k + 1]) sx += z[k + 1] * std::conj(z[k]);
      if (j + 1 < ny && valid[k + size_t(nx)]) sy += z[k + size_t(nx)] * std::conj(z[k]);
    }
  plane.gx = std::arg(sx) / (kTwoPi * step);
  plane.gy = std::arg(sy) / (kTwoPi * step);
  // Gauss-Newton on the phase residuals, weighted by each phasor's length.
  for (int iteration = 0; iteration < 4; ++iteration) {
    std::complex<double> sum = 0;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const size_t k = size_t(j) * size_t(nx) + size_t(i);
        if (!valid[k]) continue;
        const double x = x0 + (i + 0.5) * step, y = y0 + (j + 0.5) * step;
        sum += z[k] * std::polar(1.0, -kTwoPi * (plane.gx * x + plane.gy * y));
      }
    plane.phase = std::arg(sum) / kTwoPi;
    LeastSquares ls(3);
    double weights = 0, squares = 0, length = 0;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const size_t k = size_t(j) * size_t(nx) + size_t(i);
        if (!valid[k]) continue;
        const double x = x0 + (i + 0.5) * step, y = y0 + (j + 0.5) * step;
        const double w = std::abs(z[k]);
        const double r =
            wrapHalf(std::arg(z[k]) / kTwoPi - (plane.gx * x + plane.gy * y + plane.phase));
        const double row[3] = {x, y, 1};
        ls.add(row, r, w * w);
        weights += w * w;
        squares += w * w * r * r;
        length += w;
      }
    std::vector<double> d, covariance;
    if (!ls.solve(d, &covariance)) return plane;
    plane.gx += d[0], plane.gy += d[1], plane.phase += d[2];
    const double variance = squares / std::max(1.0, weights);
    // The samples are not independent (the photo's blur and the lenses' steps join
    // neighbours): count one per lens-sized cell, about a square millimetre.
    const double correlation = std::max(1.0, 1.0 / (step * step));
    plane.sigmaGradient = std::sqrt(variance * covariance[0] * weights * correlation);
    plane.sigmaPhase = std::sqrt(variance * covariance[8] * weights * correlation);
    plane.coherence = std::abs(sum) / std::max(1e-12, length);
  }
  return plane;
}

}  // namespace

LenticularMeasurement measureLenticular(const LenticularDesign& nominal,
                                        const std::vector<NamedPhoto>& photos,
                                        const std::function<void(int, int)>& progress) {
  if (photos.empty()) throw InputError("photos", "", "no photo of shot lens given");
  const LenticularShot shot = lenticularShot(nominal);
  const PhaseField field = phaseFieldOf(nominal);
  const bool invView = nominal.calibration.invView;
  const double D = nominal.viewDistanceMm;
  // The nominal sheet's gap, from the view cone: a lens of horizontal width p_h sends a view
  // cone of 2 atan(p_h / 2 g).
  const double gapGuess =
      nominal.horizontalLensPitchMm /
      (2 * std::tan(nominal.calibration.viewConeDegrees * std::numbers::pi / 360));
  int done = 0;
  const int total = int(photos.size()) + 1;

  // The markers are drawn on the pixels and seen through the lenses where the pixels are: the
  // plane the camera is fitted to is the pixel plane; the lens sheet lies a gap in front of it.
  const MarkerCamera markers = markerCamera(shot.ring, shot.panel, "lens", photos, 6);
  const vision::CameraFit& camera = markers.fit;
  if (progress) progress(++done, total);
  LenticularMeasurement out;
  out.focalPx = camera.intrinsics.focalPx;
  out.focalSigmaPx = camera.focalSigmaPx;
  out.k1 = camera.intrinsics.k1;
  out.k2 = camera.intrinsics.k2;
  std::vector<FringePlane> planes;
  std::vector<std::array<double, 3>> centres;  // over the lens sheet
  const double margin = 2.0;                   // mm inside the shot's interior
  const double x0 = shot.panel.xMm(shot.x0) + margin, x1 = shot.panel.xMm(shot.x1) - margin;
  const double y0 = shot.panel.yMm(shot.y1) + margin, y1 = shot.panel.yMm(shot.y0) - margin;
  for (size_t i = 0; i < photos.size(); ++i) {
    std::array<double, 3> c = cameraCentre(markers, i, photos[i].name);
    c[2] -= gapGuess;
    const PhotoSampler photo(photos[i].photo, camera.intrinsics, camera.poses[i], true);
    const FringePlane plane = fitFringes(photo, x0, x1, y0, y1, gapGuess, 0.25);
    LenticularPhotoReport report;
    report.name = photos[i].name;
    report.cameraMm = c;
    report.offAxisDegrees = std::atan2(std::hypot(c[0], c[1]), c[2]) * 180 / std::numbers::pi;
    report.markers = markers.markersFound[i];
    report.markerRmsPx = camera.rmsErrorPx[i];
    report.samples = plane.samples;
    report.coherence = plane.coherence;
    // psi, the raw phase seen (less the lens count), is -Psi with invView and +Psi without.
    const double s = invView ? -1.0 : 1.0;
    report.fringeGradient = {s * plane.gx, s * plane.gy};
    report.fringePhase = s * plane.phase;
    if (!(plane.coherence > kMinCoherence))
      throw InputError(photos[i].name, "",
                       "the fringes are not resolved (coherence " +
                           std::to_string(plane.coherence).substr(0, 4) +
                           "): too blurred, shaken, or not the lens shot's panel");
    out.photos.push_back(report);
    planes.push_back(plane);
    centres.push_back(c);
    if (progress) progress(++done, total);
  }

  // ---- the sheet: g, m (2), phi from every photo's plane --------------------------------------
  std::vector<double> x{gapGuess, field.gx, field.gy, 0}, covariance;
  for (int pass = 0; pass < 3; ++pass) {
    LeastSquares ls(4);
    for (size_t i = 0; i < planes.size(); ++i) {
      const LenticularPhotoReport& p = out.photos[i];
      const std::array<double, 3>& c = centres[i];
      const double wg = 1 / std::pow(std::max(planes[i].sigmaGradient, 1e-9), 2);
      const double wp = 1 / std::pow(std::max(planes[i].sigmaPhase, 1e-6), 2);
      const double rowX[4] = {field.gx / c[2], -1, 0, 0};
      ls.add(rowX, p.fringeGradient[0] - field.gx, wg);
      const double rowY[4] = {field.gy / c[2], 0, -1, 0};
      ls.add(rowY, p.fringeGradient[1] - field.gy, wg);
      if (pass == 0) continue;  // the phases are unwrapped against the first pass's sheet
      const double lever = (field.gx * c[0] + field.gy * c[1]) / c[2];
      const double model = x[3] - x[0] * lever + field.r0;
      const double seen = model + wrapHalf(p.fringePhase - model);
      const double rowPhase[4] = {-lever, 0, 0, 1};
      ls.add(rowPhase, seen - field.r0, wp);
    }
    if (pass == 0) {
      // Without the phases yet, phi is free: pin it (it does not enter the gradients).
      const double pin[4] = {0, 0, 0, 1};
      ls.add(pin, 0, 1);
    }
    if (!ls.solve(x, &covariance))
      throw InputError("photos", "", "the photos do not constrain the lens sheet");
  }
  out.gapMm = x[0];
  out.gapSigmaMm = std::sqrt(std::max(0.0, covariance[0]));
  if (!(out.gapSigmaMm < 0.1 * gapGuess)) {
    std::string all;
    for (const NamedPhoto& p : photos) all += (all.empty() ? "" : ", ") + p.name;
    throw InputError(all, "",
                     "the photos are all from about one distance: the lens sheet's gap is left "
                     "open; take two, one at least a quarter nearer than the other");
  }
  const auto fieldOf = [&](const std::vector<double>& v) {
    PhaseField f{v[1] / (1 + v[0] / D), v[2] / (1 + v[0] / D), 0.5 - v[3]};
    f.r0 -= std::floor(f.r0);
    return f;
  };
  out.measured = calibrationWithField(nominal.calibration, fieldOf(x), D);
  // The estimates' uncertainties through the conversion, one unknown at a time.
  double variance[3] = {0, 0, 0};
  std::vector<std::array<double, 3>> jacobian(4);
  for (int k = 0; k < 4; ++k) {
    std::vector<double> y = x;
    const double h = std::sqrt(std::max(covariance[size_t(5 * k)], 1e-30));
    y[size_t(k)] += h;
    const LenticularCalibration moved = calibrationWithField(nominal.calibration, fieldOf(y), D);
    jacobian[size_t(k)] = {(moved.pitch - out.measured.pitch) / h,
                           (moved.slope - out.measured.slope) / h,
                           wrapHalf(moved.center - out.measured.center) / h};
  }
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k < 4; ++k)
      for (int l = 0; l < 4; ++l)
        variance[a] += jacobian[size_t(k)][size_t(a)] * jacobian[size_t(l)][size_t(a)] *
                       covariance[size_t(4 * k + l)];
  out.pitchSigma = std::sqrt(std::max(0.0, variance[0]));
  out.slopeSigma = std::sqrt(std::max(0.0, variance[1]));
  out.centerSigma = std::sqrt(std::max(0.0, variance[2]));
  out.slantDegrees = std::atan2(-x[2], x[1]) * 180 / std::numbers::pi * (invView ? 1 : -1);
  const double m2 = x[1] * x[1] + x[2] * x[2];
  out.slantSigmaDegrees =
      std::sqrt(std::max(0.0, (x[2] * x[2] * covariance[5] + x[1] * x[1] * covariance[10] -
                               2 * x[1] * x[2] * covariance[6]) /
                                  (m2 * m2))) *
      180 / std::numbers::pi;
  return out;
}

}  // namespace parallax::photocal
