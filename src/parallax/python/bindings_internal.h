// The pieces the binding files share: numpy arrays <-> Images, and the areas'
// registration functions (module.cpp calls them). Internal to the python module, so it may
// include pybind11 (the module's own third-party library).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

#include "parallax/core/error.h"
#include "parallax/image/image.h"
#include "parallax/jobs/reporter.h"

namespace parallax::python {

namespace py = pybind11;

// A linear RGB Image as an H x W x 3 float32 array (a copy: the array owns its memory).
py::array_t<float> imageToArray(const Image& image);

// An H x W x 3 (or H x W grey) array as a linear Image: float32/float64 values are linear,
// uint8 codes are sRGB and decoded as the PNG reader decodes them. Anything else raises
// ValueError naming `name` and what it got.
Image arrayToImage(const py::array& array, const std::string& name);

// Notes and warnings on stderr, as the command line prints them, fields named as keywords.
jobs::Reporter& pythonReporter();
// The one-line message of an InputError, fields named as keywords.
std::string pythonErrorText(const InputError& error);

void bindSceneAndDisplay(py::module_& module);
void bindRender(py::module_& module);
void bindSimulate(py::module_& module);
void bindTools(py::module_& module);  // tools.cpp: interlace, calibration, lenticular simulate

}  // namespace parallax::python
