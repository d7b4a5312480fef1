#pragma once
// The parts of the module imagepro, each binding one area of the core.
#include <pybind11/pybind11.h>

namespace imagepro::python {

void bindErrors(pybind11::module_& m);    // errors.cpp: imagepro.Error and a class per status
void bindSettings(pybind11::module_& m);  // settings_binding.cpp: imagepro.Settings
void bindPipeline(pybind11::module_& m);  // pipeline_binding.cpp: Pose, detect, reconstruct, Engine, render

}  // namespace imagepro::python
