// Rendering: the display's layers (`render`), ordinary and ideal views (`view`, `view
// --display-eye`) and quilts (`render --quilt`), with the CLI's checks and defaults. The GIL is
// released while the accelerator is built and the rays are traced.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <tuple>

#include "parallax/accel/accelerator.h"
#include "parallax/app/cli_support.h"
#include "parallax/camera/display_camera.h"
#include "parallax/camera/framing.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/display/lenticular.h"
#include "parallax/io/display_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/io/lenticular_file.h"
#include "parallax/jobs/layer_output.h"
#include "parallax/python/bindings_internal.h"
#include "parallax/render/display_render.h"
#include "parallax/render/quilt.h"
#include "parallax/render/render.h"

namespace parallax::python {

namespace {

// The sampling keywords every render takes, checked as the CLI checks --spp, --jitter, ...
struct Sampling {
  int spp;
  uint64_t seed;
  int threads;
  std::string jitter;
  int bounces;
  bool adaptive;
  app::SamplingOptions options() const {
    app::SamplingOptions o;
    o.spp = spp, o.seed = seed, o.threads = threads, o.jitter = jitter, o.bounces = bounces;
    o.adaptive = adaptive;
    return o;
  }
};

app::FramingOptions framingOptions(const std::string& fit, const std::string& focus,
                                   const std::string& depthBudget) {
  app::FramingOptions o;
  o.fit = fit, o.focus = focus, o.depthBudget = depthBudget;
  DisplayPlacement probe;  // refuses bad values before any work, as render does
  o.apply(probe);
  return o;
}

// The scene framed for the design as `render` frames it; `design` becomes the framing's (g').
Framing frameForRender(Scene& scene, DisplayDesign& design, const app::FramingOptions& framing) {
  framing.apply(scene.display);
  const Framing result = frameForDisplay(scene, design);
  scene.display = result.placement;
  design = result.design;
  return result;
}

void setSampling(JsonWriter& record, const Sampling& s, const RenderSettings& settings,
                 const RenderStats& stats) {
  record.set("/spp", settings.samplesPerPixel);
  record.set("/bounces", settings.bounces);
  record.set("/seed", s.seed);
  record.set("/jitter", s.jitter);
  record.set("/threads", s.threads);
  record.set("/adaptive", settings.adaptive);
  record.set("/seconds", stats.seconds);
  record.set("/rays", stats.totalRays());
  record.set("/rays_per_second", double(stats.totalRays()) / stats.seconds);
}

// `render --display lkg:NAME|visual.json` (`lenticular render`): the panel's one picture, each
// subpixel's rays around its view; no mask (None).
std::tuple<py::array_t<float>, py::object, std::string> renderLenticular(
    const Scene& scene, const DisplayDescription& description, const Sampling& sampling,
    const RenderSettings& settings, const ViewFilter& filter, bool subpixels,
    const app::FramingOptions& framing) {
  if (subpixels)
    throw InputError("command line", "--subpixels",
                     "applies to barrier displays; a lenticular render always traces one ray per "
                     "subpixel");
  if (framing.given())
    throw InputError("command line", "--fit/--focus/--depth-budget",
                     "apply to barrier displays (their depth budget is the virtual gap)");
  const LenticularDesign design = designLenticular(description.lenticular);
  const double w = design.calibration.screenW, h = design.calibration.screenH;
  app::checkMemoryEstimate(
      imageBytes(3 * w, h) + imageBytes(w, h) + imageBytes(w, h, kRgba8PixelBytes),
      description.source(), "the panel image", "use a smaller panel");
  sampling.options().checkWork(3 * w, h);
  DisplayLayers out;
  {
    py::gil_scoped_release released;
    const Accelerator accelerator(scene,
                                  acceleratorForCameraRays(3 * w * h * settings.samplesPerPixel));
    out = renderDisplay(scene, accelerator, *makeLenticularDisplay(design, filter), settings);
  }
  JsonWriter record;
  record.set("/method", "lenticular: rays per subpixel around its view");
  record.set("/display", description.source());
  record.set("/scene", scene.source);
  setSampling(record, sampling, settings, out.stats);
  record.set("/filter/kind", viewFilterName(filter.kind));
  record.set("/filter/width_views", filter.widthViews);
  record.set("/scene_display/center", scene.display.center);
  record.set("/scene_display/normal", scene.display.normal);
  record.set("/scene_display/up", scene.display.up);
  writeLenticularDesignJson(record, "/design", design);
  return {imageToArray(out.image), py::none(), record.dump()};
}

// `render` (slits): image and mask layers (linear) and the record as JSON text.
std::tuple<py::array_t<float>, py::object, std::string> renderLayers(
    const Scene& loaded, const DisplayDescription& description, const Sampling& sampling,
    const std::string& filterKind, double filterWidth, bool subpixels, const std::string& fit,
    const std::string& focus, const std::string& depthBudget) {
  RenderSettings settings = sampling.options().settings();
  app::FilterOptions filterOptions;
  filterOptions.kind = filterKind, filterOptions.widthViews = filterWidth;
  const ViewFilter filter = filterOptions.filter();
  if (filter.kind == ViewFilterKind::None) settings.samplesPerPixel = 1;  // one central ray
  const app::FramingOptions framing = framingOptions(fit, focus, depthBudget);
  if (description.kind == DisplayKind::Lenticular)
    return renderLenticular(loaded, description, sampling, settings, filter, subpixels, framing);
  DisplayDesign design = designDisplay(description.barrier);
  if (subpixels) {
    DisplaySpec spec = design.spec;
    spec.subpixelRays = true;
    design = designDisplay(spec);
  }
  app::checkLayerWork(design, false, settings.samplesPerPixel, settings.threads,
                      description.source());
  Scene scene = loaded;
  const Framing framed = frameForRender(scene, design, framing);
  const double filmColumns = design.spec.imagePanel.width * (design.spec.subpixelRays ? 3.0 : 1.0);
  const AcceleratorOptions acceleratorOptions = acceleratorForCameraRays(
      filmColumns * design.spec.imagePanel.height * settings.samplesPerPixel);
  DisplayLayers layers;
  {
    py::gil_scoped_release released;
    const Accelerator accelerator(scene, acceleratorOptions);
    layers = renderDisplay(scene, accelerator, design, settings, {}, filter);
  }
  JsonWriter record;
  record.set("/method", "barrier-camera");
  record.set("/display", description.source());
  record.set("/layers/method", "slits");
  record.set("/scene", scene.source);
  setSampling(record, sampling, settings, layers.stats);
  record.set("/filter/kind", viewFilterName(filter.kind));
  record.set("/filter/width_views", filter.widthViews);
  record.set("/scene_display/center", scene.display.center);
  record.set("/scene_display/normal", scene.display.normal);
  record.set("/scene_display/up", scene.display.up);
  app::recordFraming(record, framed);
  writeDesignJson(record, "/design", design);
  return {imageToArray(layers.image), py::object(imageToArray(layers.mask)), record.dump()};
}

// Renders `camera`'s picture after the CLI's memory, pixel and time checks.
py::array_t<float> renderPicture(const Scene& scene, const Camera& camera,
                                 const Sampling& sampling) {
  const app::SamplingOptions options = sampling.options();
  const RenderSettings settings = options.settings();
  const std::string size = std::to_string(camera.width()) + "x" + std::to_string(camera.height());
  app::checkMemoryEstimate(imageBytes(camera.width(), camera.height()) +
                               imageBytes(camera.width(), camera.height(), kRgba8PixelBytes),
                           "size " + size, "the film", "use a smaller size");
  app::checkPixelCount(double(camera.width()) * camera.height(), "size " + size);
  options.checkWork(camera.width(), camera.height());
  const AcceleratorOptions acceleratorOptions =
      acceleratorForCameraRays(double(camera.width()) * camera.height() * sampling.spp);
  Image image;
  {
    py::gil_scoped_release released;
    const Accelerator accelerator(scene, acceleratorOptions);
    image = render(scene, accelerator, camera, settings);
  }
  return imageToArray(image);
}

void checkSize(const std::array<int, 2>& size) {
  if (size[0] < 1 || size[1] < 1)
    throw InputError("command line", "size", "expected (width, height), both positive");
}

// `view`: the pinhole picture, from the scene's camera (or its framing) unless given.
py::array_t<float> view(const Scene& scene, const std::optional<std::array<float, 3>>& eye,
                        const std::optional<std::array<float, 3>>& lookAt,
                        const std::optional<std::array<float, 3>>& up,
                        const std::optional<float>& fov, const std::array<int, 2>& size,
                        const Sampling& sampling) {
  checkSize(size);
  CameraSpec spec = scene.camera ? *scene.camera : frameScene(scene);
  const auto vec = [](const std::array<float, 3>& v) { return Vec3f{v[0], v[1], v[2]}; };
  if (eye) spec.eye = vec(*eye);
  if (lookAt) spec.lookAt = vec(*lookAt);
  if (up) spec.up = vec(*up);
  if (fov) {
    if (!(*fov > 0 && *fov < 180))
      throw InputError("command line", "--fov", "must be a number above 0 and below 180");
    spec.fovDegrees = *fov;
  }
  if (length(cross(spec.lookAt - spec.eye, spec.up)) == 0.0f)
    throw InputError("command line", "--up", "must not be parallel to the view direction");
  const PinholeCamera camera(spec.eye, spec.lookAt, spec.up, spec.fovDegrees, size[0], size[1]);
  return renderPicture(scene, camera, sampling);
}

// `view --display-eye`: the ideal picture through the display's window (the front layer's size
// unless given), the scene framed as `render` frames it.
py::array_t<float> idealView(const Scene& scene, const DisplayDescription& description,
                             const std::array<double, 3>& eyeMm,
                             const std::optional<std::array<int, 2>>& size,
                             const Sampling& sampling, const std::string& fit,
                             const std::string& focus, const std::string& depthBudget) {
  const app::FramingOptions framing = framingOptions(fit, focus, depthBudget);
  const Vec3d eye = eyeInFront(eyeMm, "eye");
  if (size) checkSize(*size);
  std::unique_ptr<Camera> camera;
  if (description.kind == DisplayKind::Lenticular) {
    if (framing.given())
      throw InputError("command line", "--fit/--focus/--depth-budget",
                       "apply to barrier displays (their depth budget is the virtual gap)");
    const std::unique_ptr<DisplayModel> display =
        makeLenticularDisplay(designLenticular(description.lenticular));
    const int width = size ? (*size)[0] : display->film().panelWidth;
    const int height = size ? (*size)[1] : display->film().panelHeight;
    camera = std::make_unique<WindowCamera>(eye, *display, scene.display, width, height);
  } else {
    const DisplayDesign design = designDisplay(description.barrier);
    const Panel& front = design.spec.order == LayerOrder::BarrierBack ? design.spec.imagePanel
                                                                      : design.spec.maskPanel;
    Scene placed;
    placed.display = scene.display;
    if (!placed.display.content) placed.display.content = scene.bounds();
    framing.apply(placed.display);
    const Framing framed = frameForDisplay(placed, design);
    camera = std::make_unique<WindowCamera>(eye, framed.design, framed.placement,
                                            size ? (*size)[0] : front.width,
                                            size ? (*size)[1] : front.height);
  }
  return renderPicture(scene, *camera, sampling);
}

// `render --quilt CxR|auto [--size WxH] --linear`: the quilt as linear floats, and its record.
std::tuple<py::array_t<float>, std::string> quilt(
    const Scene& loaded, const DisplayDescription& description,
    const std::optional<std::array<int, 2>>& layoutGiven,
    const std::optional<std::array<int, 2>>& size, const Sampling& sampling, const std::string& fit,
    const std::string& focus, const std::string& depthBudget) {
  const app::FramingOptions framing = framingOptions(fit, focus, depthBudget);
  RenderSettings settings = sampling.options().settings();
  QuiltLayout layout;
  layout.columns = layout.rows = 0;
  if (layoutGiven) {
    layout.columns = (*layoutGiven)[0], layout.rows = (*layoutGiven)[1];
    if (layout.columns < 1 || layout.rows < 1)
      throw InputError("command line", "--quilt", "expected COLUMNSxROWS, both positive");
  }
  Scene scene = loaded;
  std::unique_ptr<DisplayModel> display;
  std::optional<Framing> framed;
  if (description.kind == DisplayKind::Lenticular) {
    if (framing.given())
      throw InputError("command line", "--fit/--focus/--depth-budget",
                       "apply to barrier displays (their depth budget is the virtual gap)");
    display = makeLenticularDisplay(designLenticular(description.lenticular));
  } else {
    DisplayDesign design = designDisplay(description.barrier);
    framed = frameForRender(scene, design, framing);
    display = makeBarrierDisplay(design);
  }
  const LenticularDesign* lenticular = display->lenticularDesign();
  if (layout.columns == 0) {  // auto: the device's quilt, or one row of the barrier's views
    layout.columns = lenticular ? lenticular->calibration.quilt.columns : display->viewCount();
    layout.rows = lenticular ? lenticular->calibration.quilt.rows : 1;
  }
  int width = display->film().panelWidth, height = display->film().panelHeight;
  if (lenticular) {
    width = lenticular->calibration.quilt.width / layout.columns;
    height = lenticular->calibration.quilt.height / layout.rows;
  }
  if (size) checkSize(*size), width = (*size)[0], height = (*size)[1];
  if (width < 1 || height < 1)
    throw InputError("command line", "--quilt", "the device's quilt is too small for its tiles");
  const std::string sizeText = std::to_string(width) + "x" + std::to_string(height);
  app::checkQuiltWork(layout.columns, layout.rows, width, height, settings.samplesPerPixel,
                      settings.threads, size ? sizeText : "", true);
  layout.aspect = double(width) / height;
  RenderStats stats;
  Image result;
  {
    py::gil_scoped_release released;
    const Accelerator accelerator(
        scene, acceleratorForCameraRays(double(layout.columns) * layout.rows * width * height *
                                        settings.samplesPerPixel));
    result = renderQuilt(scene, accelerator, *display, settings, layout, width, height, &stats);
  }
  JsonWriter record;
  record.set("/method", "quilt");
  record.set("/display", description.source());
  record.set("/display_kind", displayKindName(display->kind()));
  record.set("/scene", scene.source);
  setSampling(record, sampling, settings, stats);
  record.set("/quilt/columns", layout.columns);
  record.set("/quilt/rows", layout.rows);
  record.set("/quilt/view_size", sizeText);
  record.set("/quilt/file_name", quiltFileName("quilt", layout, ".png"));
  for (int k = 0; k < layout.views(); ++k) {
    const Vec3d eye = quiltEyePosition(*display, k, layout.views());
    record.set("/quilt/eyes_mm/" + std::to_string(k),
               Vec3f(float(eye.x), float(eye.y), float(eye.z)));
  }
  if (framed) app::recordFraming(record, *framed);
  if (const DisplayDesign* barrier = display->barrierDesign())
    writeDesignJson(record, "/design", *barrier);
  if (lenticular) writeLenticularDesignJson(record, "/design", *lenticular);
  return {imageToArray(result), record.dump()};
}

}  // namespace

void bindRender(py::module_& module) {
  const app::SamplingOptions samplingDefaults;
  const app::FilterOptions filterDefaults;
  // The sampling keywords, in one order for every render function.
  const auto sampling = [](int spp, uint64_t seed, int threads, const std::string& jitter,
                           int bounces, bool adaptive) {
    return Sampling{spp, seed, threads, jitter, bounces, adaptive};
  };
  module.def(
      "_render",
      [sampling](const Scene& scene, const DisplayDescription& display, int spp, uint64_t seed,
                 int threads, const std::string& jitter, int bounces, bool adaptive,
                 const std::string& filter, double filterWidth, bool subpixels,
                 const std::string& fit, const std::string& focus, const std::string& budget) {
        return renderLayers(scene, display, sampling(spp, seed, threads, jitter, bounces, adaptive),
                            filter, filterWidth, subpixels, fit, focus, budget);
      },
      py::arg("scene"), py::arg("display"), py::kw_only(), py::arg("spp") = samplingDefaults.spp,
      py::arg("seed") = samplingDefaults.seed, py::arg("threads") = samplingDefaults.threads,
      py::arg("jitter") = samplingDefaults.jitter, py::arg("bounces") = samplingDefaults.bounces,
      py::arg("adaptive") = samplingDefaults.adaptive, py::arg("filter") = filterDefaults.kind,
      py::arg("filter_width") = filterDefaults.widthViews, py::arg("subpixels") = false,
      py::arg("fit") = "", py::arg("focus") = "", py::arg("depth_budget") = "");
  module.def(
      "_view",
      [sampling](const Scene& scene, const std::optional<std::array<float, 3>>& eye,
                 const std::optional<std::array<float, 3>>& lookAt,
                 const std::optional<std::array<float, 3>>& up, const std::optional<float>& fov,
                 const std::array<int, 2>& size, int spp, uint64_t seed, int threads,
                 const std::string& jitter, int bounces, bool adaptive) {
        return view(scene, eye, lookAt, up, fov, size,
                    sampling(spp, seed, threads, jitter, bounces, adaptive));
      },
      py::arg("scene"), py::kw_only(), py::arg("eye") = py::none(), py::arg("look_at") = py::none(),
      py::arg("up") = py::none(), py::arg("fov") = py::none(),
      py::arg("size") = std::array<int, 2>{960, 540}, py::arg("spp") = samplingDefaults.spp,
      py::arg("seed") = samplingDefaults.seed, py::arg("threads") = samplingDefaults.threads,
      py::arg("jitter") = samplingDefaults.jitter, py::arg("bounces") = samplingDefaults.bounces,
      py::arg("adaptive") = samplingDefaults.adaptive);
  module.def(
      "_ideal_view",
      [sampling](const Scene& scene, const DisplayDescription& display,
                 const std::array<double, 3>& eye, const std::optional<std::array<int, 2>>& size,
                 int spp, uint64_t seed, int threads, const std::string& jitter, int bounces,
                 bool adaptive, const std::string& fit, const std::string& focus,
                 const std::string& budget) {
        return idealView(scene, display, eye, size,
                         sampling(spp, seed, threads, jitter, bounces, adaptive), fit, focus,
                         budget);
      },
      py::arg("scene"), py::arg("display"), py::kw_only(), py::arg("eye"),
      py::arg("size") = py::none(), py::arg("spp") = samplingDefaults.spp,
      py::arg("seed") = samplingDefaults.seed, py::arg("threads") = samplingDefaults.threads,
      py::arg("jitter") = samplingDefaults.jitter, py::arg("bounces") = samplingDefaults.bounces,
      py::arg("adaptive") = samplingDefaults.adaptive, py::arg("fit") = "", py::arg("focus") = "",
      py::arg("depth_budget") = "");
  module.def(
      "_quilt",
      [sampling](const Scene& scene, const DisplayDescription& display,
                 const std::optional<std::array<int, 2>>& layout,
                 const std::optional<std::array<int, 2>>& size, int spp, uint64_t seed, int threads,
                 const std::string& jitter, int bounces, bool adaptive, const std::string& fit,
                 const std::string& focus, const std::string& budget) {
        return quilt(scene, display, layout, size,
                     sampling(spp, seed, threads, jitter, bounces, adaptive), fit, focus, budget);
      },
      py::arg("scene"), py::arg("display"), py::kw_only(), py::arg("layout") = py::none(),
      py::arg("size") = py::none(), py::arg("spp") = samplingDefaults.spp,
      py::arg("seed") = samplingDefaults.seed, py::arg("threads") = samplingDefaults.threads,
      py::arg("jitter") = samplingDefaults.jitter, py::arg("bounces") = samplingDefaults.bounces,
      py::arg("adaptive") = samplingDefaults.adaptive, py::arg("fit") = "", py::arg("focus") = "",
      py::arg("depth_budget") = "");
}

}  // namespace parallax::python
