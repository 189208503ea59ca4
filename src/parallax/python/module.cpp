// The `parallax._parallax` extension: parallax.Error for bad input, the array conversions, and
// the areas' bindings (scene_display.cpp, render.cpp, simulate.cpp, tools.cpp). The package's
// __init__.py wraps it in the documented API (docs/python.md).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstring>
#include <string>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/terminal_reporter.h"
#include "parallax/python/bindings_internal.h"

namespace parallax::python {

namespace {

std::string keyword(const std::string& field) {
  // Fields Python spells otherwise than by their name.
  if (field == "framing") return "fit/focus/depth_budget";
  if (field == "sequence") return "frames/turntable";
  if (field == "sweep") return "count";  // sweep_eyes(count=, sweep_range=, distance=)
  if (field == "sweep_distance") return "distance";
  return field;
}

}  // namespace

jobs::Reporter& pythonReporter() {
  // Notes and warnings on stderr as the command line prints them; results are returned.
  static jobs::TerminalReporter reporter(keyword, false, false);
  return reporter;
}

std::string pythonErrorText(const InputError& e) {
  return errorText(e, keyword, [](const std::string& field, const std::string& value) {
    return keyword(field) + "=" + value;
  });
}

py::array_t<float> imageToArray(const Image& image) {
  py::array_t<float> array(
      {py::ssize_t(image.height()), py::ssize_t(image.width()), py::ssize_t(3)});
  if (!image.empty())
    std::memcpy(array.mutable_data(), image.pixels().data(), image.pixels().size() * sizeof(Vec3f));
  return array;
}

Image arrayToImage(const py::array& array, const std::string& name) {
  const auto shapeText = [&array] {
    std::string text = "(";
    for (py::ssize_t d = 0; d < array.ndim(); ++d)
      text += (d ? ", " : "") + std::to_string(array.shape(d));
    return text + (array.ndim() == 1 ? ",)" : ")");
  };
  const bool grey = array.ndim() == 2;
  if (!(grey || (array.ndim() == 3 && array.shape(2) == 3)) || array.size() == 0)
    throw py::value_error(name + ": expected an H x W x 3 (or H x W grey) array, got shape " +
                          shapeText());
  const py::dtype dtype = array.dtype();
  const bool codes = dtype.is(py::dtype::of<uint8_t>());
  if (!codes && !dtype.is(py::dtype::of<float>()) && !dtype.is(py::dtype::of<double>()))
    throw py::value_error(name + ": expected float32 (linear) or uint8 (sRGB) values, got " +
                          py::cast<std::string>(py::str(static_cast<const py::handle&>(dtype))));
  const int height = int(array.shape(0)), width = int(array.shape(1));
  Image image(width, height);
  constexpr auto style = py::array::c_style | py::array::forcecast;
  const auto fill = [&](const auto& typed, auto decode) {
    const auto* values = typed.data();
    const size_t channels = grey ? 1 : 3;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const size_t at = (size_t(y) * size_t(width) + size_t(x)) * channels;
        Vec3f& p = image.at(x, y);
        for (int c = 0; c < 3; ++c) p[c] = decode(values[at + (grey ? 0 : size_t(c))]);
      }
  };
  if (codes)
    fill(py::array_t<uint8_t, style>(array), [](uint8_t v) { return srgb8ToLinear(v); });
  else
    fill(py::array_t<float, style>(array), [](float v) { return v; });
  return image;
}

}  // namespace parallax::python

PYBIND11_MODULE(_parallax, module) {
  namespace py = pybind11;
  module.doc() = "parallax: ray tracing for glasses-free 3-D displays (docs/python.md)";
  // Bad input, with the CLI's one-line message ("FILE: /key: message", "--spp: message"). The
  // exception type lives as long as the process: a static py::object would be released after
  // the interpreter is gone.
  static const auto* const error =
      new py::exception<parallax::InputError>(module, "Error", PyExc_ValueError);
  // estimate_memory's stop: the estimate in bytes, then what it is for.
  static const auto* const estimated =
      new py::exception<parallax::jobs::EstimateOnly>(module, "_Estimated", PyExc_Exception);
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const parallax::jobs::EstimateOnly& e) {
      const py::tuple args = py::make_tuple(e.estimate().bytes, e.estimate().what);
      PyErr_SetObject(estimated->ptr(), args.ptr());
    } catch (const parallax::InputError& e) {
      // One line, naming a request's field by its keyword ("spp: ...", "spp=16: ...").
      const std::string prefix = "command line: ";
      std::string text = parallax::python::pythonErrorText(e);
      if (e.file() == "command line" && !e.path().empty() && text.rfind(prefix, 0) == 0)
        text = text.substr(prefix.size());
      for (size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at))
        text.replace(at, 1, "; ");
      PyErr_SetString(error->ptr(), text.c_str());
    }
  });
  // As `parallax --version`: this build and the Embree and assimp it runs on.
  module.attr("__version__") = PARALLAX_VERSION;
  module.def("version", &parallax::jobs::versionText);
  // The CLI's --max-memory GiB and --max-time SECONDS: what every later call is held to before
  // it allocates or starts (0: the default, 3/4 of physical memory and one day).
  module.def(
      "set_limits",
      [](double maxMemoryGiB, double maxSeconds) {
        if (!(maxMemoryGiB >= 0) || !(maxSeconds >= 0))
          throw parallax::RequestError(maxMemoryGiB >= 0 ? "max_time" : "max_memory",
                                       "must be 0 (the default) or above");
        parallax::jobs::limits().maxMemoryGiB = maxMemoryGiB;
        parallax::jobs::limits().maxSeconds = maxSeconds;
      },
      py::kw_only(), py::arg("max_memory") = 0.0, py::arg("max_time") = 0.0,
      "Limits for what every later call allocates (GiB) and takes (seconds); 0: the default");
  // estimate_memory: the next call stops at its whole estimate (the CLI's --estimate).
  module.def(
      "_set_estimate_only", [](bool on) { parallax::jobs::limits().estimateOnly = on; },
      py::arg("on"));
  module.def(
      "_to_srgb8",
      [](const py::array_t<float, py::array::c_style | py::array::forcecast>& linear) {
        py::array_t<uint8_t> codes(
            std::vector<py::ssize_t>(linear.shape(), linear.shape() + linear.ndim()));
        {
          py::gil_scoped_release released;
          parallax::linearToSrgb8(linear.data(), size_t(linear.size()), codes.mutable_data());
        }
        return codes;
      },
      py::arg("linear"));
  parallax::python::bindSceneAndDisplay(module);
  parallax::python::bindRender(module);
  parallax::python::bindSimulate(module);
  parallax::python::bindTools(module);
}
