// The lenticular estimate (lenticular_estimate.h): per photo, the fringes' phase psi as a plane
// over the lens sheet (the photo read at lens-sheet points through the camera the markers gave);
// then one least-squares fit of the sheet (g, m, phi) to every photo's plane.
#include "parallax/photocal/lenticular_estimate.h"

#include <algorithm>
#include <array>
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
constexpr double kMaxPhaseSigma = 0.05;  // cycles: a photo whose fringes say less is refused

double wrapHalf(double v) {
  return v - std::round(v);
}

struct FringePlane {
  double gx = 0, gy = 0, phase = 0;  // arg z / 2 pi = gx x + gy y + phase (cycles, mm)
  double amplitude = 0;              // |z| of the fit: 1 full contrast
  double sigmaGx = 0, sigmaGy = 0, sigmaPhase = 0;
  double coherence = 0;  // the fit's amplitude over the blocks' rms |z|: 1 clean, 0 none
  int samples = 0;
};

// The mean R, G, B of the photo over a rectangle of the sheet (mm, at depth sheetZ in the
// marker camera's frame), sampled on a grid of `step`; false when less than half of it is in the
// photo.
bool meanRgb(const PhotoSampler& photo, double x0, double x1, double y0, double y1, double sheetZ,
             double step, double rgb[3], int* count = nullptr) {
  const int nx = std::max(1, int(std::lround((x1 - x0) / step)));
  const int ny = std::max(1, int(std::lround((y1 - y0) / step)));
  double sum[3] = {0, 0, 0};
  int n = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      float c[3];
      const double x = x0 + (i + 0.5) * (x1 - x0) / nx, y = y0 + (j + 0.5) * (y1 - y0) / ny;
      if (!photo.rgbAt(photo.project(x, y, sheetZ), c)) continue;
      for (int ch = 0; ch < 3; ++ch) sum[ch] += c[ch];
      ++n;
    }
  if (count) *count += n;
  if (2 * n < nx * ny) return false;
  for (int ch = 0; ch < 3; ++ch) rgb[ch] = sum[ch] / n;
  return true;
}

// The fringes' phasor plane. The photo is read in blocks of the sheet (a few mm: the fringes
// move by far less than a cycle across one), each block's mean colour turned into the phasor
// z = (R / (kR G) - 1) + i (B / (kB G) - 1): the shot's green is the mid level everywhere (1/2)
// and R, B swing about it, so without any mean taken out a fringe flatter than a cycle keeps its
// phase; kR, kB are the camera's colour balance, from the white band around the interior; G is
// smoothed (a quadratic over the sheet: the exposure's fall-off) so that its noise does not
// divide. A common black level only scales z. Then z = A exp(2 pi i (gx x + gy y + phase)):
// the gradient from the periodogram's peak, refined by Gauss-Newton on the demodulated blocks.
FringePlane fitFringes(const PhotoSampler& photo, const LenticularShot& shot, double sheetZ,
                       double x0, double x1, double y0, double y1, double searchRange) {
  FringePlane plane;
  const double pxPerMm = photo.pixelsPerMm(0, 0);
  const double area = (x1 - x0) * (y1 - y0);
  if (!(pxPerMm > 0) || !(area > 0)) return plane;
  // Two samples a photo pixel, at most about a million over the interior.
  const double step = std::max(0.5 / pxPerMm, std::sqrt(area / 1e6));
  // The colour balance from the white quiet zone between the markers and the interior.
  const PanelGrid& g = shot.panel;
  const MarkerRing& ring = shot.ring;
  const double inner = (ring.quietPx + ring.markerPx + 0.25 * ring.quietPx) * g.pitchMm;
  const double outer = (ring.quietPx + ring.markerPx + 0.75 * ring.quietPx) * g.pitchMm;
  const double hw = 0.5 * g.width * g.pitchMm, hh = 0.5 * g.height * g.pitchMm;
  double white[3] = {0, 0, 0};
  int whiteCount = 0;
  const double strips[4][4] = {{-hw + inner, hw - inner, hh - outer, hh - inner},
                               {-hw + inner, hw - inner, -hh + inner, -hh + outer},
                               {-hw + inner, -hw + outer, -hh + outer, hh - outer},
                               {hw - outer, hw - inner, -hh + outer, hh - outer}};
  for (const auto& strip : strips) {
    double rgb[3];
    int n = 0;
    if (!meanRgb(photo, strip[0], strip[1], strip[2], strip[3], sheetZ, step, rgb, &n)) continue;
    for (int ch = 0; ch < 3; ++ch) white[ch] += rgb[ch] * n;
    whiteCount += n;
  }
  if (whiteCount < 100 || !(white[1] > 0)) return plane;
  const double kR = white[0] / white[1], kB = white[2] / white[1];
  // The blocks.
  const double block = std::clamp(std::sqrt(area / 400), 0.25, 2.0);
  const int nx = std::max(2, int((x1 - x0) / block)), ny = std::max(2, int((y1 - y0) / block));
  const double bx = (x1 - x0) / nx, by = (y1 - y0) / ny;
  struct Block {
    double x, y, rgb[3];
    int i, j;
  };
  std::vector<Block> blocks;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      Block b{x0 + (i + 0.5) * bx, y0 + (j + 0.5) * by, {0, 0, 0}, i, j};
      if (meanRgb(photo, b.x - 0.5 * bx, b.x + 0.5 * bx, b.y - 0.5 * by, b.y + 0.5 * by, sheetZ,
                  step, b.rgb, &plane.samples))
        blocks.push_back(b);
    }
  if (blocks.size() < 16) return plane;
  // The green level, smoothed.
  const double sx = 2 / (x1 - x0), sy = 2 / (y1 - y0), cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  const auto basis = [&](double x, double y, double row[6]) {
    const double u = (x - cx) * sx, v = (y - cy) * sy;
    row[0] = 1, row[1] = u, row[2] = v, row[3] = u * u, row[4] = u * v, row[5] = v * v;
  };
  LeastSquares greenFit(6);
  for (const Block& b : blocks) {
    double row[6];
    basis(b.x, b.y, row);
    greenFit.add(row, b.rgb[1]);
  }
  std::vector<double> green;
  if (!greenFit.solve(green)) return plane;
  std::vector<std::complex<double>> z(blocks.size());
  for (size_t k = 0; k < blocks.size(); ++k) {
    double row[6], level = 0;
    basis(blocks[k].x, blocks[k].y, row);
    for (int i = 0; i < 6; ++i) level += green[size_t(i)] * row[i];
    if (!(level > 1e-6)) return plane;
    z[k] = {blocks[k].rgb[0] / (kR * level) - 1, blocks[k].rgb[2] / (kB * level) - 1};
  }
  // The periodogram's peak over gradients within searchRange (cycles per mm), a quarter cycle
  // over the interior apart: separable over the block grid (rows first).
  const double stepX = 0.25 / (x1 - x0), stepY = 0.25 / (y1 - y0);
  const int mx = int(std::ceil(searchRange / stepX)), my = int(std::ceil(searchRange / stepY));
  std::vector<std::complex<double>> grid(size_t(nx) * size_t(ny), 0.0);
  std::vector<std::complex<double>> rows(size_t(ny), 0.0);
  for (size_t k = 0; k < blocks.size(); ++k) grid[size_t(blocks[k].j * nx + blocks[k].i)] = z[k];
  double best = -1;
  for (int a = -mx; a <= mx; ++a) {
    const double gx = a * stepX;
    const std::complex<double> turn = std::polar(1.0, -kTwoPi * gx * bx);
    for (int j = 0; j < ny; ++j) {
      std::complex<double> sum = 0, w = std::polar(1.0, -kTwoPi * gx * (x0 + 0.5 * bx));
      for (int i = 0; i < nx; ++i, w *= turn) sum += grid[size_t(j * nx + i)] * w;
      rows[size_t(j)] = sum;
    }
    for (int c = -my; c <= my; ++c) {
      const double gy = c * stepY;
      const std::complex<double> turnY = std::polar(1.0, -kTwoPi * gy * by);
      std::complex<double> sum = 0, w = std::polar(1.0, -kTwoPi * gy * (y0 + 0.5 * by));
      for (int j = 0; j < ny; ++j, w *= turnY) sum += rows[size_t(j)] * w;
      if (std::norm(sum) > best) best = std::norm(sum), plane.gx = gx, plane.gy = gy;
    }
  }
  // Gauss-Newton: each block demodulated by the model, w = z exp(-2 pi i theta) = A + noise;
  // its imaginary part is A 2 pi (the model's phase error) to first order.
  double rms = 0;
  for (const auto& v : z) rms += std::norm(v);
  rms = std::sqrt(rms / double(z.size()));
  for (int iteration = 0; iteration < 6; ++iteration) {
    std::complex<double> sum = 0;
    for (size_t k = 0; k < blocks.size(); ++k)
      sum += z[k] * std::polar(1.0, -kTwoPi * (plane.gx * blocks[k].x + plane.gy * blocks[k].y));
    plane.phase = std::arg(sum) / kTwoPi;
    plane.amplitude = std::abs(sum) / double(blocks.size());
    LeastSquares ls(3);
    double noise = 0;
    for (size_t k = 0; k < blocks.size(); ++k) {
      const Block& b = blocks[k];
      const std::complex<double> w =
          z[k] * std::polar(1.0, -kTwoPi * (plane.gx * b.x + plane.gy * b.y + plane.phase));
      const double row[3] = {b.x, b.y, 1};
      ls.add(row, w.imag() / (kTwoPi * plane.amplitude));
      noise += std::norm(w - plane.amplitude);
    }
    std::vector<double> d, covariance;
    if (!ls.solve(d, &covariance)) return plane;
    plane.gx += d[0], plane.gy += d[1], plane.phase += d[2];
    // The noise of one component of one block, over (2 pi A)^2 per unit of phase.
    const double variance = noise / (2.0 * std::max(1.0, double(blocks.size()) - 4)) /
                            std::pow(kTwoPi * std::max(plane.amplitude, 1e-9), 2);
    plane.sigmaGx = std::sqrt(variance * covariance[0]);
    plane.sigmaGy = std::sqrt(variance * covariance[4]);
    plane.sigmaPhase = std::sqrt(variance * covariance[8]);
    plane.coherence = plane.amplitude / std::max(1e-12, rms);
  }
  // The blocks' errors are not independent: the moire of the lenses' spots against the
  // subpixels is slow, so the blocks' scatter understates what the plane is sure of. The plane
  // is also fitted to 6 x 6 super-blocks' mean phasors, and its uncertainty is the larger of the
  // two (the super-blocks' scatter with 36 - 3 degrees of freedom).
  constexpr int kSuper = 6;
  std::vector<std::complex<double>> superSum(kSuper * kSuper, 0.0);
  std::vector<double> superX(kSuper * kSuper, 0.0), superY(kSuper * kSuper, 0.0);
  std::vector<int> superCount(kSuper * kSuper, 0);
  for (size_t k = 0; k < blocks.size(); ++k) {
    const Block& b = blocks[k];
    const size_t cell = size_t(b.j * kSuper / ny * kSuper + b.i * kSuper / nx);
    superSum[cell] +=
        z[k] * std::polar(1.0, -kTwoPi * (plane.gx * b.x + plane.gy * b.y + plane.phase));
    superX[cell] += b.x, superY[cell] += b.y, ++superCount[cell];
  }
  LeastSquares superFit(3);
  std::vector<std::array<double, 3>> superRows;
  std::vector<double> superPhase;
  for (size_t c = 0; c < superSum.size(); ++c) {
    if (superCount[c] == 0 || std::abs(superSum[c]) == 0) continue;
    superRows.push_back({superX[c] / superCount[c], superY[c] / superCount[c], 1});
    superPhase.push_back(std::arg(superSum[c]) / kTwoPi);
    superFit.add(superRows.back().data(), superPhase.back());
  }
  std::vector<double> d, covariance;
  if (superRows.size() > 8 && superFit.solve(d, &covariance)) {
    double sum = 0;
    for (size_t c = 0; c < superRows.size(); ++c) {
      const double r = superPhase[c] - (d[0] * superRows[c][0] + d[1] * superRows[c][1] + d[2]);
      sum += r * r;
    }
    const double variance = sum / double(superRows.size() - 3);
    plane.sigmaGx = std::max(plane.sigmaGx, std::sqrt(variance * covariance[0]));
    plane.sigmaGy = std::max(plane.sigmaGy, std::sqrt(variance * covariance[4]));
    plane.sigmaPhase = std::max(plane.sigmaPhase, std::sqrt(variance * covariance[8]));
  }
  plane.phase -= std::floor(plane.phase);
  return plane;
}

// The interior the fringes are read over (sheet mm): the shot's, 2 mm in.
struct Interior {
  double x0, x1, y0, y1;
};
Interior interiorOf(const LenticularShot& shot) {
  const double margin = 2.0;
  return {shot.panel.xMm(shot.x0) + margin, shot.panel.xMm(shot.x1) - margin,
          shot.panel.yMm(shot.y1) + margin, shot.panel.yMm(shot.y0) - margin};
}

double searchRangeOf(const PhaseField& field) {
  // The fringes' gradient: within a few percent of the field's (the nominal within about 1 %
  // of the truth, and the gap's term g / C_z small).
  return 0.03 * std::hypot(field.gx, field.gy) + 0.01;
}

}  // namespace

LenticularFringes readLenticularFringes(const LenticularDesign& nominal, const vision::Photo& photo,
                                        const vision::CameraIntrinsics& intrinsics,
                                        const vision::CameraPose& pixelPlanePose, double gapMm) {
  const LenticularShot shot = lenticularShot(nominal);
  const Interior in = interiorOf(shot);
  const PhotoSampler sampler(photo, intrinsics, pixelPlanePose, true);
  const FringePlane plane = fitFringes(sampler, shot, gapMm, in.x0, in.x1, in.y0, in.y1,
                                       searchRangeOf(phaseFieldOf(nominal)));
  const double s = nominal.calibration.invView ? -1.0 : 1.0;
  LenticularFringes f;
  f.gradient = {s * plane.gx, s * plane.gy};
  f.gradientSigma = {plane.sigmaGx, plane.sigmaGy};
  f.phase = s * plane.phase - std::floor(s * plane.phase);
  f.phaseSigma = plane.sigmaPhase;
  f.amplitude = plane.amplitude;
  f.coherence = plane.coherence;
  f.samples = plane.samples;
  return f;
}

LenticularMeasurement measureLenticular(const LenticularDesign& nominal,
                                        const std::vector<NamedPhoto>& photos,
                                        const std::function<void(int, int)>& progress,
                                        const std::vector<std::array<double, 3>>& knownCamerasMm) {
  if (photos.empty()) throw InputError("photos", "", "no photo of shot lens given");
  const LenticularShot shot = lenticularShot(nominal);
  const PhaseField field = phaseFieldOf(nominal);
  const bool invView = nominal.calibration.invView;
  const double D = nominal.viewDistanceMm;
  const double gapGuess = sheetGapOfViewCone(nominal);
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
  const Interior in = interiorOf(shot);
  const double searchRange = searchRangeOf(field);
  for (size_t i = 0; i < photos.size(); ++i) {
    std::array<double, 3> c = cameraCentre(markers, i, photos[i].name);
    if (i < knownCamerasMm.size()) c = knownCamerasMm[i];
    c[2] -= gapGuess;
    const PhotoSampler photo(photos[i].photo, camera.intrinsics, camera.poses[i], true);
    const FringePlane plane =
        fitFringes(photo, shot, gapGuess, in.x0, in.x1, in.y0, in.y1, searchRange);
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
    if (!(plane.sigmaPhase < kMaxPhaseSigma))
      throw InputError(photos[i].name, "",
                       "the fringes are not resolved (their phase within " +
                           std::to_string(plane.sigmaPhase).substr(0, 4) +
                           " of a cycle only): too blurred, shaken, or not the lens shot's panel");
    out.photos.push_back(report);
    planes.push_back(plane);
    centres.push_back(c);
    if (progress) progress(++done, total);
  }

  // ---- the sheet: g, m (2), phi from every photo's plane --------------------------------------
  // psi_i = phi - g L_i + r0 (mod 1) with the lever L_i = G . C_i / C_z: the phases pin g far
  // better than the gradients do, but only modulo 1 / (L_i - L_j). The branch is the one that
  // best agrees with the gradients and the nominal gap together: a search over g, each g with
  // its best m (the gradients' mean) and phi (the phases' circular mean), then least squares.
  const size_t n = planes.size();
  std::vector<double> lever(n), wg(n), wp(n);
  // Each photo's fringes are off the model by more than fitFringes' sigmas say: the floors are
  // what photos through a known camera show (the photo maker, 60 dB); and the phase carries the
  // camera's direction from the markers (g |G| of a period a radian), which is known to about
  // a thousandth of a radian times the camera's distance over the panel's width
  // (calibrate study's phones_mm: a Portrait from 1.5 m, median 0.007 rad, 90 % within 0.03;
  // a 53 cm monitor from 1.8 m, 0.002 and 0.006).
  constexpr double kGradientFloor = 1.5e-4, kPhaseFloor = 0.004, kDirectionPerAspect = 1e-3;
  // And the plane's tilt, measured or not, is off by about a twentieth of a cycle over the
  // panel (a Portrait's fringes through a known camera at 60 dB: 5e-4 cycles a millimetre
  // across its 120 mm; a 53 cm monitor's, a fifth of that), more than their super-blocks show.
  constexpr double kTiltFloorCycles = 0.05;
  const double phasePerRadian = gapGuess * std::hypot(field.gx, field.gy);
  for (size_t i = 0; i < n; ++i) {
    FringePlane& p = planes[i];
    const std::array<double, 3>& c = centres[i];
    const double direction =
        knownCamerasMm.empty()
            ? kDirectionPerAspect * std::hypot(c[0], c[1], c[2]) / nominal.widthMm * phasePerRadian
            : 0.0;
    p.sigmaGx = std::hypot(p.sigmaGx, kGradientFloor, kTiltFloorCycles / nominal.widthMm);
    p.sigmaGy = std::hypot(p.sigmaGy, kGradientFloor, kTiltFloorCycles / nominal.heightMm);
    p.sigmaPhase = std::hypot(p.sigmaPhase, kPhaseFloor, direction);
    lever[i] = (field.gx * c[0] + field.gy * c[1]) / c[2];
    wg[i] = 1 / (p.sigmaGx * p.sigmaGx + p.sigmaGy * p.sigmaGy);
    wp[i] = 1 / (p.sigmaPhase * p.sigmaPhase);
  }
  const double priorSigma = 0.3 * gapGuess;
  double bestCost = 1e300, bestG = gapGuess, bestPhi = 0;
  for (double g = 0.3 * gapGuess; g <= 2.0 * gapGuess; g += 0.0005 * gapGuess) {
    double mx = 0, my = 0, wsum = 0;
    std::complex<double> mean = 0;
    for (size_t i = 0; i < n; ++i) {
      const double k = 1 + g / centres[i][2];
      mx += wg[i] * (field.gx * k - out.photos[i].fringeGradient[0]);
      my += wg[i] * (field.gy * k - out.photos[i].fringeGradient[1]);
      wsum += wg[i];
      mean += wp[i] * std::polar(1.0, kTwoPi * (out.photos[i].fringePhase + g * lever[i]));
    }
    mx /= wsum, my /= wsum;
    const double phi = std::arg(mean) / kTwoPi - field.r0;
    double cost = std::pow((g - gapGuess) / priorSigma, 2);
    for (size_t i = 0; i < n; ++i) {
      const double k = 1 + g / centres[i][2];
      cost += wg[i] * (std::pow(field.gx * k - mx - out.photos[i].fringeGradient[0], 2) +
                       std::pow(field.gy * k - my - out.photos[i].fringeGradient[1], 2));
      cost += wp[i] *
              std::pow(wrapHalf(out.photos[i].fringePhase - (phi - g * lever[i] + field.r0)), 2);
    }
    if (cost < bestCost) bestCost = cost, bestG = g, bestPhi = phi;
  }
  std::vector<double> x{bestG, field.gx * (1 + bestG / D), field.gy * (1 + bestG / D), bestPhi},
      covariance;
  for (int pass = 0; pass < 3; ++pass) {
    LeastSquares ls(4);
    for (size_t i = 0; i < n; ++i) {
      const LenticularPhotoReport& p = out.photos[i];
      const std::array<double, 3>& c = centres[i];
      const double rowX[4] = {field.gx / c[2], -1, 0, 0};
      ls.add(rowX, p.fringeGradient[0] - field.gx, 1 / std::pow(planes[i].sigmaGx, 2));
      const double rowY[4] = {field.gy / c[2], 0, -1, 0};
      ls.add(rowY, p.fringeGradient[1] - field.gy, 1 / std::pow(planes[i].sigmaGy, 2));
      const double model = x[3] - x[0] * lever[i] + field.r0;
      const double seen = model + wrapHalf(p.fringePhase - model);
      const double rowPhase[4] = {-lever[i], 0, 0, 1};
      ls.add(rowPhase, seen - field.r0, wp[i]);
    }
    if (!ls.solve(x, &covariance))
      throw InputError("photos", "", "the photos do not constrain the lens sheet");
  }
  out.gapMm = x[0];
  out.gapSigmaMm = std::sqrt(std::max(0.0, covariance[0]));
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
  // The centre needs the gap (the phases seen from off the axis carry g times the lever): photos
  // whose levers and distances are too alike leave it open.
  if (!(out.gapSigmaMm < gapGuess) || !(out.centerSigma < 0.1)) {
    std::string all;
    for (const NamedPhoto& p : photos) all += (all.empty() ? "" : ", ") + p.name;
    throw InputError(all, "",
                     "the photos leave the lens sheet's gap open (the centre only within " +
                         std::to_string(out.centerSigma).substr(0, 5) +
                         " of a lens): take two, one at least a quarter nearer than the other "
                         "and from another side");
  }
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
