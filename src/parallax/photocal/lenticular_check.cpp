// The seat check (lenticular_check.h): one camera from every photo's markers (a pose each), the
// shot's phasor plane read per photo as the estimator reads its fringes, and the plane's phase,
// gradient and amplitude turned into the views seen.
#include "parallax/photocal/lenticular_check.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "parallax/core/error.h"
#include "parallax/photocal/lenticular_estimate.h"
#include "parallax/photocal/lenticular_model.h"
#include "parallax/photocal/lenticular_shot.h"

namespace parallax::photocal {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMaxPhaseSigma = 0.05;  // cycles: as the estimator refuses a photo

double sinc(double u) {
  return std::abs(u) < 1e-12 ? 1.0 : std::sin(kPi * u) / (kPi * u);
}

// The share of the renderer's seen-view distribution (a box of width delta convolved with a
// box of width W delta: a trapezoid) beyond +-halfView of its centre.
double shareBeyond(double delta, double spotWidth, double halfView) {
  const int steps = 4000;
  const double reach = 0.5 * (delta + spotWidth);
  if (halfView >= reach) return 0.0;
  double inside = 0, total = 0;
  for (int i = 0; i < steps; ++i) {
    const double x = -reach + (i + 0.5) * 2 * reach / steps;
    // The overlap of [x - delta/2, x + delta/2] with [-W delta/2, W delta/2], or the box itself
    // for an ideal lens.
    const double density = spotWidth > 0
                               ? std::max(0.0, std::min(x + 0.5 * delta, 0.5 * spotWidth) -
                                                   std::max(x - 0.5 * delta, -0.5 * spotWidth))
                               : (std::abs(x) < 0.5 * delta ? 1.0 : 0.0);
    total += density;
    if (std::abs(x) <= halfView) inside += density;
  }
  return total > 0 ? 1 - inside / total : 0.0;
}

}  // namespace

double seenAmplitudeOfSpot(const LenticularDesign& d, double spotSubpixels) {
  const double delta = subpixelViewWidth(d);
  return std::abs(sinc(delta) * sinc(spotSubpixels * delta));
}

double spotOfSeenAmplitude(const LenticularDesign& d, double amplitude) {
  // sinc(W delta) falls from 1 at W = 0 to 0 at W delta = 1: bisection on that branch.
  const double delta = subpixelViewWidth(d);
  const double target = amplitude / sinc(delta);
  if (!(target < 1)) return 0.0;
  double low = 0, high = std::min(kMaxLensSpotSubpixels, 1 / delta);
  if (sinc(high * delta) >= target) return high;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (low + high);
    (sinc(mid * delta) > target ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

double otherViewsShare(const LenticularDesign& d, double spotSubpixels) {
  return shareBeyond(subpixelViewWidth(d), spotSubpixels * subpixelViewWidth(d),
                     0.5 / std::max(1, d.quiltViews));
}

std::vector<SeatCheck> checkLenticularSeats(const LenticularDesign& shown,
                                            const std::vector<NamedPhoto>& photos,
                                            const std::function<void(int, int)>& progress) {
  if (photos.empty()) throw InputError("photos", "", "no photo of shot lens given");
  const LenticularShot shot = lenticularShot(shown);
  const double gap = sheetGapOfViewCone(shown);
  // The raw phase the fringes report is -f with invView, +f without.
  const double s = shown.calibration.invView ? -1.0 : 1.0;
  const double halfW = 0.5 * shown.widthMm, halfH = 0.5 * shown.heightMm;
  const PhaseField field = phaseFieldOf(shown);
  std::vector<SeatCheck> seats;
  // One phone at one zoom for every seat, as calibrate photo assumes: seats at different angles
  // pin its focal length, and with it each camera's distance, better than one photo alone.
  const MarkerCamera markers = markerCamera(shot.ring, shot.panel, "lens", photos, 6);
  for (size_t i = 0; i < photos.size(); ++i) {
    const std::array<double, 3> c = cameraCentre(markers, i, photos[i].name);
    const LenticularFringes fringes = readLenticularFringes(
        shown, photos[i].photo, markers.fit.intrinsics, markers.fit.poses[i], gap);
    if (!(fringes.phaseSigma < kMaxPhaseSigma))
      throw InputError(photos[i].name, "",
                       "the shot's colours are not resolved (the view within " +
                           std::to_string(fringes.phaseSigma).substr(0, 4) +
                           " of a period only): too blurred, shaken, or not the lens shot's panel");
    SeatCheck seat;
    seat.name = photos[i].name;
    seat.cameraMm = c;
    seat.offAxisDegrees = std::atan2(std::hypot(c[0], c[1]), c[2]) * 180 / kPi;
    seat.markers = markers.markersFound[i];
    seat.distanceSigmaMm = markers.focalRelativeSigma * std::hypot(c[0], c[1], c[2]);
    seat.viewSeen = s * fringes.phase - std::floor(s * fringes.phase);
    seat.viewSeenSigma = fringes.phaseSigma;
    const double gx = s * fringes.gradient[0], gy = s * fringes.gradient[1];
    seat.edgesSeen = {seat.viewSeen - gx * halfW, seat.viewSeen + gx * halfW};
    seat.topBottomSeen = {seat.viewSeen + gy * halfH, seat.viewSeen - gy * halfH};
    // What a calibration that is right shows there (the fringe model with the sheet as the file
    // describes it: G the file's field, the gap its view cone's, the camera over the sheet):
    // raw phase 1/2 - (g / C_z) G . C at the centre, gradient G g (1 / C_z - 1 / D).
    const double cz = c[2] - gap;
    const double aimedRaw = 0.5 - gap / cz * (field.gx * c[0] + field.gy * c[1]);
    seat.viewAimed = s * aimedRaw - std::floor(s * aimedRaw);
    const double fan = s * field.gx * gap * (1 / cz - 1 / shown.viewDistanceMm) * halfW;
    seat.edgesAimed = {seat.viewAimed - fan, seat.viewAimed + fan};
    seat.amplitude = fringes.amplitude;
    seat.coherence = fringes.coherence;
    seat.spotSubpixels = spotOfSeenAmplitude(shown, fringes.amplitude);
    seat.otherViews = otherViewsShare(shown, seat.spotSubpixels);
    seats.push_back(seat);
    if (progress) progress(int(i + 1), int(photos.size()));
  }
  return seats;
}

}  // namespace parallax::photocal
