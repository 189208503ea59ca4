// The accuracy study of calibration from photos (calibrate_study.h). Per trial: a true display
// drawn around the nominal one, the nominal's shots shown on it, photos by a random hand-held
// phone (pose, focal length, distortion, aperture, noise, exposure, JPEG, EXIF orientation) from
// the photo maker, which knows only the physics; the estimator reads them as it reads a user's.
#include "parallax/jobs/calibrate_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "parallax/core/error.h"
#include "parallax/core/random.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/requests.h"
#include "parallax/photocal/barrier_estimate.h"
#include "parallax/photocal/barrier_shot.h"
#include "parallax/photocal/lenticular_estimate.h"
#include "parallax/photocal/lenticular_shot.h"
#include "parallax/photomaker/photo_maker.h"

namespace parallax::jobs {

namespace {

constexpr double kPi = std::numbers::pi;

// Uniform doubles from one seeded stream.
class Draw {
 public:
  explicit Draw(uint64_t seed) : state_(mix64(seed)) {}
  double uniform(double low, double high) {
    state_ = mix64(state_ + 0x9e3779b97f4a7c15ull);
    return low + (high - low) * double(state_ >> 11) * 0x1p-53;
  }

 private:
  uint64_t state_;
};

double wrapHalf(double v) {
  return v - std::round(v);
}

// The largest focal length (pixels) that keeps the panel's corners (front, z = 0) inside the
// frame of a pinhole at `position` looking at `target`, rolled by `roll`, with a margin of 4 % of
// the frame; 0 when a corner is behind the camera.
double largestFocalInFrame(const std::array<double, 3>& position,
                           const std::array<double, 3>& target, double roll, int width, int height,
                           double halfW, double halfH) {
  double forward[3] = {target[0] - position[0], target[1] - position[1], target[2] - position[2]};
  const double length = std::hypot(forward[0], forward[1], forward[2]);
  for (double& v : forward) v /= length;
  // right = forward x up(0,1,0), down = forward x right
  double right[3] = {-forward[2], 0, forward[0]};
  const double rl = std::hypot(right[0], right[2]);
  right[0] /= rl, right[2] /= rl;
  double down[3] = {forward[1] * right[2] - forward[2] * right[1],
                    forward[2] * right[0] - forward[0] * right[2],
                    forward[0] * right[1] - forward[1] * right[0]};
  double focal = 1e300;
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0}) {
      const double p[3] = {sx * halfW - position[0], sy * halfH - position[1], -position[2]};
      const double z = p[0] * forward[0] + p[1] * forward[1] + p[2] * forward[2];
      const double xr = p[0] * right[0] + p[1] * right[1] + p[2] * right[2];
      const double yr = p[0] * down[0] + p[1] * down[1] + p[2] * down[2];
      const double x = xr * std::cos(roll) - yr * std::sin(roll);
      const double y = xr * std::sin(roll) + yr * std::cos(roll);
      if (!(z > 0)) return 0;
      if (x != 0) focal = std::min(focal, 0.46 * width * z / std::abs(x));
      if (y != 0) focal = std::min(focal, 0.46 * height * z / std::abs(y));
    }
  return focal;
}

// A set's phone (one focal length and distortion) and each photo's pose: distances from the
// panel's centre between 0.5 D and 2 D (at least 25 % apart within the set), directions up to
// maxOffAxis from the panel's normal (uniform over the solid angle), rolled up to 10 degrees,
// aimed at the panel's centre give or take 5 % of its size. The phone is held the panel's way
// (upright for a portrait panel) and zoomed (24 to 70 mm equivalent) so that the panel fills
// 75 to 100 % of what the tightest photo allows with the whole panel in the frame: a small
// panel with a large design distance (a Portrait: D = 1.37 m) is photographed as a user would,
// zoomed in, not as a speck in a wide frame.
std::vector<photomaker::PhoneCamera> randomPhones(Draw& draw, const CalibrationStudyRequest& r,
                                                  double D, double halfW, double halfH,
                                                  double whiteLevel) {
  photomaker::PhoneCamera base;
  const bool upright = halfH > halfW;
  base.width =
      upright ? std::min(r.photoWidth, r.photoHeight) : std::max(r.photoWidth, r.photoHeight);
  base.height =
      upright ? std::max(r.photoWidth, r.photoHeight) : std::min(r.photoWidth, r.photoHeight);
  base.samplesPerPixel = r.samplesPerPixel;
  base.k1 = draw.uniform(-0.1, 0.03);
  base.k2 = draw.uniform(-0.01, 0.04);
  const double pxPerEquivalentMm = std::max(r.photoWidth, r.photoHeight) / 36.0;
  const double widest = 24 * pxPerEquivalentMm, longest = 70 * pxPerEquivalentMm;
  std::vector<photomaker::PhoneCamera> phones;
  double firstDistance = 0, focalLimit = 1e300;
  for (int i = 0; i < r.photosPerSet; ++i) {
    photomaker::PhoneCamera c = base;
    for (int attempt = 0;; ++attempt) {
      double distance = draw.uniform(0.5, 2.0) * D;
      if (i > 0) {
        // At least 25 % from the first photo's distance, toward the side that has room.
        const double nearer = firstDistance / 1.25, farther = firstDistance * 1.25;
        distance = (farther <= 2 * D && (nearer < 0.5 * D || draw.uniform(0, 1) < 0.5))
                       ? draw.uniform(farther, std::max(farther, 2 * D))
                       : draw.uniform(0.5 * D, std::max(0.5 * D, nearer));
      }
      if (attempt > 40) distance = std::min(2 * D, distance * (1 + 0.05 * (attempt - 40)));
      const double cosMax = std::cos(r.maxOffAxisDegrees * kPi / 180);
      const double cosAngle = 1 - draw.uniform(0, 1) * (1 - cosMax);
      const double angle = std::acos(cosAngle), azimuth = draw.uniform(0, 2 * kPi);
      c.positionMm = {distance * std::sin(angle) * std::cos(azimuth),
                      distance * std::sin(angle) * std::sin(azimuth), distance * cosAngle};
      c.lookAtMm = {draw.uniform(-0.05, 0.05) * 2 * halfW, draw.uniform(-0.05, 0.05) * 2 * halfH,
                    0};
      c.rollDegrees = draw.uniform(-10, 10);
      const double limit = largestFocalInFrame(c.positionMm, c.lookAtMm, c.rollDegrees * kPi / 180,
                                               c.width, c.height, halfW, halfH);
      if (limit >= widest || attempt > 200) {
        focalLimit = std::min(focalLimit, limit);
        break;
      }
    }
    if (i == 0) firstDistance = std::hypot(c.positionMm[0], c.positionMm[1], c.positionMm[2]);
    const double toCentre = std::hypot(c.positionMm[0], c.positionMm[1], c.positionMm[2]);
    c.focusDistanceMm = toCentre * draw.uniform(0.93, 1.07);
    c.apertureMm = r.blurMm >= 0 ? r.blurMm : draw.uniform(1.5, 3.0);
    // A phone's lens, diffraction and demosaicing blur about a sensor pixel.
    c.blurSigmaPx = r.blurMm >= 0 ? 0.0 : draw.uniform(0.6, 1.2);
    // White on the panel, as the camera sees it, at 55 to 90 % of the sensor's range; the SNR is
    // the pattern's amplitude (half its swing from black to white) over the noise.
    c.exposure = draw.uniform(0.55, 0.9) / whiteLevel;
    c.noiseSigma = 0.5 * whiteLevel * c.exposure * std::pow(10.0, -r.snrDb / 20);
    c.seed = uint64_t(draw.uniform(0, 1) * 9e15);
    phones.push_back(c);
  }
  const double focal = std::clamp(focalLimit * draw.uniform(0.75, 1.0), widest, longest);
  for (size_t i = 0; i < phones.size(); ++i) {
    photomaker::PhoneCamera& c = phones[i];
    c.focalPx = focal;
  }
  return phones;
}

// The photo as a phone stores it (JPEG, quality 75 to 95, turned with its EXIF orientation),
// read back as calibrate photo reads a file.
photocal::NamedPhoto storedPhoto(Draw& draw, const photomaker::PhotoPixels& pixels,
                                 const std::string& name, const std::string& keepIn) {
  static constexpr int kOrientations[] = {1, 3, 6, 8};
  const vision::Photo photo{pixels.width, pixels.height, pixels.rgb};
  const int quality = int(draw.uniform(75, 95.99));
  const int orientation = kOrientations[int(draw.uniform(0, 3.999))];
  const std::vector<uint8_t> jpeg = vision::encodeJpeg(photo, quality, orientation);
  if (!keepIn.empty())
    writeFileAtomically((std::filesystem::path(keepIn) / (name + ".jpg")).string(),
                        std::string_view(reinterpret_cast<const char*>(jpeg.data()), jpeg.size()));
  photocal::NamedPhoto stored{name, vision::decodePhoto(jpeg, name, 1u << 30)};
  if (!keepIn.empty()) {
    // The upright photo as a PNG too, for a look (a browser turns the JPEG by its EXIF tag).
    Image look(stored.photo.width, stored.photo.height);
    for (int y = 0; y < look.height(); ++y)
      for (int x = 0; x < look.width(); ++x) {
        const uint8_t* p = &stored.photo.rgb[3 * (size_t(y) * size_t(look.width()) + size_t(x))];
        look.at(x, y) = Vec3f(srgb8ToLinear(p[0]), srgb8ToLinear(p[1]), srgb8ToLinear(p[2]));
      }
    writeImage((std::filesystem::path(keepIn) / (name + ".png")).string(), look);
  }
  return stored;
}

photomaker::LcdPanel lcd(const Panel& panel) {
  photomaker::LcdPanel p;
  p.width = panel.width;
  p.height = panel.height;
  p.pitchMm = panel.pitchMm;
  p.bgr = panel.subpixels == SubpixelOrder::BGR;
  return p;
}

CalibrationTrial barrierTrial(Draw& draw, const CalibrationStudyRequest& r,
                              const DisplayDesign& nominal, const photocal::BarrierShot& shot,
                              const photocal::BarrierShotPictures& pictures, int index) {
  const DisplaySpec& spec = nominal.spec;
  const bool back = spec.order == LayerOrder::BarrierBack;
  photomaker::PhysicalBarrier truth;
  truth.front = lcd(back ? spec.imagePanel : spec.maskPanel);
  truth.rear = lcd(back ? spec.maskPanel : spec.imagePanel);
  truth.gapMm = spec.gapMm * draw.uniform(0.8, 1.2);
  // The mask panel sits o pixels to the left of where the design puts it (the display file's
  // panel_offset_px = o), turned a little, a pixel or two off vertically.
  const double offsetPx = draw.uniform(-40, 40), rotation = draw.uniform(-0.05, 0.05);
  const double maskShiftMm = -offsetPx * spec.maskPanel.pitchMm;
  truth.rear.offsetXMm = back ? maskShiftMm : -maskShiftMm;
  truth.rear.offsetYMm = draw.uniform(-3, 3) * truth.rear.pitchMm;
  truth.rear.rotationDegrees = back ? rotation : -rotation;
  const double halfW = 0.5 * truth.front.width * truth.front.pitchMm;
  const double halfH = 0.5 * truth.front.height * truth.front.pitchMm;
  // White through both panels: each colour passes where a front stripe's aperture lies over
  // the same colour's on the rear; over the moire of the two grids, fill^2 / 3 of the light.
  const double white = truth.front.fillFactor * truth.rear.fillFactor / 3;
  const auto phones = randomPhones(draw, r, nominal.viewDistanceMm, halfW, halfH, white);
  std::vector<photocal::NamedPhoto> photos;
  for (size_t i = 0; i < phones.size(); ++i)
    photos.push_back(storedPhoto(
        draw, photomaker::photographBarrier(truth, pictures.front, pictures.rear, phones[i]),
        "grid-" + std::to_string(index) + "-" + std::to_string(i + 1), r.photos));
  CalibrationTrial trial;
  for (const photomaker::PhoneCamera& phone : phones) trial.truePhones.push_back(phone.positionMm);
  const auto start = std::chrono::steady_clock::now();
  try {
    const photocal::BarrierMeasurement m = photocal::measureBarrier(spec, photos);
    DisplaySpec measured = spec, true_ = spec;
    measured.gapMm = m.gapMm;
    true_.gapMm = truth.gapMm;
    trial.errors = {(m.gapMm - truth.gapMm) / truth.gapMm, m.maskPanelOffsetPx - offsetPx,
                    m.maskRotationDegrees - rotation,
                    designDisplay(measured).slitPeriodPx - designDisplay(true_).slitPeriodPx};
    trial.sigmas = {m.gapSigmaMm / truth.gapMm, m.maskPanelOffsetSigmaPx, m.rotationSigmaDegrees,
                    0};
    trial.truths = {truth.gapMm, offsetPx, rotation};
    trial.trueGapMm = truth.gapMm;
    trial.measuredGapMm = m.gapMm;
    for (const photocal::BarrierPhotoReport& p : m.photos)
      trial.measuredPhones.push_back(p.cameraMm);
    trial.estimates = {m.gapMm, m.maskPanelOffsetPx, m.maskRotationDegrees};
  } catch (const InputError& e) {
    trial.refused = true;
    trial.refusal = e.what();
  }
  (void)shot;
  trial.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return trial;
}

CalibrationTrial lenticularTrial(Draw& draw, const CalibrationStudyRequest& r,
                                 const LenticularDesign& nominal, const Image& picture, int index) {
  const LenticularCalibration& c = nominal.calibration;
  const double D = nominal.viewDistanceMm;
  const photocal::PhaseField f0 = photocal::phaseFieldOf(nominal);
  const double s = c.invView ? 1.0 : -1.0;
  // The nominal sheet as the field says, then the truth around it: the apparent pitch and the
  // slope within 1 %, the phase anywhere, the gap that the view cone implies.
  const double pitchAtD = 1 / std::hypot(f0.gx, f0.gy) * draw.uniform(0.99, 1.01);
  const double nominalSlant = std::atan2(-s * f0.gy, s * f0.gx);
  const double slant = std::atan(std::tan(nominalSlant) * draw.uniform(0.99, 1.01));
  const double cone = c.viewConeDegrees * kPi / 180;
  photocal::LensSheet sheet;
  sheet.slantDegrees = slant * 180 / kPi;
  sheet.gapMm = 1.0;
  for (int i = 0; i < 8; ++i) {
    sheet.pitchMm = pitchAtD * D / (D + sheet.gapMm);
    sheet.gapMm =
        sheet.pitchMm * D / (2 * D * std::tan(cone / 2) * std::cos(slant) - sheet.pitchMm);
  }
  sheet.phaseMm = draw.uniform(0, sheet.pitchMm);
  const LenticularCalibration truthCalibration =
      photocal::calibrationWithField(c, photocal::fieldOfSheet(sheet, c.invView, D), D);
  photomaker::PhysicalLenticular truth;
  truth.panel.width = c.screenW;
  truth.panel.height = c.screenH;
  truth.panel.pitchMm = nominal.pixelPitchMm;
  truth.panel.bgr = c.flipSubpixels;
  truth.pitchMm = sheet.pitchMm;
  truth.slantDegrees = sheet.slantDegrees;
  truth.phaseMm = sheet.phaseMm;
  truth.focalGapMm = sheet.gapMm;
  truth.spotSigmaMm = 0.1 * sheet.pitchMm;
  // A lit subpixel's aperture is fill of its stripe and of the pixel's height: fill^2 / 3 of
  // the panel's area gives each colour.
  const double white = truth.panel.fillFactor * truth.panel.fillFactor / 3;
  const auto phones =
      randomPhones(draw, r, D, 0.5 * nominal.widthMm, 0.5 * nominal.heightMm, white);
  std::vector<photocal::NamedPhoto> photos;
  for (size_t i = 0; i < phones.size(); ++i)
    photos.push_back(storedPhoto(draw, photomaker::photographLenticular(truth, picture, phones[i]),
                                 "lens-" + std::to_string(index) + "-" + std::to_string(i + 1),
                                 r.photos));
  CalibrationTrial trial;
  for (const photomaker::PhoneCamera& phone : phones) trial.truePhones.push_back(phone.positionMm);
  const auto start = std::chrono::steady_clock::now();
  try {
    // The phones stand over the lens sheet; the estimator's cameras over the pixels behind it.
    std::vector<std::array<double, 3>> known;
    if (r.trueCamera)
      for (const photomaker::PhoneCamera& phone : phones)
        known.push_back(
            {phone.positionMm[0], phone.positionMm[1], phone.positionMm[2] + sheet.gapMm});
    const photocal::LenticularMeasurement m =
        photocal::measureLenticular(nominal, photos, {}, known);
    const auto slantOf = [](double slope) { return std::atan(1 / slope) * 180 / kPi; };
    trial.errors = {(m.measured.pitch - truthCalibration.pitch) / truthCalibration.pitch,
                    slantOf(m.measured.slope) - slantOf(truthCalibration.slope),
                    wrapHalf(m.measured.center - truthCalibration.center)};
    const double dSlant =
        std::abs(slantOf(m.measured.slope + m.slopeSigma) - slantOf(m.measured.slope));
    // The raw phase's error where the viewer sees it: at the panel's centre, and the worst of
    // the four corners (center itself is the phase at the shader's origin, a corner).
    const photocal::PhaseField fm = photocal::phaseFieldOf(designLenticular(m.measured, D));
    const photocal::PhaseField ft = photocal::phaseFieldOf(designLenticular(truthCalibration, D));
    double cornerError = 0;
    for (int corner = 0; corner < 4; ++corner) {
      const double x = (corner % 2 ? 0.5 : -0.5) * nominal.widthMm;
      const double y = (corner / 2 ? 0.5 : -0.5) * nominal.heightMm;
      cornerError =
          std::max(cornerError,
                   std::abs(wrapHalf((fm.gx - ft.gx) * x + (fm.gy - ft.gy) * y + fm.r0 - ft.r0)));
    }
    trial.errors.push_back(wrapHalf(fm.r0 - ft.r0));
    trial.errors.push_back(cornerError);
    trial.sigmas = {m.pitchSigma / truthCalibration.pitch, dSlant, m.centerSigma, 0, 0};
    trial.truths = {truthCalibration.pitch, slantOf(truthCalibration.slope),
                    truthCalibration.center};
    trial.estimates = {m.measured.pitch, slantOf(m.measured.slope), m.measured.center};
    trial.trueGapMm = sheet.gapMm;
    trial.measuredGapMm = m.gapMm;
    for (const photocal::LenticularPhotoReport& p : m.photos)
      trial.measuredPhones.push_back(p.cameraMm);
  } catch (const InputError& e) {
    trial.refused = true;
    trial.refusal = e.what();
  }
  trial.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return trial;
}

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return NAN;
  std::sort(values.begin(), values.end());
  const double at = q * double(values.size() - 1);
  const size_t i = size_t(at);
  return i + 1 < values.size() ? values[i] + (at - double(i)) * (values[i + 1] - values[i])
                               : values.back();
}

}  // namespace

CalibrationStudy calibrationStudy(const CalibrationStudyRequest& r, Reporter& reporter) {
  if (r.sets < 1 || r.sets > 100000) throw RequestError("sets", "must be 1 to 100000");
  if (r.photosPerSet < 1 || r.photosPerSet > 6)
    throw RequestError("photos_per_set", "must be 1 to 6");
  if (r.photoWidth < 320 || r.photoHeight < 240 || r.photoWidth > 12000 || r.photoHeight > 12000)
    throw RequestError("photo_size", "must be 320x240 to 12000x12000");
  if (r.samplesPerPixel < 1 || r.samplesPerPixel > 256)
    throw RequestError("samples", "must be 1 to 256");
  if (!(r.snrDb > -20 && r.snrDb < 120)) throw RequestError("snr", "must be -20 to 120 dB");
  if (!(r.maxOffAxisDegrees >= 0 && r.maxOffAxisDegrees <= 60))
    throw RequestError("max_off_axis", "must be 0 to 60 degrees");
  const DisplayDescription display = r.display.describe(reporter);
  if (!r.photos.empty()) std::filesystem::create_directories(r.photos);
  CalibrationStudy study;
  Draw draw(r.seed);
  const auto progress = reporter.progress("trials");
  if (display.kind == DisplayKind::Barrier) {
    study.kind = "barrier";
    study.quantities = {"gap (relative)", "mask offset (mask px)", "rotation (degrees)",
                        "slit period at D (mask px)"};
    const DisplayDesign nominal = barrierDesignOf(display);
    const photocal::BarrierShot shot = photocal::barrierShot(nominal.spec);
    const photocal::BarrierShotPictures pictures = photocal::drawBarrierShot(shot);
    for (int i = 0; i < r.sets; ++i) {
      study.trials.push_back(barrierTrial(draw, r, nominal, shot, pictures, i + 1));
      progress->update(i + 1, r.sets);
    }
  } else {
    study.kind = "lenticular";
    study.quantities = {"pitch (relative)", "slant (degrees)", "center (lens periods)",
                        "phase at the panel's centre (periods)", "phase, worst corner (periods)"};
    const LenticularDesign nominal = designLenticular(display.lenticular);
    const Image picture = photocal::drawLenticularShot(photocal::lenticularShot(nominal), nominal);
    for (int i = 0; i < r.sets; ++i) {
      study.trials.push_back(lenticularTrial(draw, r, nominal, picture, i + 1));
      progress->update(i + 1, r.sets);
    }
  }
  return study;
}

void runCalibrationStudy(const CalibrationStudyRequest& r, Reporter& reporter) {
  const CalibrationStudy study = calibrationStudy(r, reporter);
  int refused = 0;
  double seconds = 0;
  for (const CalibrationTrial& t : study.trials) {
    refused += t.refused;
    seconds += t.seconds;
  }
  JsonWriter json;
  json.set("/kind", study.kind);
  json.set("/sets", int(study.trials.size()));
  json.set("/refused", refused);
  json.set("/snr_db", r.snrDb);
  json.set("/mean_estimate_seconds", seconds / double(study.trials.size()));
  std::vector<std::string> lines = {
      printed("%s: %zu photo sets of %d photos, %.0f dB SNR, %dx%d photos; %d refused; "
              "estimate %.2f s a set",
              study.kind.c_str(), study.trials.size(), r.photosPerSet, r.snrDb, r.photoWidth,
              r.photoHeight, refused, seconds / double(study.trials.size())),
      "quantity                      median |error|   95th percentile   within 2 sigma"};
  for (size_t q = 0; q < study.quantities.size(); ++q) {
    std::vector<double> errors;
    int within = 0, counted = 0;
    for (const CalibrationTrial& t : study.trials) {
      if (t.refused) continue;
      errors.push_back(std::abs(t.errors[q]));
      if (t.sigmas[q] > 0) {
        ++counted;
        within += std::abs(t.errors[q]) <= 2 * t.sigmas[q];
      }
    }
    const double median = percentile(errors, 0.5), p95 = percentile(errors, 0.95);
    const std::string at = "/quantities/" + std::to_string(q);
    json.set(at + "/name", study.quantities[q]);
    json.set(at + "/median", median);
    json.set(at + "/p95", p95);
    json.set(at + "/within_two_sigma", counted ? double(within) / counted : -1.0);
    lines.push_back(printed("%-29s %14.3g   %15.3g   %s", study.quantities[q].c_str(), median, p95,
                            counted ? printed("%.0f %%", 100.0 * within / counted).c_str() : "-"));
  }
  for (size_t i = 0; i < study.trials.size(); ++i) {
    const CalibrationTrial& t = study.trials[i];
    const std::string at = "/trials/" + std::to_string(i);
    json.set(at + "/refused", t.refused);
    for (size_t q = 0; q < t.errors.size(); ++q)
      json.set(at + "/errors/" + std::to_string(q), t.errors[q]);
    for (size_t q = 0; q < t.sigmas.size(); ++q)
      json.set(at + "/sigmas/" + std::to_string(q), t.sigmas[q]);
    for (size_t q = 0; q < t.truths.size(); ++q)
      json.set(at + "/truths/" + std::to_string(q), t.truths[q]);
    for (size_t q = 0; q < t.estimates.size(); ++q)
      json.set(at + "/estimates/" + std::to_string(q), t.estimates[q]);
    if (t.trueGapMm > 0) json.set(at + "/gap_mm/truth", t.trueGapMm);
    if (t.measuredGapMm > 0) json.set(at + "/gap_mm/estimate", t.measuredGapMm);
    const auto setPhones = [&](const std::string& key,
                               const std::vector<std::array<double, 3>>& phones) {
      for (size_t p = 0; p < phones.size(); ++p)
        for (size_t k = 0; k < 3; ++k)
          json.set(at + "/" + key + "/" + std::to_string(p) + "/" + std::to_string(k),
                   phones[p][k]);
    };
    setPhones("phones_mm/truth", t.truePhones);
    setPhones("phones_mm/estimate", t.measuredPhones);
  }
  int refusal = 0;
  for (size_t i = 0; i < study.trials.size(); ++i)
    if (study.trials[i].refused) {
      json.set("/refusals/" + std::to_string(refusal) + "/set", int(i + 1));
      json.set("/refusals/" + std::to_string(refusal++) + "/why", study.trials[i].refusal);
      lines.push_back("refused, set " + std::to_string(i + 1) + ": " + study.trials[i].refusal);
    }
  if (r.json) {
    reporter.result(json.dump());
    return;
  }
  for (const std::string& line : lines) reporter.result(line);
}

}  // namespace parallax::jobs
