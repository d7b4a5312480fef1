#include "python/errors.h"

#include <array>

#include "python/bindings.h"

namespace py = pybind11;

namespace imagepro::python {

namespace {

constexpr std::size_t kStatusCount = static_cast<std::size_t>(Status::Stopped) + 1;

// The classes live as long as the interpreter: the module holds them, and these
// references are never released.
PyObject* g_base = nullptr;
std::array<PyObject*, kStatusCount> g_classes{};

}  // namespace

StatusError::StatusError(Status status, const std::string& detail)
    : std::runtime_error(detail.empty() ? std::string(statusMessage(status)) : detail), status_(status) {}

void bindErrors(py::module_& m) {
  g_base = PyErr_NewExceptionWithDoc("imagepro.Error",
                                     "Base of imagepro's exceptions; each subclass is named after one status.",
                                     PyExc_Exception, nullptr);
  if (!g_base) throw py::error_already_set();
  py::setattr(g_base, "status", py::none());
  m.add_object("Error", py::reinterpret_borrow<py::object>(g_base));
  for (std::size_t i = 0; i < kStatusCount; ++i) {
    const auto status = static_cast<Status>(i);
    if (ok(status)) continue;
    const std::string name(statusName(status));
    const std::string qualified = "imagepro." + name;
    const std::string doc(statusMessage(status));
    PyObject* cls = PyErr_NewExceptionWithDoc(qualified.c_str(), doc.c_str(), g_base, nullptr);
    if (!cls) throw py::error_already_set();
    py::setattr(cls, "status", py::str(name));
    g_classes[i] = cls;
    m.add_object(name.c_str(), py::reinterpret_borrow<py::object>(cls));
  }
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const StatusError& e) {
      PyObject* cls = g_classes[static_cast<std::size_t>(e.status())];
      PyErr_SetString(cls ? cls : g_base, e.what());
    }
  });
}

}  // namespace imagepro::python
