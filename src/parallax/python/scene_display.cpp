// Scenes and displays: loading them as the CLI does, and a display's derived design as
// `parallax design --json` prints it.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <string>

#include "parallax/io/display_file.h"
#include "parallax/jobs/design_job.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/scene_request.h"
#include "parallax/python/bindings_internal.h"

namespace parallax::python {

namespace {

// `design --json [--depth MM] [--scene S --fit ...]`: the same figures, as JSON text.
std::string designJson(const DisplayDescription& description, double depthMm,
                       const std::optional<Scene>& scene, const std::string& fit,
                       const std::string& focus, const std::string& depthBudget) {
  jobs::DesignRequest request;
  request.display.loaded = description;
  request.depth = depthMm;
  if (scene) request.scene = jobs::SceneRequest{};
  request.framing.fit = fit, request.framing.focus = focus,
  request.framing.depthBudget = depthBudget;
  return jobs::designReport(request, pythonReporter(), scene ? &*scene : nullptr).json;
}

}  // namespace

void bindSceneAndDisplay(py::module_& module) {
  py::class_<Scene>(module, "Scene", "A loaded scene (parallax.load_scene)")
      .def_property_readonly("source", [](const Scene& s) { return s.source; })
      .def_property_readonly("bounds",
                             [](const Scene& s) {
                               const Bounds3f b = s.bounds();
                               return py::make_tuple(py::make_tuple(b.lo.x, b.lo.y, b.lo.z),
                                                     py::make_tuple(b.hi.x, b.hi.y, b.hi.z));
                             })
      .def("__repr__", [](const Scene& s) { return "<parallax.Scene " + s.source + ">"; });

  module.def(
      "load_scene",
      [](const std::optional<std::string>& path, const std::string& camera,
         const std::optional<double>& exposure, const std::optional<std::string>& viewTransform,
         const std::string& focusOn) {
        jobs::SceneRequest request;
        request.path = path.value_or("");
        request.load.camera = camera;
        request.load.focusOn = focusOn;
        request.load.exposureStops = exposure;
        request.load.viewTransform = viewTransform.value_or("");
        return jobs::loadScene(request, pythonReporter());
      },
      py::arg("path") = py::none(), py::kw_only(), py::arg("camera") = "",
      py::arg("exposure") = py::none(), py::arg("view_transform") = py::none(),
      py::arg("focus_on") = "",
      "The scene or mesh file (None: the built-in scene), as `parallax render SCENE` loads it; "
      "camera by name, node name or index as --camera; focus_on an object's name as --focus-on; "
      "exposure (stops) and view_transform ('standard' or 'filmic') as --exposure and "
      "--view-transform, over the file's own look (docs/look.md)");

  py::class_<DisplayDescription>(module, "Display",
                                 "A display of either kind (parallax.load_display)")
      .def_property_readonly("source", [](const DisplayDescription& d) { return d.source(); })
      .def_property_readonly("kind",
                             [](const DisplayDescription& d) { return displayKindName(d.kind); })
      .def("__repr__", [](const DisplayDescription& d) {
        return std::string("<parallax.Display ") + displayKindName(d.kind) + " " + d.source() + ">";
      });

  module.def(
      "load_display",
      [](const std::optional<std::string>& pathOrName) {
        DisplayDescription description =
            jobs::loadDisplay(pathOrName.value_or(""), pythonReporter());
        // Checked now, as every command checks it (G1-G4), not at the first render.
        jobs::makeDisplay(description);
        return description;
      },
      py::arg("path_or_name") = py::none(),
      "A barrier display file, a Looking Glass visual.json or lkg:NAME (None: the built-in "
      "display)");

  module.def(
      "_design_json",
      [](const DisplayDescription& display, double depth, const std::optional<Scene>& scene,
         const std::string& fit, const std::string& focus, const std::string& depthBudget) {
        return designJson(display, depth, scene, fit, focus, depthBudget);
      },
      py::arg("display"), py::kw_only(), py::arg("depth"), py::arg("scene"), py::arg("fit"),
      py::arg("focus"), py::arg("depth_budget"));
}

}  // namespace parallax::python
