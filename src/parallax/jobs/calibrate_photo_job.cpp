// Calibration from photos: the shot set written and read back (index.json), the photos matched
// to their shots by name, read with their memory estimated from their headers, and measured by
// photocal's estimator of the display's kind.
#include "parallax/jobs/calibrate_photo_job.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "parallax/core/error.h"
#include "parallax/core/output_path.h"
#include "parallax/io/image_file.h"
#include "parallax/io/input_file.h"
#include "parallax/io/json_reader.h"
#include "parallax/io/json_writer.h"
#include "parallax/io/lenticular_file.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/layer_output.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/requests.h"
#include "parallax/photocal/barrier_shot.h"
#include "parallax/photocal/lenticular_shot.h"

namespace parallax::jobs {

namespace fs = std::filesystem;

namespace {

constexpr const char* kIndex = "index.json";
constexpr int kShotsVersion = 1;  // the shots' layout; the estimator reads only its own
// A photo's pixels: a phone's largest are 200 megapixels.
constexpr uint64_t kMaxPhotoPixels = 250'000'000;
constexpr uintmax_t kMaxPhotoFileBytes = 512u << 20;

const char* kindName(const DisplayDescription& d) {
  return d.kind == DisplayKind::Barrier ? "barrier" : "lenticular";
}

}  // namespace

// ---- the shots -------------------------------------------------------------------------------

CalibrationShotSet calibrationShots(const CalibrationShotsRequest& r, Reporter& reporter) {
  CalibrationShotSet set;
  set.display = r.display.describe(reporter);
  set.kind = kindName(set.display);
  JsonWriter index;
  index.set("/kind", set.kind);
  index.set("/version", kShotsVersion);
  set.displayFile = set.display.kind == DisplayKind::Barrier ? "display.json" : "visual.json";
  index.set("/display", set.displayFile);
  std::string take;
  if (set.display.kind == DisplayKind::Lenticular) {
    const LenticularDesign design = designLenticular(set.display.lenticular);
    const LenticularCalibration& c = design.calibration;
    checkMemoryEstimate(double(c.screenW) * c.screenH * (kFloatRgbPixelBytes + kRgba8PixelBytes),
                        c.source, "the shot's picture", "use a smaller panel");
    const photocal::LenticularShot shot = photocal::lenticularShot(design);
    set.pictures.push_back(
        {"lens", "panel", "lens-panel.png", photocal::drawLenticularShot(shot, design)});
    set.displayText = lenticularCalibrationText(c);
    index.set("/shots/0/name", "lens");
    index.set("/shots/0/panel", "lens-panel.png");
    take =
        "Show lens-panel.png full screen on the panel (`parallax show SHOTS`, SHOTS this "
        "folder), take two photos\nof the whole panel with a phone, one at least a quarter "
        "nearer than the other (lens-near.jpg,\nlens-far.jpg), then\n  parallax calibrate photo "
        "--shots SHOTS lens-near.jpg lens-far.jpg -o measured-visual.json\n";
  } else {
    const DisplayDesign design = barrierDesignOf(set.display);
    const DisplaySpec& spec = design.spec;
    const double pixels = double(spec.imagePanel.width) * spec.imagePanel.height +
                          double(spec.maskPanel.width) * spec.maskPanel.height;
    checkMemoryEstimate(pixels * (kFloatRgbPixelBytes + kRgba8PixelBytes), spec.source,
                        "the shot's two pictures", "use a smaller display");
    const photocal::BarrierShot shot = photocal::barrierShot(spec);
    photocal::BarrierShotPictures pictures = photocal::drawBarrierShot(shot);
    const std::string frontLayer = shot.frontIsImage ? "image" : "mask";
    const std::string rearLayer = shot.frontIsImage ? "mask" : "image";
    set.pictures.push_back(
        {"grid", frontLayer, "grid-" + frontLayer + ".png", std::move(pictures.front)});
    set.pictures.push_back(
        {"grid", rearLayer, "grid-" + rearLayer + ".png", std::move(pictures.rear)});
    set.displayText = displayFileText(spec, set.display.camera);
    index.set("/shots/0/name", "grid");
    index.set("/shots/0/image", "grid-image.png");
    index.set("/shots/0/mask", "grid-mask.png");
    take =
        "Show them 1:1 with `parallax show SHOTS`, SHOTS this folder (grid-image.png on the "
        "image layer,\ngrid-mask.png on the mask layer), take two photos of the whole panel "
        "with a phone, from 10\nto 30 degrees to either side (grid-1.jpg, grid-2.jpg), then\n"
        "  parallax calibrate photo --shots SHOTS grid-1.jpg grid-2.jpg -o measured.json\n";
  }
  set.index = index.dump() + "\n";
  set.readme = "Calibration shots (parallax calibrate patterns --photo) for " +
               set.display.source() + " (" + set.kind + ").\n" + take +
               "docs/calibration.md, \"From photos\", says why and how.\n";
  return set;
}

void runCalibrationShots(const CalibrationShotsRequest& r, Reporter& reporter) {
  const CalibrationShotSet set = calibrationShots(r, reporter);
  std::vector<std::string> names;
  for (const ShotPicture& p : set.pictures) names.push_back(p.file);
  names.insert(names.end(), {kIndex, "README.txt", set.displayFile});
  OutputSet::check(r.output, names);
  OutputSet out(r.output);
  for (const ShotPicture& p : set.pictures) writeImage(out.path(p.file), p.picture);
  writeFileAtomically(out.path(kIndex), set.index);
  writeFileAtomically(out.path("README.txt"), set.readme);
  writeFileAtomically(out.path(set.displayFile), set.displayText);
  out.commit();
  reporter.result(printed("wrote %zu shot pictures (%s), index.json, README.txt and %s to %s",
                          set.pictures.size(), set.kind.c_str(), set.displayFile.c_str(),
                          out.dir().c_str()));
}

// ---- the photos ------------------------------------------------------------------------------

namespace {

struct ShotsFolder {
  std::string kind;
  std::vector<std::string> shotNames;
  std::string displayPath;
};

ShotsFolder readShotsFolder(const std::string& dir) {
  if (dir.empty())
    throw RequestError("shots", "needs the folder `calibrate patterns --photo` wrote");
  if (!fs::is_directory(dir))
    throw InputError(dir, "", "not a folder: give the folder `calibrate patterns --photo` wrote");
  const std::string indexPath = (fs::path(dir) / kIndex).string();
  const JsonDocument doc = JsonDocument::parseFile(indexPath);
  const JsonReader root = doc.root();
  root.expectObject({"kind", "version", "display", "shots"});
  ShotsFolder folder;
  folder.kind = root["kind"].string();
  if (folder.kind != "barrier" && folder.kind != "lenticular")
    throw InputError(indexPath, "/kind", "expected \"barrier\" or \"lenticular\"");
  if (root["version"].integer(0, 1000) != kShotsVersion)
    throw InputError(indexPath, "/version",
                     "made by another version of parallax: make the shots again");
  folder.displayPath = (fs::path(dir) / root["display"].string()).string();
  for (const JsonReader& shot : root["shots"].elements()) {
    if (folder.kind == "barrier")
      shot.expectObject({"name", "image", "mask"});
    else
      shot.expectObject({"name", "panel"});
    folder.shotNames.push_back(shot["name"].string());
  }
  if (folder.shotNames.empty()) throw InputError(indexPath, "/shots", "holds no shot");
  return folder;
}

// The shot a photo shows, by its file name: the shot's name, then '-' or '.'.
std::string shotOfPhoto(const std::string& photo, const ShotsFolder& folder,
                        const std::string& dir) {
  const std::string name = fs::path(photo).filename().string();
  for (const std::string& shot : folder.shotNames)
    if (name.size() > shot.size() && name.compare(0, shot.size(), shot) == 0 &&
        (name[shot.size()] == '-' || name[shot.size()] == '.'))
      return shot;
  std::string shots;
  for (const std::string& s : folder.shotNames) shots += (shots.empty() ? "" : ", ") + s;
  throw InputError(photo, "",
                   "matches no shot of " + dir + " (" + shots +
                       "): a photo's name starts with its shot's name and '-' or '.'");
}

std::string formatted(double value, int decimals) {
  return printed("%.*f", decimals, value);
}

// Where a photo was taken, under `at`.
void recordPhotoPlace(JsonWriter& json, const std::string& at, const std::string& file,
                      const std::array<double, 3>& cameraMm, double offAxisDegrees, int markers) {
  json.set(at + "/file", file);
  json.set(at + "/camera_mm", Vec3f{float(cameraMm[0]), float(cameraMm[1]), float(cameraMm[2])});
  json.set(at + "/off_axis_degrees", offAxisDegrees);
  json.set(at + "/markers", markers);
}

// What either kind's measurement says of the camera and of each photo, under /camera and
// /photos.
template <class Measurement>
void recordCameraAndPhotos(JsonWriter& json, const Measurement& m) {
  json.set("/camera/focal_px/value", m.focalPx);
  json.set("/camera/focal_px/sigma", m.focalSigmaPx);
  json.set("/camera/k1", m.k1);
  json.set("/camera/k2", m.k2);
  for (size_t i = 0; i < m.photos.size(); ++i) {
    const auto& p = m.photos[i];
    const std::string at = "/photos/" + std::to_string(i);
    recordPhotoPlace(json, at, p.name, p.cameraMm, p.offAxisDegrees, p.markers);
    json.set(at + "/marker_rms_px", p.markerRmsPx);
  }
}

// The barrier's measurement, its display file and its report.
void barrierReport(const DisplayDescription& nominal,
                   const std::vector<photocal::NamedPhoto>& photos, Reporter& reporter,
                   const std::string& output, PhotoCalibration& result) {
  const DisplayDesign design = barrierDesignOf(nominal);
  photocal::BarrierMeasurement m;
  {
    const auto progress = reporter.progress("measuring");
    m = photocal::measureBarrier(design.spec, photos, progress->callback());
  }
  result.barrier = m;
  DisplaySpec measured = design.spec;
  measured.gapMm = m.gapMm;
  measured.mask.panelOffsetPx = m.maskPanelOffsetPx;
  result.measured.barrier = measured;
  result.measuredText = displayFileText(measured, nominal.camera);
  const DisplayDesign after = designDisplay(measured, nominal.camera);

  JsonWriter json;
  json.set("/kind", result.kind);
  json.set("/display", nominal.source());
  json.set("/gap_mm/value", m.gapMm);
  json.set("/gap_mm/sigma", m.gapSigmaMm);
  json.set("/gap_mm/nominal", design.spec.gapMm);
  json.set("/mask/panel_offset_px/value", m.maskPanelOffsetPx);
  json.set("/mask/panel_offset_px/sigma", m.maskPanelOffsetSigmaPx);
  json.set("/mask/rotation_degrees/value", m.maskRotationDegrees);
  json.set("/mask/rotation_degrees/sigma", m.rotationSigmaDegrees);
  json.set("/mask/rotation_edge_error_px", m.rotationEdgeErrorPx);
  json.set("/slit_period_px", after.slitPeriodPx);
  json.set("/residual_px", m.residualPx);
  recordCameraAndPhotos(json, m);
  for (size_t i = 0; i < m.photos.size(); ++i) {
    const std::string at = "/photos/" + std::to_string(i);
    json.set(at + "/blocks", m.photos[i].rearBlocks);
    json.set(at + "/contrast", m.photos[i].contrast);
  }
  if (!output.empty()) json.set("/output", output);
  result.json = json.dump();

  const double quarter = 0.25;
  result.lines = {
      "display          " + nominal.source() + " (barrier, " + std::to_string(photos.size()) +
          " photos)",
      "gap              " + formatted(m.gapMm, 3) + " ± " + formatted(m.gapSigmaMm, 3) +
          " mm (nominal " + printed("%g", design.spec.gapMm) + " mm): slit period " +
          formatted(after.slitPeriodPx, 5) +
          " mask px at D = " + printed("%.1f", after.viewDistanceMm) + " mm",
      "mask offset      " + formatted(m.maskPanelOffsetPx, 3) + " ± " +
          formatted(m.maskPanelOffsetSigmaPx, 3) + " mask px (mask.panel_offset_px)",
      "mask rotation    " + formatted(m.maskRotationDegrees, 4) + " ± " +
          formatted(m.rotationSigmaDegrees, 4) + " degrees: the mask is off by up to " +
          formatted(m.rotationEdgeErrorPx, 2) + " px at its top and bottom rows" +
          (m.rotationEdgeErrorPx > quarter ? " (more than the quarter pixel the phase allows: "
                                             "turn the panels into line)"
                                           : ""),
      "camera           focal " + formatted(m.focalPx, 1) + " ± " + formatted(m.focalSigmaPx, 1) +
          " px, k1 " + formatted(m.k1, 4) + ", k2 " + formatted(m.k2, 4)};
  for (const photocal::BarrierPhotoReport& p : m.photos)
    result.lines.push_back(
        printed("photo            %s: camera at (%.0f, %.0f, %.0f) mm, %.1f "
                "degrees off axis, %d markers, %d blocks, contrast %.2f",
                p.name.c_str(), p.cameraMm[0], p.cameraMm[1], p.cameraMm[2], p.offAxisDegrees,
                p.markers, p.rearBlocks, p.contrast));
}

// The lenticular panel's measurement, its visual.json and its report.
void lenticularReport(const DisplayDescription& nominal,
                      const std::vector<photocal::NamedPhoto>& photos, Reporter& reporter,
                      const std::string& output, PhotoCalibration& result) {
  const LenticularDesign design = designLenticular(nominal.lenticular);
  photocal::LenticularMeasurement m;
  {
    const auto progress = reporter.progress("measuring");
    m = photocal::measureLenticular(design, photos, progress->callback());
  }
  result.lenticular = m;
  result.measured.lenticular = m.measured;
  result.measuredText = lenticularCalibrationText(m.measured);
  const LenticularCalibration& n = design.calibration;
  JsonWriter json;
  json.set("/kind", result.kind);
  json.set("/display", nominal.source());
  json.set("/pitch/value", m.measured.pitch);
  json.set("/pitch/sigma", m.pitchSigma);
  json.set("/pitch/nominal", n.pitch);
  json.set("/slope/value", m.measured.slope);
  json.set("/slope/sigma", m.slopeSigma);
  json.set("/slope/nominal", n.slope);
  json.set("/center/value", m.measured.center);
  json.set("/center/sigma", m.centerSigma);
  json.set("/center/nominal", n.center);
  json.set("/slant_degrees/value", m.slantDegrees);
  json.set("/slant_degrees/sigma", m.slantSigmaDegrees);
  json.set("/gap_mm/value", m.gapMm);
  json.set("/gap_mm/sigma", m.gapSigmaMm);
  json.set("/view_distance_mm", design.viewDistanceMm);
  recordCameraAndPhotos(json, m);
  for (size_t i = 0; i < m.photos.size(); ++i)
    json.set("/photos/" + std::to_string(i) + "/coherence", m.photos[i].coherence);
  if (!output.empty()) json.set("/output", output);
  result.json = json.dump();
  result.lines = {
      "display          " + nominal.source() + " (lenticular, " + std::to_string(photos.size()) +
          " photos)",
      "pitch            " + formatted(m.measured.pitch, 5) + " ± " + formatted(m.pitchSigma, 5) +
          " lenses an inch (nominal " + printed("%g", n.pitch) +
          "), converging at D = " + printed("%.0f", design.viewDistanceMm) + " mm",
      "slope            " + formatted(m.measured.slope, 5) + " ± " + formatted(m.slopeSigma, 5) +
          " (nominal " + printed("%g", n.slope) + "): lenses " + formatted(m.slantDegrees, 4) +
          " ± " + formatted(m.slantSigmaDegrees, 4) + " degrees from vertical",
      "center           " + formatted(m.measured.center, 4) + " ± " + formatted(m.centerSigma, 4) +
          " lens periods (nominal " + printed("%g", n.center) + ")",
      "lens gap         " + formatted(m.gapMm, 3) + " ± " + formatted(m.gapSigmaMm, 3) +
          " mm (air-equivalent)",
      "camera           focal " + formatted(m.focalPx, 1) + " ± " + formatted(m.focalSigmaPx, 1) +
          " px, k1 " + formatted(m.k1, 4) + ", k2 " + formatted(m.k2, 4)};
  for (const photocal::LenticularPhotoReport& p : m.photos)
    result.lines.push_back(
        printed("photo            %s: camera at (%.0f, %.0f, %.0f) mm, %.1f "
                "degrees off axis, %d markers, fringe coherence %.2f",
                p.name.c_str(), p.cameraMm[0], p.cameraMm[1], p.cameraMm[2], p.offAxisDegrees,
                p.markers, p.coherence));
}

}  // namespace

namespace {

// The shots folder, the display it was made for (or the request's), and the photos decoded:
// every photo's header first (its shot, its size and the memory its decoding takes), then the
// photos, all kept (3 bytes a pixel); one at a time has its markers looked for, which is the
// peak: OpenCV's marker detector holds the contours of a noisy 12-megapixel photo in about 55
// bytes a pixel (measured: one photo 721 MB, two 756 MB, four 827 MB, the process itself
// 80 MB).
struct PhotosOfShots {
  ShotsFolder folder;
  DisplayDescription display;
  std::vector<photocal::NamedPhoto> photos;
};

// `refuseKind`: a kind of shots the caller cannot read ("" none) and why, refused before any
// display or photo is read.
PhotosOfShots readPhotosOfShots(const std::string& shots, const DisplayRequest& display,
                                const std::vector<std::string>& paths, Reporter& reporter,
                                const std::string& refuseKind = "", const std::string& why = "") {
  PhotosOfShots out;
  out.folder = readShotsFolder(shots);
  if (!refuseKind.empty() && out.folder.kind == refuseKind) throw InputError(shots, "", why);
  out.display = display.describe(reporter, out.folder.displayPath);
  if (kindName(out.display) != out.folder.kind)
    throw InputError(out.display.source(), "",
                     std::string("is a ") + kindName(out.display) + " display, and " + shots +
                         " holds " + out.folder.kind + " shots");
  if (paths.empty()) throw RequestError("photos", "needs at least one photo of the shots");
  constexpr double kDetectionBytesPerPixel = 56;
  double kept = 0, largest = 0;
  for (const std::string& path : paths) {
    shotOfPhoto(path, out.folder, shots);
    requireRegularFile(path);
    if (fs::file_size(path) > kMaxPhotoFileBytes)
      throw InputError(
          path, "",
          "is larger than a photo (" + std::to_string(fs::file_size(path) >> 20) + " MiB)");
    std::ifstream in(path, std::ios::binary);
    std::vector<uint8_t> head(size_t(std::min<uintmax_t>(fs::file_size(path), 1u << 20)));
    in.read(reinterpret_cast<char*>(head.data()), std::streamsize(head.size()));
    const vision::PhotoHeader header = vision::readPhotoHeader(head, path, kMaxPhotoPixels);
    const double pixels = double(header.width) * header.height;
    kept += 3 * pixels;
    largest = std::max(largest, double(header.decodeBytes) + kDetectionBytesPerPixel * pixels);
  }
  checkMemoryEstimate(kept + largest, paths.front(), "the photos and finding their markers",
                      "give fewer or smaller photos");
  const auto progress = reporter.progress("reading photos");
  for (size_t i = 0; i < paths.size(); ++i) {
    const std::string text = readInputFile(paths[i]);
    const std::span<const uint8_t> data(reinterpret_cast<const uint8_t*>(text.data()), text.size());
    out.photos.push_back({paths[i], vision::decodePhoto(data, paths[i], kMaxPhotoPixels)});
    progress->update(int(i + 1), int(paths.size()));
  }
  return out;
}

}  // namespace

PhotoCalibration calibrateFromPhotos(const CalibratePhotoRequest& r, Reporter& reporter) {
  const PhotosOfShots in = readPhotosOfShots(r.shots, r.display, r.photos, reporter);
  PhotoCalibration result;
  result.kind = in.folder.kind;
  result.measured = in.display;
  if (in.display.kind == DisplayKind::Lenticular)
    lenticularReport(in.display, in.photos, reporter, r.output, result);
  else
    barrierReport(in.display, in.photos, reporter, r.output, result);
  return result;
}

void runCalibratePhoto(const CalibratePhotoRequest& r, Reporter& reporter) {
  if (!r.output.empty()) checkOutputFile(r.output);
  const PhotoCalibration result = calibrateFromPhotos(r, reporter);
  if (!r.output.empty()) writeFileAtomically(r.output, result.measuredText);
  if (r.json) {
    reporter.result(result.json);
    return;
  }
  for (const std::string& line : result.lines) reporter.result(line);
  if (!r.output.empty()) reporter.result("wrote " + r.output);
}

// ---- the check ---------------------------------------------------------------------------------

SeatCheckReport checkSeats(const CalibrationCheckRequest& r, Reporter& reporter) {
  const PhotosOfShots in =
      readPhotosOfShots(r.shots, r.display, r.photos, reporter, "barrier",
                        "holds barrier shots: the seat check reads a lenticular panel's lens shot "
                        "(a barrier's is not written yet)");
  const LenticularDesign shown = designLenticular(in.display.lenticular);
  SeatCheckReport report;
  {
    const auto progress = reporter.progress("checking");
    report.seats = photocal::checkLenticularSeats(shown, in.photos, progress->callback());
  }
  const int views = std::max(1, shown.quiltViews);
  const double ideal = photocal::seenAmplitudeOfSpot(shown, 0);
  JsonWriter json;
  json.set("/display", in.display.source());
  json.set("/views", views);
  json.set("/ideal_lens_amplitude", ideal);
  report.lines.push_back(
      printed("display          %s (lenticular, the shot drawn with it; "
              "views as fractions of the cone, view k of %d at (k + 1/2) / %d)",
              in.display.source().c_str(), views, views));
  for (size_t i = 0; i < report.seats.size(); ++i) {
    const photocal::SeatCheck& seat = report.seats[i];
    const std::string at = "/seats/" + std::to_string(i);
    recordPhotoPlace(json, at, seat.name, seat.cameraMm, seat.offAxisDegrees, seat.markers);
    json.set(at + "/distance_sigma_mm", seat.distanceSigmaMm);
    json.set(at + "/view_seen/value", seat.viewSeen);
    json.set(at + "/view_seen/sigma", seat.viewSeenSigma);
    json.set(at + "/view_aimed", seat.viewAimed);
    json.set(at + "/edges_seen/0", seat.edgesSeen[0]);
    json.set(at + "/edges_seen/1", seat.edgesSeen[1]);
    json.set(at + "/edges_aimed/0", seat.edgesAimed[0]);
    json.set(at + "/edges_aimed/1", seat.edgesAimed[1]);
    json.set(at + "/top_bottom_seen/0", seat.topBottomSeen[0]);
    json.set(at + "/top_bottom_seen/1", seat.topBottomSeen[1]);
    json.set(at + "/amplitude", seat.amplitude);
    json.set(at + "/lens_spot_subpixels", seat.spotSubpixels);
    json.set(at + "/other_views_share", seat.otherViews);
    json.set(at + "/coherence", seat.coherence);
    const auto view = [&](double f) { return printed("%.3f (view %.1f)", f, f * views - 0.5); };
    const double off = seat.viewSeen - seat.viewAimed - std::round(seat.viewSeen - seat.viewAimed);
    report.lines.push_back(printed(
        "photo            %s: camera at (%.0f, %.0f, %.0f) mm (its distance ± %.0f mm), %.1f "
        "degrees off axis, %d markers",
        seat.name.c_str(), seat.cameraMm[0], seat.cameraMm[1], seat.cameraMm[2],
        seat.distanceSigmaMm, seat.offAxisDegrees, seat.markers));
    report.lines.push_back(
        "  sees           " + view(seat.viewSeen) + " ± " + printed("%.3f", seat.viewSeenSigma) +
        " at the panel's centre; the "
        "file aims " +
        view(seat.viewAimed) + " there (" + printed("%+.1f", off * views) + " views)");
    report.lines.push_back(printed(
        "  across         left edge %.3f, right edge %.3f (the file: %.3f, %.3f); top %.3f, "
        "bottom %.3f (the file: %.3f at both)",
        seat.edgesSeen[0], seat.edgesSeen[1], seat.edgesAimed[0], seat.edgesAimed[1],
        seat.topBottomSeen[0], seat.topBottomSeen[1], seat.viewAimed));
    report.lines.push_back(printed(
        "  crosstalk      amplitude %.2f (an ideal lens %.2f, fringes' coherence %.2f): a focal "
        "spot of %.1f subpixels (simulate --lens-spot), %.0f %% of the light from other views "
        "(an ideal lens %.0f %%)",
        seat.amplitude, ideal, seat.coherence, seat.spotSubpixels, 100 * seat.otherViews,
        100 * photocal::otherViewsShare(shown, 0)));
  }
  report.json = json.dump();
  return report;
}

void runCalibrationCheck(const CalibrationCheckRequest& r, Reporter& reporter) {
  const SeatCheckReport report = checkSeats(r, reporter);
  if (r.json) {
    reporter.result(report.json);
    return;
  }
  for (const std::string& line : report.lines) reporter.result(line);
}

}  // namespace parallax::jobs
