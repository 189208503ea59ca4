// Rendering: the display's pictures (`render`, quilts, sequences to files) and ordinary and
// ideal views (`view`, `view --display-eye`), each a RenderRequest or ViewRequest run by the
// request layer (jobs/render_job.h, jobs/view_job.h) as the command line runs it. Keywords are
// the requests' field names. The GIL is released while the runners work.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/jobs/render_job.h"
#include "parallax/jobs/view_job.h"
#include "parallax/python/bindings_internal.h"

namespace parallax::python {

namespace {

// The keywords every render takes, in one order.
jobs::SamplingRequest sampling(const py::kwargs& kw) {
  jobs::SamplingRequest s;
  if (kw.contains("spp")) s.spp = kw["spp"].cast<int>();
  if (kw.contains("seed")) {
    // pybind11's own cast error would be a RuntimeError without the keyword's name.
    const py::object seed = kw["seed"];
    if (!py::isinstance<py::int_>(seed) || seed.cast<py::int_>() < py::int_(0) ||
        seed.cast<py::int_>() > py::int_(std::numeric_limits<uint64_t>::max()))
      throw RequestError("seed", "must be a whole number from 0 to 2^64 - 1");
    s.seed = seed.cast<uint64_t>();
  }
  if (kw.contains("threads")) s.threads = kw["threads"].cast<int>();
  if (kw.contains("jitter")) s.jitter = kw["jitter"].cast<std::string>();
  if (kw.contains("bounces")) s.bounces = kw["bounces"].cast<int>();
  if (kw.contains("adaptive")) s.adaptive = kw["adaptive"].cast<bool>();
  if (kw.contains("adaptive_threshold") && !kw["adaptive_threshold"].is_none()) {
    // As the command line's --adaptive-threshold needs --adaptive: refused, not ignored.
    if (!s.adaptive) throw RequestError("adaptive_threshold", "applies with adaptive=True");
    s.adaptiveThreshold = kw["adaptive_threshold"].cast<double>();
  }
  return s;
}

// The Python keywords of a RenderRequest (python/parallax/__init__.py passes them by name).
jobs::RenderRequest renderRequest(const DisplayDescription& display, const py::kwargs& kw) {
  jobs::RenderRequest r;
  r.display = jobs::DisplayRequest::of(display);
  r.sampling = sampling(kw);
  const auto text = [&](const char* key, std::string& to) {
    if (kw.contains(key) && !kw[key].is_none()) to = py::str(kw[key]).cast<std::string>();
  };
  text("filter", r.filter.kind);
  if (kw.contains("filter_width") && !kw["filter_width"].is_none())
    r.filter.widthViews = kw["filter_width"].cast<double>();
  text("fit", r.framing.fit);
  text("focus", r.framing.focus);
  text("depth_budget", r.framing.depthBudget);
  if (kw.contains("subpixels")) r.display.subpixels = kw["subpixels"].cast<bool>();
  if (kw.contains("direct_mapping")) r.directMapping = kw["direct_mapping"].cast<bool>();
  if (kw.contains("linear")) r.linear = kw["linear"].cast<bool>();
  if (kw.contains("distance")) r.display.distance = kw["distance"].cast<double>();
  if (kw.contains("lens_spot") && !kw["lens_spot"].is_none())
    r.display.lens.spot = kw["lens_spot"].cast<double>();
  text("bundles", r.display.lens.bundles);
  text("layers", r.layers.method);
  if (kw.contains("rank")) r.layers.rank = kw["rank"].cast<int>();
  if (kw.contains("iterations") && !kw["iterations"].is_none())
    r.layers.iterations = kw["iterations"].cast<int>();
  if (kw.contains("brightness")) r.layers.brightness = kw["brightness"].cast<double>();
  if (kw.contains("train_eyes")) r.layers.trainEyes = kw["train_eyes"].cast<int>();
  if (kw.contains("train_spp") && !kw["train_spp"].is_none())
    r.layers.trainSpp = kw["train_spp"].cast<int>();
  text("train_distances", r.layers.trainDistances);
  if (kw.contains("diffuser")) r.layers.diffuser = kw["diffuser"].cast<double>();
  if (kw.contains("color_filters")) r.layers.colorFilters = kw["color_filters"].cast<bool>();
  if (kw.contains("pupil")) r.layers.pupil = kw["pupil"].cast<double>();
  if (kw.contains("pupil_samples")) r.layers.pupilSamples = kw["pupil_samples"].cast<int>();
  text("layer_error", r.layers.error);
  if (kw.contains("quilt") && !kw["quilt"].is_none()) {
    r.quilt.wanted = true;
    if (!py::isinstance<py::str>(kw["quilt"])) {  // (columns, rows); "auto": the display's
      const auto layout = kw["quilt"].cast<std::array<int, 2>>();
      if (layout[0] < 1 || layout[1] < 1)
        throw RequestError("quilt", "expected (columns, rows), both positive");
      r.quilt.columns = layout[0], r.quilt.rows = layout[1];
    }
  }
  if (kw.contains("size") && !kw["size"].is_none()) {
    const auto size = kw["size"].cast<std::array<int, 2>>();
    if (size[0] < 1 || size[1] < 1)
      throw RequestError("size", "expected (width, height), both positive");
    r.quilt.width = size[0], r.quilt.height = size[1];
  }
  // A sequence (rendered to files): frames, chunk, turntable, duration, fps, video.
  text("frames", r.sequence.frames);
  text("chunk", r.sequence.chunk);
  if (kw.contains("turntable")) r.sequence.turntable = kw["turntable"].cast<double>();
  if (kw.contains("duration")) r.sequence.duration = kw["duration"].cast<double>();
  if (kw.contains("fps")) r.sequence.fps = kw["fps"].cast<double>();
  text("video", r.sequence.video.file);
  text("video_codec", r.sequence.video.codec);
  if (kw.contains("video_quality")) r.sequence.video.quality = kw["video_quality"].cast<int>();
  return r;
}

std::vector<std::string> knownRenderKeywords() {
  return {"spp",
          "seed",
          "threads",
          "jitter",
          "bounces",
          "adaptive",
          "adaptive_threshold",
          "filter",
          "filter_width",
          "fit",
          "focus",
          "depth_budget",
          "subpixels",
          "direct_mapping",
          "linear",
          "distance",
          "lens_spot",
          "bundles",
          "layers",
          "rank",
          "iterations",
          "brightness",
          "train_eyes",
          "train_distances",
          "train_spp",
          "diffuser",
          "color_filters",
          "pupil",
          "pupil_samples",
          "layer_error",
          "quilt",
          "size",
          "frames",
          "chunk",
          "turntable",
          "duration",
          "fps",
          "video",
          "video_codec",
          "video_quality"};
}

// Unknown keywords are errors (TypeError), as for any Python function.
void checkKeywords(const py::kwargs& kw, const std::vector<std::string>& known) {
  for (const auto& item : kw) {
    const std::string key = py::str(item.first).cast<std::string>();
    if (std::find(known.begin(), known.end(), key) == known.end())
      throw py::type_error("unexpected keyword argument '" + key + "'");
  }
}

// `render` / `render --quilt` in memory: the frames (image, mask or None) and the record.
std::tuple<std::vector<std::tuple<py::array_t<float>, py::object>>, py::object, std::string>
renderInMemory(const Scene& scene, const DisplayDescription& display, const py::kwargs& kw) {
  checkKeywords(kw, knownRenderKeywords());
  const jobs::RenderRequest request = renderRequest(display, kw);
  jobs::RenderResult result;
  {
    py::gil_scoped_release released;
    // Notes and warnings on stderr with keywords (what --filter none does with spp, framing).
    result = jobs::renderInMemory(request, scene, pythonReporter());
  }
  std::vector<std::tuple<py::array_t<float>, py::object>> frames;
  for (const LayerFrame& frame : result.frames)
    frames.emplace_back(imageToArray(frame.image),
                        frame.mask.empty() ? py::none() : py::object(imageToArray(frame.mask)));
  py::object quilt = result.quilt.empty() ? py::none() : py::object(imageToArray(result.quilt));
  return {std::move(frames), std::move(quilt), result.record};
}

// `parallax render` to files: the same files (and sequences, videos) as the command line.
void renderToFiles(const std::string& output, const std::optional<std::string>& scenePath,
                   const std::optional<std::string>& displayPath, const std::string& camera,
                   const std::optional<double>& exposure,
                   const std::optional<std::string>& viewTransform, const std::string& focusOn,
                   const py::kwargs& kw) {
  checkKeywords(kw, knownRenderKeywords());
  jobs::RenderRequest request = renderRequest(DisplayDescription{}, kw);
  request.display.loaded.reset();
  request.display.path = displayPath.value_or("");
  request.scene.path = scenePath.value_or("");
  request.scene.load.camera = camera;
  request.scene.load.focusOn = focusOn;
  request.scene.load.exposureStops = exposure;
  request.scene.load.viewTransform = viewTransform.value_or("");
  request.output = output;
  py::gil_scoped_release released;
  jobs::runRender(request, pythonReporter());
}

std::optional<Vec3f> vec3(const std::optional<std::array<float, 3>>& v) {
  if (!v) return std::nullopt;
  return Vec3f{(*v)[0], (*v)[1], (*v)[2]};
}

// `view` and `view --display-eye` in memory.
py::array_t<float> view(const Scene& scene, const std::optional<DisplayDescription>& display,
                        const std::optional<std::array<double, 3>>& displayEye,
                        const std::optional<std::array<float, 3>>& eye,
                        const std::optional<std::array<float, 3>>& lookAt,
                        const std::optional<std::array<float, 3>>& up,
                        const std::optional<float>& fov,
                        const std::optional<std::array<int, 2>>& size, const py::kwargs& kw) {
  checkKeywords(kw, {"spp", "seed", "threads", "jitter", "bounces", "adaptive",
                     "adaptive_threshold", "fit", "focus", "depth_budget"});
  jobs::ViewRequest r;
  r.sampling = sampling(kw);
  if (size) {
    if ((*size)[0] < 1 || (*size)[1] < 1)
      throw RequestError("size", "expected (width, height), both positive");
    r.width = (*size)[0], r.height = (*size)[1];
  }
  // Everything given goes into the request, which refuses a mix of the two cameras.
  if (displayEye) r.displayEye = Vec3d{(*displayEye)[0], (*displayEye)[1], (*displayEye)[2]};
  if (display) r.display.loaded = *display;
  const auto text = [&](const char* key, std::string& to) {
    if (kw.contains(key) && !kw[key].is_none()) to = py::str(kw[key]).cast<std::string>();
  };
  text("fit", r.framing.fit);
  text("focus", r.framing.focus);
  text("depth_budget", r.framing.depthBudget);
  r.eye = vec3(eye), r.lookAt = vec3(lookAt), r.up = vec3(up), r.fov = fov;
  Image image;
  {
    py::gil_scoped_release released;
    image = jobs::viewInMemory(r, scene, jobs::silentReporter());
  }
  return imageToArray(image);
}

}  // namespace

void bindRender(py::module_& module) {
  module.def("_render", &renderInMemory, py::arg("scene"), py::arg("display"));
  module.def("_render_files", &renderToFiles, py::arg("output"), py::arg("scene") = py::none(),
             py::arg("display") = py::none(), py::arg("camera") = "",
             py::arg("exposure") = py::none(), py::arg("view_transform") = py::none(),
             py::arg("focus_on") = "");
  module.def("_view", &view, py::arg("scene"), py::kw_only(), py::arg("display") = py::none(),
             py::arg("display_eye") = py::none(), py::arg("eye") = py::none(),
             py::arg("look_at") = py::none(), py::arg("up") = py::none(),
             py::arg("fov") = py::none(), py::arg("size") = py::none());
}

}  // namespace parallax::python
