// The Python module imagepro (docs/python.md).
#include "core/common/version.h"
#include "python/bindings.h"

PYBIND11_MODULE(imagepro, m) {
  m.doc() = "ImagePro: find the circular target in images and reconstruct its pose (docs/python.md).";
  m.attr("__version__") = imagepro::kVersion;
  imagepro::python::bindErrors(m);
  imagepro::python::bindSettings(m);
  imagepro::python::bindPipeline(m);
}
