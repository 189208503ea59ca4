// The display tools: interlacing views or a quilt onto a display (`interlace`), calibration
// patterns (`calibrate patterns`) and a lenticular panel seen through its lenses (`lenticular
// simulate`), each a request run by the request layer (jobs/interlace_job.h,
// jobs/calibrate_job.h) as the command line runs it, in memory or to the same files. Keywords
// are the requests' field names. The GIL is released while the runners work.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "parallax/jobs/calibrate_job.h"
#include "parallax/jobs/calibrate_photo_job.h"
#include "parallax/jobs/interlace_job.h"
#include "parallax/jobs/splat_making.h"
#include "parallax/python/bindings_internal.h"

namespace parallax::python {

namespace {

using Layout = std::optional<std::array<int, 2>>;

jobs::InterlaceRequest interlaceRequest(const Layout& quiltLayout, bool subpixels,
                                        const std::string& viewResampling,
                                        const std::optional<double>& lensSpot,
                                        const std::string& bundles) {
  jobs::InterlaceRequest r;
  if (quiltLayout) r.quiltLayout = QuiltLayout{(*quiltLayout)[0], (*quiltLayout)[1], 0.0};
  r.display.subpixels = subpixels;
  r.viewResampling = viewResampling;
  r.display.lens = {lensSpot, bundles};
  return r;
}

// `interlace` in memory: the image layer (a lenticular panel's picture), the mask (None for a
// panel) and the record.
std::tuple<py::array_t<float>, py::object, std::string> interlace(
    const std::optional<std::vector<py::array>>& views, const std::optional<py::array>& quilt,
    const DisplayDescription& display, const Layout& quiltLayout, bool subpixels,
    const std::string& viewResampling, const std::optional<double>& lensSpot,
    const std::string& bundles) {
  jobs::InterlaceRequest r =
      interlaceRequest(quiltLayout, subpixels, viewResampling, lensSpot, bundles);
  const jobs::DisplayRequest given = jobs::DisplayRequest::of(display);
  r.display.path = given.path, r.display.loaded = given.loaded;
  std::vector<Image> images;
  for (size_t k = 0; views && k < views->size(); ++k)
    images.push_back(arrayToImage((*views)[k], "views[" + std::to_string(k) + "]"));
  const Image quiltImage = quilt ? arrayToImage(*quilt, "quilt") : Image();
  jobs::InterlaceResult result;
  {
    py::gil_scoped_release released;
    result = jobs::interlaceInMemory(r, images, quiltImage, jobs::silentReporter());
  }
  py::object mask = result.mask.empty() ? py::none() : py::object(imageToArray(result.mask));
  return {imageToArray(result.image), std::move(mask), result.record};
}

// `parallax interlace` to files.
void interlaceFiles(const std::string& output, const std::vector<std::string>& views,
                    const std::string& quilt, const std::string& display, const Layout& quiltLayout,
                    bool subpixels, const std::string& viewResampling, bool linear,
                    const std::optional<double>& lensSpot, const std::string& bundles) {
  jobs::InterlaceRequest r =
      interlaceRequest(quiltLayout, subpixels, viewResampling, lensSpot, bundles);
  r.views = views, r.quilt = quilt, r.display.path = display, r.linear = linear;
  r.output = output;
  py::gil_scoped_release released;
  jobs::runInterlace(r, jobs::silentReporter());
}

PatternSettings patternSettings(const py::kwargs& kw) {
  PatternSettings s;
  const auto take = [&](const char* key, auto& to) {
    if (kw.contains(key)) to = kw[key].cast<std::decay_t<decltype(to)>>();
  };
  take("screen_period_px", s.screenPeriodPx);
  take("slit_period_px", s.slitPeriodPx);
  take("phase_px", s.phasePx);
  take("from_px", s.fromPx);
  take("to_px", s.toPx);
  take("period_steps", s.periodSteps);
  take("phase_step_px", s.phaseStepPx);
  take("duty", s.duty);
  take("label_scale", s.labelScale);
  for (const auto& item : kw) {
    const std::string key = py::str(item.first).cast<std::string>();
    if (key != "screen_period_px" && key != "slit_period_px" && key != "phase_px" &&
        key != "from_px" && key != "to_px" && key != "period_steps" && key != "phase_step_px" &&
        key != "duty" && key != "label_scale")
      throw py::type_error("unexpected keyword argument '" + key + "'");
  }
  return s;
}

// `calibrate patterns` in memory: (file name, picture) of each pattern, index.json, README.txt.
std::tuple<std::vector<std::pair<std::string, py::array_t<float>>>, std::string, std::string>
calibrationPatterns(const DisplayDescription& display, const py::kwargs& kw) {
  jobs::CalibrationPatternsRequest r;
  r.display.loaded = display;
  r.settings = patternSettings(kw);
  jobs::CalibrationPatternSet set;
  std::vector<Image> pictures;
  {
    py::gil_scoped_release released;
    set = jobs::calibrationPatterns(r, jobs::silentReporter(), true);
    for (size_t i = 0; i < set.patterns.size(); ++i) pictures.push_back(set.draw(i));
  }
  std::vector<std::pair<std::string, py::array_t<float>>> named;
  for (size_t i = 0; i < pictures.size(); ++i)
    named.emplace_back(set.patterns[i].file, imageToArray(pictures[i]));
  return {std::move(named), set.index, set.readme};
}

// `parallax calibrate patterns` to files.
void calibrationPatternsFiles(const std::string& output, const std::string& display,
                              const py::kwargs& kw) {
  jobs::CalibrationPatternsRequest r;
  r.display.path = display;
  r.output = output;
  r.settings = patternSettings(kw);
  py::gil_scoped_release released;
  jobs::runCalibrationPatterns(r, jobs::silentReporter());
}

// `parallax calibrate patterns --photo`: the shots' folder.
void calibrationPhotoPatterns(const std::string& output, const std::string& display) {
  jobs::CalibrationShotsRequest r;
  r.display.path = display;
  r.output = output;
  py::gil_scoped_release released;
  jobs::runCalibrationShots(r, jobs::silentReporter());
}

// `parallax calibrate photo`: the report (the --json object) and the measured display's text,
// written to `output` too when it is given.
std::pair<std::string, std::string> calibratePhoto(const std::string& shots,
                                                   const std::vector<std::string>& photos,
                                                   const std::string& output,
                                                   const std::string& display) {
  jobs::CalibratePhotoRequest r;
  r.shots = shots;
  r.photos = photos;
  r.output = output;
  r.display.path = display;
  r.json = true;
  py::gil_scoped_release released;
  jobs::RecordingReporter reporter;
  if (!output.empty()) {
    jobs::runCalibratePhoto(r, reporter);
    return {reporter.results.back(), ""};
  }
  const jobs::PhotoCalibration result = jobs::calibrateFromPhotos(r, reporter);
  return {result.json, result.measuredText};
}

// `parallax calibrate check --json`: what each seat sees.
std::string calibrationCheck(const std::string& shots, const std::vector<std::string>& photos,
                             const std::string& display) {
  jobs::CalibrationCheckRequest r;
  r.shots = shots;
  r.photos = photos;
  r.display.path = display;
  r.json = true;
  py::gil_scoped_release released;
  jobs::RecordingReporter reporter;
  return jobs::checkSeats(r, reporter).json;
}

// `lenticular simulate` in memory: the panel picture seen from the eye through the lenses.
py::array_t<float> lenticularSimulate(const py::array& image, const DisplayDescription& display,
                                      const std::optional<std::array<double, 3>>& eye,
                                      double distance, const std::optional<double>& lensSpot,
                                      const std::string& bundles) {
  jobs::LenticularSimulateRequest r;
  r.display.loaded = display;
  if (eye) r.eye = Vec3d{(*eye)[0], (*eye)[1], (*eye)[2]};
  r.display.distance = distance;
  r.display.lens = {lensSpot, bundles};
  const Image panel = arrayToImage(image, "image");
  Image view;
  {
    py::gil_scoped_release released;
    view = jobs::lenticularViewInMemory(r, panel, jobs::silentReporter());
  }
  return imageToArray(view);
}

}  // namespace

// `parallax splats from-mesh|capture-like`: the file written; its figures returned.
py::dict makeSplats(const std::string& output, const std::string& source,
                    const std::optional<std::string>& scene, size_t count, uint64_t seed) {
  jobs::SplatMakingRequest r;
  if (source == "mesh")
    r.source = jobs::SplatMakingRequest::Source::Surfaces;
  else if (source != "capture-like")
    throw RequestError("source", "expected \"mesh\" or \"capture-like\"", source);
  else if (scene)
    throw RequestError("scene", "is for source=\"mesh\"");
  r.scene.path = scene.value_or("");
  r.count = count;
  r.seed = seed;
  r.output = output;
  jobs::SplatMakingResult result;
  {
    py::gil_scoped_release released;
    result = jobs::runSplatMaking(r, jobs::silentReporter());
  }
  py::dict figures;
  figures["gaussians"] = result.gaussians;
  figures["sh_degree"] = result.shDegree;
  figures["file_bytes"] = result.fileBytes;
  return figures;
}

void bindTools(py::module_& module) {
  module.def("_make_splats", &makeSplats, py::arg("output"), py::arg("source"), py::arg("scene"),
             py::arg("count"), py::arg("seed"));
  module.def("_interlace", &interlace, py::arg("views"), py::arg("quilt"), py::arg("display"),
             py::kw_only(), py::arg("quilt_layout") = py::none(), py::arg("subpixels") = false,
             py::arg("view_resampling") = "linear", py::arg("lens_spot") = py::none(),
             py::arg("bundles") = "");
  module.def("_interlace_files", &interlaceFiles, py::arg("output"), py::arg("views"),
             py::arg("quilt"), py::arg("display"), py::kw_only(),
             py::arg("quilt_layout") = py::none(), py::arg("subpixels") = false,
             py::arg("view_resampling") = "linear", py::arg("linear") = false,
             py::arg("lens_spot") = py::none(), py::arg("bundles") = "");
  module.def("_calibration_patterns", &calibrationPatterns, py::arg("display"));
  module.def("_calibration_patterns_files", &calibrationPatternsFiles, py::arg("output"),
             py::arg("display"));
  module.def("_calibration_photo_patterns", &calibrationPhotoPatterns, py::arg("output"),
             py::arg("display"));
  module.def("_calibrate_photo", &calibratePhoto, py::arg("shots"), py::arg("photos"),
             py::arg("output"), py::arg("display"));
  module.def("_calibration_check", &calibrationCheck, py::arg("shots"), py::arg("photos"),
             py::arg("display"));
  module.def("_lenticular_simulate", &lenticularSimulate, py::arg("image"), py::arg("display"),
             py::kw_only(), py::arg("eye") = py::none(), py::arg("distance") = 0.0,
             py::arg("lens_spot") = py::none(), py::arg("bundles") = "");
}

}  // namespace parallax::python
