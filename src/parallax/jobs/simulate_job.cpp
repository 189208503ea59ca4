// The simulate runner's pieces that both front ends use: the simulator's options and their
// checks, the eyes, the estimates, and the quality figures at given eyes.
#include "parallax/jobs/simulate_job.h"

#include <cmath>
#include <limits>
#include <memory>

#include "parallax/camera/framing.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/display/depth_scaled_display.h"
#include "parallax/image/metrics.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/lens_readings.h"
#include "parallax/jobs/limits.h"
#include "parallax/quality/viewer_quality.h"
#include "parallax/sim/crosstalk.h"

namespace parallax::jobs {

namespace {
// An eye farther than this from the display (1 km) sees nothing a simulation could show.
constexpr double kMaxEyeMm = 1e6;
}  // namespace

SimulationOptions simulationOptions(const SimulatorRequest& r, const DisplayModel& display) {
  const int root = int(std::lround(std::sqrt(double(std::max(r.spp, 0)))));
  if (r.spp < 0 || root * root != r.spp)
    throw RequestError("spp", "must be 0 or a square number n*n");
  if (!(r.pupil >= 0 && r.pupil <= 100))
    throw RequestError("pupil", "must be a number from 0 to 100");
  checkThreads(r.threads);
  if (r.pupilSamples < 1)
    throw RequestError("pupil_samples", "must be a whole number of at least 1");
  const double diffuser = r.diffuser ? *r.diffuser : display.diffuserSigmaMm();
  if (!(diffuser >= 0 && std::isfinite(diffuser)))
    throw RequestError("diffuser", "must be a number of at least 0");
  // Options that only the two-layer simulator has (a display with a mask layer), refused for
  // other kinds by name.
  if (!display.hasMaskLayer()) {
    const auto refuse = [](const char* field) {
      throw RequestError(field,
                         "applies to the two-layer (barrier) simulator; a lenticular panel is seen "
                         "through its lenses at the panel's resolution");
    };
    if (r.size) refuse("size");
    if (r.spp != 0) refuse("spp");
    if (r.pupil > 0) refuse("pupil");
    if (diffuser > 0) refuse("diffuser");
    if (r.colorFilters) refuse("color_filters");
    if (r.raw) refuse("raw");
  }
  const std::optional<LensOptics> optics = lensReading(display, r.lens);
  SimulationOptions sim;
  if (r.size) {
    if ((*r.size)[0] < 1 || (*r.size)[1] < 1)
      throw RequestError("size", "expected (width, height), both positive");
    sim.width = (*r.size)[0], sim.height = (*r.size)[1];
  }
  const DisplayWindow window = display.window();
  if (diffuser > window.widthMm)
    throw RequestError("diffuser", "a blur wider than the display (" +
                                       std::to_string(int(window.widthMm)) + " mm) is no diffuser");
  sim.samplesPerPixel = r.spp;
  sim.pupilDiameterMm = r.pupil;
  sim.pupilSamples = r.pupilSamples;
  sim.diffuserSigmaMm = diffuser;
  sim.colourFilters = r.colorFilters;
  sim.normalise = !r.raw;
  sim.threads = r.threads;
  sim.lensOptics = optics;
  return sim;
}

void checkMaskLayer(const DisplayModel& display, bool maskGiven) {
  if (maskGiven && !display.hasMaskLayer())
    throw RequestError("mask", "a lenticular display has no mask layer");
}

std::vector<Vec3d> sweepEyes(const DisplayModel& display, const SweepRequest& sweep) {
  if (sweep.count < 1) throw RequestError("sweep", "must be at least 1 eye");
  if (!(sweep.range > 0 && sweep.range <= 10))
    throw RequestError("sweep_range", "must be above 0 and at most 10");
  if (!(sweep.distance >= 0 && std::isfinite(sweep.distance)))
    throw RequestError("sweep_distance", "must be 0 (D) or a distance in mm");
  const Vec3d centre = display.window().eyeMm;  // the zone's centre at the design distance D
  if (sweep.distance > 100 * centre.z)
    throw RequestError("sweep_distance", "must be at most 100 times the design distance D = " +
                                             std::to_string(int(centre.z)) + " mm");
  const double z = sweep.distance > 0 ? sweep.distance : centre.z;
  std::vector<Vec3d> eyes;
  // Across the view zone (scaled by the range), scaled to the distance so that a farther sweep
  // covers the same views.
  for (int i = 0; i < sweep.count; ++i) {
    const double t = sweep.count == 1 ? 0.5 : double(i) / double(sweep.count - 1);
    const Vec3d e = display.eyeAcrossZone(0.5 + sweep.range * (t - 0.5));
    eyes.push_back({centre.x + (e.x - centre.x) * z / centre.z, centre.y, z});
  }
  return eyes;
}

std::vector<Vec3d> simulatedEyes(const DisplayModel& display, const std::vector<Vec3d>& given,
                                 const SweepRequest& sweep) {
  std::vector<Vec3d> eyes;
  for (const Vec3d& e : given) {
    // Finite and within a kilometre: a NaN would otherwise pass as "in front" and reach the
    // simulator, 1e300 mm gave a picture of nothing.
    if (!(std::abs(e.x) <= kMaxEyeMm && std::abs(e.y) <= kMaxEyeMm && e.z <= kMaxEyeMm))
      throw RequestError("eye", "must be finite and within 1e6 mm (1 km) of the display");
    if (!(e.z > 0)) throw RequestError("eye", "the eye must be in front (z > 0)");
    eyes.push_back(e);
  }
  if (sweep.count > 0)
    for (const Vec3d& e : sweepEyes(display, sweep)) eyes.push_back(e);
  if (eyes.empty()) eyes.push_back(display.window().eyeMm);
  return eyes;
}

void checkLayerValues(const LayerImages& layers) {
  const auto check = [](const Image& image, const char* field, bool transmittance) {
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x)
        for (int c = 0; c < 3; ++c) {
          const float v = image.at(x, y)[c];
          if (std::isfinite(v) && v >= 0 && (!transmittance || v <= 1)) continue;
          const std::string where = "pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                    ") channel " + std::to_string(c) + " is ";
          throw RequestError(field, where +
                                        (std::isnan(v)   ? std::string("NaN")
                                         : std::isinf(v) ? std::string("infinite")
                                                         : printed("%g", double(v))) +
                                        (transmittance ? ": a transmittance is from 0 to 1"
                                                       : ": light is finite and not negative"));
        }
  };
  check(layers.image, "image", false);
  check(layers.mask, "mask", true);
}

std::pair<double, double> seenPictureSize(const DisplayModel& display, const SimulatorRequest& r) {
  // (A size is the two-layer simulator's: refused for the other kinds.)
  const PanelSize panel = display.viewerPanel();
  return {r.size ? (*r.size)[0] : panel.width, r.size ? (*r.size)[1] : panel.height};
}

void checkSimulationWork(const DisplayModel& display, const LayerImages& layers,
                         const SimulatorRequest& r, size_t eyes, int sweep, int referenceSpp,
                         int keptCopies) {
  checkLayerValues(layers);
  const auto [w, h] = seenPictureSize(display, r);
  const double layerBytes = imageBytes(layers.image.width(), layers.image.height()) +
                            imageBytes(layers.mask.width(), layers.mask.height());
  // Eyes are seen one at a time: one view and its picture at once, and per eye only what is
  // kept (a sweep's PNG, at most about the 8-bit codes, and a small thumbnail).
  const double oneEye = imageBytes(w, h, 2 * kFloatRgbPixelBytes + kRgba8PixelBytes);
  const double perEye = imageBytes(w, h, kRgba8PixelBytes);
  const std::string subject =
      sweep > 0 ? "{sweep} " + std::to_string(sweep)
      : r.size  ? "{size} " + std::to_string((*r.size)[0]) + "x" + std::to_string((*r.size)[1])
                : "{eye}";
  // Eyes alone (no sweep, no reference): the whole estimate, the layers loaded (the simulator
  // holds its own copy). A sweep's is
  // made at its first picture, the dense measure's with its scene; this one refuses early.
  if (sweep == 0 && referenceSpp == 0)
    checkPeakMemory(
        keptCopies == 0 ? layerBytes + oneEye
                        // In memory (Python): the layers are moved into the simulator; the
                        // pictures are kept as made, then copied for the caller.
                        : std::max(oneEye + double(eyes - 1) * imageBytes(w, h),
                                   double(keptCopies) * double(eyes) * imageBytes(w, h)),
        subject, std::to_string(eyes) + " simulated views", "use a smaller size or fewer eyes");
  else
    checkMemoryEstimate(2 * layerBytes + oneEye + double(eyes) * perEye, subject,
                        std::to_string(eyes) + " simulated views",
                        sweep > 0 ? "use fewer steps" : "use a smaller size or fewer eyes");
  checkPixelCount(w * h, subject);
  // The exact integral costs about as much as 3 x 3 point samples (the pieces between the two
  // layers' pixel edges: 2 to 3 along each axis).
  const double perPixel = r.spp > 0 ? r.spp : 9;
  const double samples = double(eyes) * w * h * perPixel * (r.pupil > 0 ? r.pupilSamples : 1);
  if (sweep > 0)
    checkTimeEstimate(samples, r.threads, "sweep", std::to_string(sweep),
                      "use fewer samples or eyes");
  else
    checkTimeEstimate(samples, r.threads, "spp", std::to_string(r.spp),
                      "use fewer samples or eyes");
  if (referenceSpp > 0)
    checkTimeEstimate(double(eyes) * w * h * referenceSpp, r.threads, "reference_spp",
                      std::to_string(referenceSpp), "use fewer samples");
}

Image seenPicture(const SimulatedDisplay& simulator, const Image& view, bool rawPixels) {
  return rawPixels ? view : simulator.atDisplayResolution(view);
}

std::vector<Image> simulatedPictures(const DisplayModel& display, LayerImages layers,
                                     const SimulatorRequest& request,
                                     const std::vector<Vec3d>& eyes) {
  const SimulationOptions sim = simulationOptions(request, display);
  const std::vector<Vec3d> checked = simulatedEyes(display, eyes);
  checkSimulationWork(display, layers, request, checked.size(), 0, 0, 2);
  const std::unique_ptr<SimulatedDisplay> simulator =
      simulateDisplay(display, std::move(layers), sim);
  std::vector<Image> pictures;
  for (const Vec3d& eye : checked)
    pictures.push_back(seenPicture(*simulator, simulator->view(eye), request.rawPixels));
  return pictures;
}

RenderedReference referenceScene(Scene scene, const DisplayModel& display,
                                 const FramingRequest& framing) {
  RenderedReference reference;
  reference.display = &display;
  framing.apply(scene.display);
  const Framing framed = frameForDisplay(scene, display);
  scene.display = framed.placement;
  reference.scene = std::move(scene);
  // A barrier shows the camera's depth through its virtual gap, which its display file
  // carries; a lenticular panel's camera scaled depth, which the reference's display does too.
  if (framed.lenticular && framed.depthScale != 1) {
    reference.scaled = depthScaledView(display, framed.depthScale);
    reference.display = reference.scaled.get();
  }
  return reference;
}

EyeFigures eyeFigures(const QualityReference& r, const Vec3d& eye, const Image& view,
                      const Image& seen) {
  const Image ideal = idealView(r.scene, r.accelerator, r.display, r.simulator, eye, view.width(),
                                view.height(), r.referenceSpp, r.options.threads);
  EyeFigures f;
  f.psnr = psnr(seen, ideal);
  f.ssim = ssim(seen, ideal);
  if (const DisplayDesign* d = r.display.barrierDesign()) {
    // Brightness is the raw mean transmittance, whatever raw says for the pictures; with
    // time-multiplexed frames, the mean over the frames' masks (the eye averages them).
    SimulationOptions raw = r.options;
    raw.normalise = false;
    for (const LayerImages& frame : r.frames) {
      const CrosstalkResult c = measureCrosstalk(*d, frame.mask, raw, eye);
      f.brightness += c.brightness / double(r.frames.size());
      f.crosstalk += c.crosstalk / double(r.frames.size());
      f.ownView = c.ownView;
    }
  } else {
    f.brightness = 1.0;  // a lens passes all its light (no barrier)
    f.crosstalk = std::numeric_limits<double>::quiet_NaN();
  }
  return f;
}

void checkReferenceSpp(int referenceSpp) {
  if (referenceSpp < 1) throw RequestError("reference_spp", "must be a whole number of at least 1");
}

std::vector<EyeFigures> qualityFigures(const Scene& scene, const DisplayModel& display,
                                       LayerImages layers, const SimulatorRequest& request,
                                       const std::vector<Vec3d>& eyes, int referenceSpp) {
  checkReferenceSpp(referenceSpp);
  const SimulationOptions sim = simulationOptions(request, display);
  const std::vector<Vec3d> checked = simulatedEyes(display, eyes);
  checkSimulationWork(display, layers, request, checked.size(), 0, referenceSpp);
  const std::vector<LayerImages> frames{std::move(layers)};
  const std::unique_ptr<SimulatedDisplay> simulator = simulateDisplay(display, frames, sim);
  const Accelerator accelerator(scene);
  const QualityReference reference{scene,  accelerator, display,     *simulator,
                                   frames, sim,         referenceSpp};
  std::vector<EyeFigures> figures;
  for (const Vec3d& eye : checked) {
    const Image view = simulator->view(eye);
    figures.push_back(eyeFigures(reference, eye, view, simulator->atDisplayResolution(view)));
  }
  return figures;
}

std::string qualityReport(const Scene& scene, const DisplayModel& display, LayerImages layers,
                          const SimulatorRequest& request, const std::vector<Vec3d>& eyes,
                          int referenceSpp, const FramingRequest& framing) {
  const RenderedReference reference = referenceScene(scene, display, framing);
  const std::vector<EyeFigures> figures = qualityFigures(
      reference.scene, *reference.display, std::move(layers), request, eyes, referenceSpp);
  JsonWriter json;
  json.set("/display", display.source());
  json.set("/display_kind", displayKindName(display.kind()));
  recordEyeFigures(json, eyes, figures);
  return json.dump();
}

void recordEyeFigures(JsonWriter& json, const std::vector<Vec3d>& eyes,
                      const std::vector<EyeFigures>& figures) {
  EyeFigures mean;
  for (size_t i = 0; i < eyes.size(); ++i) {
    const std::string at = "/eyes/" + std::to_string(i);
    json.set(at + "/eye", Vec3f{float(eyes[i].x), float(eyes[i].y), float(eyes[i].z)});
    if (figures.empty()) continue;
    const EyeFigures& f = figures[i];
    json.set(at + "/psnr", f.psnr);
    json.set(at + "/ssim", f.ssim);
    json.set(at + "/brightness", f.brightness);
    json.set(at + "/crosstalk", f.crosstalk);
    json.set(at + "/own_view", f.ownView);
    mean.psnr += f.psnr / double(eyes.size());
    mean.ssim += f.ssim / double(eyes.size());
    mean.brightness += f.brightness / double(eyes.size());
    mean.crosstalk += f.crosstalk / double(eyes.size());
  }
  if (figures.empty()) return;
  json.set("/mean/psnr", mean.psnr);
  json.set("/mean/ssim", mean.ssim);
  json.set("/mean/brightness", mean.brightness);
  json.set("/mean/crosstalk", mean.crosstalk);
}

}  // namespace parallax::jobs
