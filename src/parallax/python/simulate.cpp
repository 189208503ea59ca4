// What an eye sees on the display (`simulate`), the eyes of a sweep (`simulate --sweep`) and
// the quality figures against the ideal views (`simulate --reference --json`): the keywords
// spell the simulate runner's requests (jobs/simulate_job.h). The GIL is released while the
// pictures are made.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "parallax/display/display_model.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/simulate_job.h"
#include "parallax/python/bindings_internal.h"
#include "parallax/quality/viewer_quality.h"

namespace parallax::python {

namespace {

using SeeOptions = jobs::SimulatorRequest;

LayerImages layerImages(const py::array& image, const std::optional<py::array>& mask,
                        const DisplayModel& display) {
  jobs::checkMaskLayer(display, mask.has_value());
  LayerImages layers;
  layers.image = arrayToImage(image, "image");
  if (display.hasMaskLayer()) {
    if (!mask) throw py::value_error("mask: a barrier display needs the mask layer's array");
    layers.mask = arrayToImage(*mask, "mask");
  }
  return layers;
}

std::vector<Vec3d> givenEyes(const std::vector<std::array<double, 3>>& given) {
  if (given.empty()) throw py::value_error("eyes: expected at least one eye (x, y, z) in mm");
  std::vector<Vec3d> eyes;
  for (const auto& e : given) eyes.push_back({e[0], e[1], e[2]});
  return eyes;
}

// The pictures the eyes see, as `simulate --eye ...` writes them (at the display's resolution
// unless raw_pixels), as one N x H x W x 3 array. Each picture is freed as it is copied in, so the
// peak is the pictures once plus the array, whatever the allocator keeps (a stack made in Python
// from N arrays would hold a third copy while the pictures' freed pages are still resident).
py::array_t<float> see(const py::array& image, const std::optional<py::array>& mask,
                       const DisplayDescription& description,
                       const std::vector<std::array<double, 3>>& eyeList, const SeeOptions& o) {
  const jobs::BuiltDisplay display = jobs::makeDisplay(description);
  const std::vector<Vec3d> eyes = givenEyes(eyeList);
  LayerImages layers = layerImages(image, mask, *display);
  std::vector<Image> pictures;
  {
    py::gil_scoped_release released;
    pictures = jobs::simulatedPictures(*display, std::move(layers), o, eyes);
  }
  const int width = pictures.front().width(), height = pictures.front().height();
  py::array_t<float> stack(
      {py::ssize_t(pictures.size()), py::ssize_t(height), py::ssize_t(width), py::ssize_t(3)});
  float* out = stack.mutable_data();
  for (Image& p : pictures) {
    if (p.width() != width || p.height() != height)
      throw std::logic_error("simulate: the eyes' pictures differ in size");
    std::memcpy(out, p.pixels().data(), p.pixels().size() * sizeof(Vec3f));
    out += p.pixels().size() * 3;
    p = Image();
  }
  return stack;
}

// `simulate --sweep N [--sweep-range F] [--sweep-distance MM]`'s eyes, left to right.
std::vector<std::array<double, 3>> sweepEyes(const DisplayDescription& description, int count,
                                             double range, double distance) {
  std::vector<std::array<double, 3>> eyes;
  for (const Vec3d& e : jobs::sweepEyes(*jobs::makeDisplay(description), {count, range, distance}))
    eyes.push_back({e.x, e.y, e.z});
  return eyes;
}

// `simulate --reference --eye ... --json`: per eye PSNR and SSIM against the ideal view, the
// brightness and cross-talk (barrier), and their means, as JSON text.
std::string quality(const Scene& loaded, const DisplayDescription& description,
                    const py::array& image, const std::optional<py::array>& mask,
                    const std::vector<std::array<double, 3>>& eyeList, int referenceSpp,
                    const SeeOptions& o, const std::string& fit, const std::string& focus,
                    const std::string& depthBudget) {
  const jobs::BuiltDisplay display = jobs::makeDisplay(description);
  const std::vector<Vec3d> eyes = givenEyes(eyeList);
  LayerImages layers = layerImages(image, mask, *display);
  jobs::FramingRequest framing;
  framing.fit = fit, framing.focus = focus, framing.depthBudget = depthBudget;
  py::gil_scoped_release released;
  return jobs::qualityReport(loaded, *display, std::move(layers), o, eyes, referenceSpp, framing);
}

}  // namespace

void bindSimulate(py::module_& module) {
  const SimulationOptions defaults;
  const auto options = [](const std::optional<std::array<int, 2>>& size, int spp, double pupil,
                          int pupilSamples, const std::optional<double>& diffuser,
                          bool colourFilters, bool raw, bool rawPixels, int threads,
                          const std::optional<double>& lensSpot, const std::string& bundles) {
    return SeeOptions{size,          spp, pupil,     pupilSamples, diffuser,
                      colourFilters, raw, rawPixels, threads,      {lensSpot, bundles}};
  };
  module.def(
      "_simulate",
      [options](const py::array& image, const std::optional<py::array>& mask,
                const DisplayDescription& display, const std::vector<std::array<double, 3>>& eyes,
                const std::optional<std::array<int, 2>>& size, int spp, double pupil,
                int pupilSamples, const std::optional<double>& diffuser, bool colourFilters,
                bool raw, bool rawPixels, int threads, const std::optional<double>& lensSpot,
                const std::string& bundles) {
        return see(image, mask, display, eyes,
                   options(size, spp, pupil, pupilSamples, diffuser, colourFilters, raw, rawPixels,
                           threads, lensSpot, bundles));
      },
      py::arg("image"), py::arg("mask"), py::arg("display"), py::kw_only(), py::arg("eyes"),
      py::arg("size") = py::none(), py::arg("spp") = defaults.samplesPerPixel,
      py::arg("pupil") = defaults.pupilDiameterMm, py::arg("pupil_samples") = defaults.pupilSamples,
      py::arg("diffuser") = py::none(), py::arg("color_filters") = false, py::arg("raw") = false,
      py::arg("raw_pixels") = false, py::arg("threads") = 0, py::arg("lens_spot") = py::none(),
      py::arg("bundles") = "");
  module.def("_sweep_eyes", &sweepEyes, py::arg("display"), py::kw_only(), py::arg("count"),
             py::arg("sweep_range") = 1.0, py::arg("distance") = 0.0);
  module.def(
      "_quality",
      [options](const Scene& scene, const DisplayDescription& display, const py::array& image,
                const std::optional<py::array>& mask,
                const std::vector<std::array<double, 3>>& eyes, int referenceSpp,
                const std::optional<std::array<int, 2>>& size, int spp, double pupil,
                int pupilSamples, const std::optional<double>& diffuser, bool colourFilters,
                bool raw, bool rawPixels, int threads, const std::string& fit,
                const std::string& focus, const std::string& budget,
                const std::optional<double>& lensSpot, const std::string& bundles) {
        return quality(scene, display, image, mask, eyes, referenceSpp,
                       options(size, spp, pupil, pupilSamples, diffuser, colourFilters, raw,
                               rawPixels, threads, lensSpot, bundles),
                       fit, focus, budget);
      },
      py::arg("scene"), py::arg("display"), py::arg("image"), py::arg("mask"), py::kw_only(),
      py::arg("eyes"), py::arg("reference_spp") = kDefaultReferenceSpp,
      py::arg("size") = py::none(), py::arg("spp") = defaults.samplesPerPixel,
      py::arg("pupil") = defaults.pupilDiameterMm, py::arg("pupil_samples") = defaults.pupilSamples,
      py::arg("diffuser") = py::none(), py::arg("color_filters") = false, py::arg("raw") = false,
      py::arg("raw_pixels") = false, py::arg("threads") = 0, py::arg("fit") = "",
      py::arg("focus") = "", py::arg("depth_budget") = "", py::arg("lens_spot") = py::none(),
      py::arg("bundles") = "");
}

}  // namespace parallax::python
