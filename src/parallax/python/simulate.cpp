// What an eye sees on the display (`simulate`), the eyes of a sweep (`simulate --sweep`) and
// the quality figures against the ideal views (`simulate --reference --json`). The GIL is
// released while the pictures are made.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/camera/framing.h"
#include "parallax/core/error.h"
#include "parallax/display/display_model.h"
#include "parallax/display/lenticular.h"
#include "parallax/image/metrics.h"
#include "parallax/io/json_writer.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/requests.h"
#include "parallax/python/bindings_internal.h"
#include "parallax/quality/viewer_quality.h"
#include "parallax/sim/crosstalk.h"
#include "parallax/sim/simulated_display.h"

namespace parallax::python {

namespace {

// The simulator's keywords (simulate's options).
struct SeeOptions {
  std::optional<std::array<int, 2>> size;
  int spp;
  double pupil;
  int pupilSamples;
  double diffuser;
  bool colourFilters, raw, rawPixels;
  int threads;
};

std::unique_ptr<DisplayModel> makeDisplay(const DisplayDescription& d) {
  return jobs::makeDisplay(d).model;
}

// The options as SimulationOptions, refused as the CLI refuses them.
SimulationOptions simulationOptions(const SeeOptions& o, const DisplayModel& display) {
  const int root = int(std::lround(std::sqrt(double(std::max(o.spp, 0)))));
  if (o.spp < 0 || root * root != o.spp)
    throw InputError("command line", "--spp", "must be 0 or a square number n*n");
  if (!(o.pupil >= 0 && o.pupil <= 100))
    throw InputError("command line", "--pupil", "must be a number from 0 to 100");
  if (o.pupilSamples < 1)
    throw InputError("command line", "--pupil-samples", "must be a whole number of at least 1");
  if (!(o.diffuser >= 0 && std::isfinite(o.diffuser)))
    throw InputError("command line", "--diffuser", "must be a number of at least 0");
  if (!display.barrierDesign()) {
    const auto refuse = [](const char* option) {
      throw InputError("command line", option,
                       "applies to the two-layer (barrier) simulator; a lenticular panel is seen "
                       "through its lenses at the panel's resolution");
    };
    if (o.size) refuse("--size");
    if (o.spp != 0) refuse("--spp");
    if (o.pupil > 0) refuse("--pupil");
    if (o.diffuser > 0) refuse("--diffuser");
    if (o.colourFilters) refuse("--color-filters");
    if (o.raw) refuse("--raw");
  }
  SimulationOptions sim;
  if (o.size) {
    if ((*o.size)[0] < 1 || (*o.size)[1] < 1)
      throw InputError("command line", "--size", "expected (width, height), both positive");
    sim.width = (*o.size)[0], sim.height = (*o.size)[1];
  }
  sim.samplesPerPixel = o.spp;
  sim.pupilDiameterMm = o.pupil;
  sim.pupilSamples = o.pupilSamples;
  sim.diffuserSigmaMm = o.diffuser;
  sim.colourFilters = o.colourFilters;
  sim.normalise = !o.raw;
  sim.threads = o.threads;
  return sim;
}

LayerImages layerImages(const py::array& image, const std::optional<py::array>& mask,
                        const DisplayModel& display) {
  LayerImages layers;
  layers.image = arrayToImage(image, "image");
  if (display.hasMaskLayer()) {
    if (!mask) throw py::value_error("mask: a barrier display needs the mask layer's array");
    layers.mask = arrayToImage(*mask, "mask");
  } else if (mask) {
    throw InputError("command line", "--mask", "a lenticular display has no mask layer");
  }
  return layers;
}

std::vector<Vec3d> eyesInFront(const std::vector<std::array<double, 3>>& given) {
  if (given.empty()) throw py::value_error("eyes: expected at least one eye (x, y, z) in mm");
  std::vector<Vec3d> eyes;
  for (const auto& e : given) eyes.push_back(eyeInFront(e, "--eye"));
  return eyes;
}

// The pictures the eyes see, as `simulate --eye ...` writes them (at the display's resolution
// unless raw_pixels).
std::vector<py::array_t<float>> see(const py::array& image, const std::optional<py::array>& mask,
                                    const DisplayDescription& description,
                                    const std::vector<std::array<double, 3>>& eyeList,
                                    const SeeOptions& o) {
  const std::unique_ptr<DisplayModel> display = makeDisplay(description);
  const SimulationOptions sim = simulationOptions(o, *display);
  const std::vector<Vec3d> eyes = eyesInFront(eyeList);
  LayerImages layers = layerImages(image, mask, *display);
  std::vector<Image> pictures;
  {
    py::gil_scoped_release released;
    const std::unique_ptr<SimulatedDisplay> simulator =
        simulateDisplay(*display, std::move(layers), sim);
    for (const Vec3d& eye : eyes) {
      const Image view = simulator->view(eye);
      pictures.push_back(o.rawPixels ? view : simulator->atDisplayResolution(view));
    }
  }
  std::vector<py::array_t<float>> arrays;
  for (const Image& p : pictures) arrays.push_back(imageToArray(p));
  return arrays;
}

// `simulate --sweep N [--sweep-range F] [--sweep-distance MM]`'s eyes, left to right.
std::vector<std::array<double, 3>> sweepEyes(const DisplayDescription& description, int count,
                                             double range, double distance) {
  if (count < 1) throw InputError("command line", "--sweep", "must be at least 1 eye");
  if (!(range > 0 && range <= 10))
    throw InputError("command line", "--sweep-range", "must be above 0 and at most 10");
  if (!(distance >= 0 && std::isfinite(distance)))
    throw InputError("command line", "--sweep-distance", "must be 0 (D) or a distance in mm");
  const std::unique_ptr<DisplayModel> display = makeDisplay(description);
  const Vec3d centre = display->window().eyeMm;  // the zone's centre at the design distance D
  if (distance > 100 * centre.z)
    throw InputError("--sweep-distance", "",
                     "must be at most 100 times the design distance D = " +
                         std::to_string(int(centre.z)) + " mm");
  const double z = distance > 0 ? distance : centre.z;
  std::vector<std::array<double, 3>> eyes;
  for (int i = 0; i < count; ++i) {
    const double t = count == 1 ? 0.5 : double(i) / double(count - 1);
    const Vec3d e = display->eyeAcrossZone(0.5 + range * (t - 0.5));
    eyes.push_back({centre.x + (e.x - centre.x) * z / centre.z, centre.y, z});
  }
  return eyes;
}

// `simulate --reference --eye ... --json`: per eye PSNR and SSIM against the ideal view, the
// brightness and cross-talk (barrier), and their means, as JSON text.
std::string quality(const Scene& loaded, const DisplayDescription& description,
                    const py::array& image, const std::optional<py::array>& mask,
                    const std::vector<std::array<double, 3>>& eyeList, int referenceSpp,
                    const SeeOptions& o, const std::string& fit, const std::string& focus,
                    const std::string& depthBudget) {
  if (referenceSpp < 1)
    throw InputError("command line", "--reference-spp", "must be a whole number of at least 1");
  const std::unique_ptr<DisplayModel> display = makeDisplay(description);
  SimulationOptions sim = simulationOptions(o, *display);
  const std::vector<Vec3d> eyes = eyesInFront(eyeList);
  LayerImages layers = layerImages(image, mask, *display);
  Scene scene = loaded;
  const DisplayDesign* barrier = display->barrierDesign();
  if (barrier) {  // framed as render framed it (framedScene: what simulate --reference reads)
    jobs::FramingRequest framing;
    framing.fit = fit, framing.focus = focus, framing.depthBudget = depthBudget;
    framing.apply(scene.display);
    scene = framedScene(std::move(scene), *barrier);
  }
  struct Figures {
    double psnr = 0, ssim = 0, brightness = 0, crosstalk = 0;
    int ownView = -1;
  };
  std::vector<Figures> figures;
  {
    py::gil_scoped_release released;
    const Image maskLayer = layers.mask;
    const std::unique_ptr<SimulatedDisplay> simulator =
        simulateDisplay(*display, std::move(layers), sim);
    const Accelerator accelerator(scene);
    for (const Vec3d& eye : eyes) {
      const Image view = simulator->view(eye);
      const Image picture = o.rawPixels ? view : simulator->atDisplayResolution(view);
      const Image reference = idealView(scene, accelerator, *display, *simulator, eye, view.width(),
                                        view.height(), referenceSpp, o.threads);
      const Image seen = o.rawPixels ? simulator->atDisplayResolution(view) : picture;
      Figures f;
      f.psnr = psnr(seen, reference);
      f.ssim = ssim(seen, reference);
      if (barrier) {
        SimulationOptions raw = sim;  // brightness is the raw mean transmittance
        raw.normalise = false;
        const CrosstalkResult c = measureCrosstalk(*barrier, maskLayer, raw, eye);
        f.brightness = c.brightness, f.crosstalk = c.crosstalk, f.ownView = c.ownView;
      } else {
        f.brightness = 1.0;  // a lens passes all its light
        f.crosstalk = std::numeric_limits<double>::quiet_NaN();
      }
      figures.push_back(f);
    }
  }
  JsonWriter json;
  json.set("/display", display->source());
  json.set("/display_kind", displayKindName(display->kind()));
  Figures mean;
  const double n = double(eyes.size());
  for (size_t i = 0; i < eyes.size(); ++i) {
    const std::string at = "/eyes/" + std::to_string(i);
    const Figures& f = figures[i];
    json.set(at + "/eye", Vec3f{float(eyes[i].x), float(eyes[i].y), float(eyes[i].z)});
    json.set(at + "/psnr", f.psnr);
    json.set(at + "/ssim", f.ssim);
    json.set(at + "/brightness", f.brightness);
    json.set(at + "/crosstalk", f.crosstalk);
    json.set(at + "/own_view", f.ownView);
    mean.psnr += f.psnr / n, mean.ssim += f.ssim / n;
    mean.brightness += f.brightness / n, mean.crosstalk += f.crosstalk / n;
  }
  json.set("/mean/psnr", mean.psnr);
  json.set("/mean/ssim", mean.ssim);
  json.set("/mean/brightness", mean.brightness);
  json.set("/mean/crosstalk", mean.crosstalk);
  return json.dump();
}

}  // namespace

void bindSimulate(py::module_& module) {
  const SimulationOptions defaults;
  const auto options = [](const std::optional<std::array<int, 2>>& size, int spp, double pupil,
                          int pupilSamples, double diffuser, bool colourFilters, bool raw,
                          bool rawPixels, int threads) {
    return SeeOptions{size,          spp, pupil,     pupilSamples, diffuser,
                      colourFilters, raw, rawPixels, threads};
  };
  module.def(
      "_simulate",
      [options](const py::array& image, const std::optional<py::array>& mask,
                const DisplayDescription& display, const std::vector<std::array<double, 3>>& eyes,
                const std::optional<std::array<int, 2>>& size, int spp, double pupil,
                int pupilSamples, double diffuser, bool colourFilters, bool raw, bool rawPixels,
                int threads) {
        return see(image, mask, display, eyes,
                   options(size, spp, pupil, pupilSamples, diffuser, colourFilters, raw, rawPixels,
                           threads));
      },
      py::arg("image"), py::arg("mask"), py::arg("display"), py::kw_only(), py::arg("eyes"),
      py::arg("size") = py::none(), py::arg("spp") = defaults.samplesPerPixel,
      py::arg("pupil") = defaults.pupilDiameterMm, py::arg("pupil_samples") = defaults.pupilSamples,
      py::arg("diffuser") = defaults.diffuserSigmaMm, py::arg("color_filters") = false,
      py::arg("raw") = false, py::arg("raw_pixels") = false, py::arg("threads") = 0);
  module.def("_sweep_eyes", &sweepEyes, py::arg("display"), py::kw_only(), py::arg("count"),
             py::arg("sweep_range") = 1.0, py::arg("distance") = 0.0);
  module.def(
      "_quality",
      [options](const Scene& scene, const DisplayDescription& display, const py::array& image,
                const std::optional<py::array>& mask,
                const std::vector<std::array<double, 3>>& eyes, int referenceSpp,
                const std::optional<std::array<int, 2>>& size, int spp, double pupil,
                int pupilSamples, double diffuser, bool colourFilters, bool raw, bool rawPixels,
                int threads, const std::string& fit, const std::string& focus,
                const std::string& budget) {
        return quality(scene, display, image, mask, eyes, referenceSpp,
                       options(size, spp, pupil, pupilSamples, diffuser, colourFilters, raw,
                               rawPixels, threads),
                       fit, focus, budget);
      },
      py::arg("scene"), py::arg("display"), py::arg("image"), py::arg("mask"), py::kw_only(),
      py::arg("eyes"), py::arg("reference_spp") = 16, py::arg("size") = py::none(),
      py::arg("spp") = defaults.samplesPerPixel, py::arg("pupil") = defaults.pupilDiameterMm,
      py::arg("pupil_samples") = defaults.pupilSamples,
      py::arg("diffuser") = defaults.diffuserSigmaMm, py::arg("color_filters") = false,
      py::arg("raw") = false, py::arg("raw_pixels") = false, py::arg("threads") = 0,
      py::arg("fit") = "", py::arg("focus") = "", py::arg("depth_budget") = "");
}

}  // namespace parallax::python
